//! How a run steps and what it writes: the increment controls (cutback, growth, the predictor,
//! the convergence test) and the output controls (which fields, how often, at what precision).

use crate::error::{Error, Result};

/// How the load steps are subdivided when Newton struggles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteppingControls {
    /// Factor applied to the increment after a failed attempt (0 < f < 1).
    pub cutback_factor: f64,
    /// Factor applied after an easy increment (>= 1); never past the requested increment.
    pub growth_factor: f64,
    /// An increment converged in at most this many Newton iterations is easy (4: CalculiX's
    /// I_G, for its field test, the default here too; 6 let a stiff contact's increment grow
    /// right after a cutback and fail again).
    pub easy_iterations: usize,
    /// Smallest increment, as a fraction of the step, before the run gives up.
    pub min_increment: f64,
    /// Newton iterations allowed per attempt (PETSc's -snes_max_it overrides it).
    pub max_newton_iterations: usize,
    /// Where Newton starts an increment.
    pub predictor: Predictor,
    /// How Newton's convergence is judged.
    pub convergence: Convergence,
}

/// Where Newton starts an increment. Without a predictor it starts from the last converged
/// state with only the prescribed nodes moved: on the bellows a 0.2 mm step of tube B's end then
/// strains the row of 8 mm elements next to it by 2.5 %, far past yield, and Newton wanders
/// between loading and unloading there.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Predictor {
    /// Abaqus's default (*STEP, EXTRAPOLATION=LINEAR): the last increment's displacement
    /// increment scaled to this one's size; the step's first increment (nothing to extrapolate)
    /// and every increment of a step after a failed attempt take the tangent predictor. No
    /// factorisation of its own: the bellows' default (13 % faster there), not the decks', as a
    /// growing stiff contact extrapolated throws the nodes about to touch deep into the other
    /// body (the stiff-penalty Hertz cases of tests/hertz_sphere_on_flat.rs: 4 to 6 cutbacks
    /// against 0 to 2).
    Extrapolate,
    /// The linear response to the prescribed DOFs' motion, with the tangent at the converged
    /// state (points on the yield surface flowing): one more factorisation per increment.
    #[default]
    Tangent,
    /// From the converged state with only the prescribed DOFs moved.
    None,
}

impl<'de> serde::Deserialize<'de> for Predictor {
    /// "extrapolate", "tangent" or "none"; true and false (older decks) mean "tangent" and "none".
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        #[serde(untagged)]
        enum Spec {
            Flag(bool),
            Name(String),
        }
        match Spec::deserialize(d)? {
            Spec::Flag(true) => Ok(Predictor::Tangent),
            Spec::Flag(false) => Ok(Predictor::None),
            Spec::Name(name) => match name.as_str() {
                "extrapolate" => Ok(Predictor::Extrapolate),
                "tangent" => Ok(Predictor::Tangent),
                "none" => Ok(Predictor::None),
                other => Err(serde::de::Error::custom(format!("predictor {other:?}: expected \"extrapolate\", \"tangent\" or \"none\""))),
            },
        }
    }
}

/// How a Newton solve is judged converged.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Convergence {
    /// CalculiX's and Abaqus's field test: the largest residual force within 0.5 % of the
    /// time-averaged force, the largest correction within 2 % of the increment's largest
    /// displacement (or the residual test below, whichever passes first).
    #[default]
    Field,
    /// ||F|| down by 1e-10 from its start, or to the round-off floor.
    Residual,
}

impl Default for SteppingControls {
    fn default() -> Self {
        SteppingControls {
            cutback_factor: 0.5,
            growth_factor: 1.5,
            easy_iterations: 4,
            min_increment: 1e-5,
            max_newton_iterations: 25,
            predictor: Predictor::default(),
            convergence: Convergence::default(),
        }
    }
}

/// What the results file keeps: the fields (displacement, stresses, contact state) of every
/// `every`-th increment and of the last increment of each step; the history has a row for
/// every converged increment whatever this says. The solver computes the same either way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputControls {
    pub every: usize,
    /// Which fields beside the displacement (always written) the results keep.
    pub fields: OutputFields,
    /// The floating-point width of the visualisation fields.
    pub precision: Precision,
}

/// The width of the visualisation fields' floats (the stresses, strains, their invariants and
/// the contact state, at the Gauss points and the nodes). The displacement (which a restart
/// reads), the restart state, the history and the mesh are always 64-bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// 64-bit floats: the values as computed (`full` says the same).
    #[serde(alias = "full")]
    Double,
    /// 32-bit floats (each value to 2^-24 of itself, 7 significant digits), as CalculiX's
    /// .frd and Abaqus's .odb store results: the default, for 40 % off the file and a sixth
    /// off its writing, the low bits being noise nobody reads (docs/performance.md).
    #[default]
    Single,
    /// Each field kept to a stated absolute resolution (HDF5's scale-offset filter, decimal
    /// scaling, which every HDF5 reader decodes): the finer of its unit's (1e-3 MPa, 1e-6 mm,
    /// 1e-8 for a strain, 1e-3 N) and 1e-6 of the field's largest value at the increment;
    /// written in each dataset's `resolution` attribute. A field with a value that is not
    /// finite is kept whole.
    Resolution,
}

/// The fields an increment's group holds beside the displacement: named in a deck's
/// `fields = [...]` by [`OutputFields::NAMES`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputFields {
    /// Gauss-point stresses and the stress components at the nodes.
    pub stress: bool,
    /// Von Mises stress at the Gauss points, its element mean, at the nodes.
    pub von_mises: bool,
    /// Equivalent plastic strain at the Gauss points, its element maximum, at the nodes.
    pub plastic_strain: bool,
    /// Total and plastic strain tensors at the nodes.
    pub strain: bool,
    pub temperature: bool,
    /// Contact gap, pressure, traction and status per pass and at the nodes.
    pub contact: bool,
    /// The stress at each element's nodes before averaging (not written by default).
    pub element_nodal: bool,
}

impl OutputFields {
    pub const NAMES: [&'static str; 7] = ["stress", "von_mises", "plastic_strain", "strain", "temperature", "contact", "element_nodal"];
    /// What a run writes unless its deck says otherwise: everything but the element-nodal
    /// stress (as large as the Gauss-point stress, and wanted only to see the jumps between
    /// elements).
    pub const DEFAULT: OutputFields =
        OutputFields { stress: true, von_mises: true, plastic_strain: true, strain: true, temperature: true, contact: true, element_nodal: false };

    /// The fields named in `names` (each one of [`Self::NAMES`]).
    pub fn from_names(names: &[String]) -> Result<Self> {
        let mut f =
            OutputFields { stress: false, von_mises: false, plastic_strain: false, strain: false, temperature: false, contact: false, element_nodal: false };
        for name in names {
            match name.as_str() {
                "stress" => f.stress = true,
                "von_mises" => f.von_mises = true,
                "plastic_strain" => f.plastic_strain = true,
                "strain" => f.strain = true,
                "temperature" => f.temperature = true,
                "contact" => f.contact = true,
                "element_nodal" => f.element_nodal = true,
                "displacement" => {}
                other => {
                    return Err(Error::input(format!(
                        "[output] fields: unknown field {other:?} (the fields are {}; the displacement is always written)",
                        Self::NAMES.join(", ")
                    )))
                }
            }
        }
        Ok(f)
    }
}

impl Default for OutputControls {
    fn default() -> Self {
        OutputControls { every: 1, fields: OutputFields::DEFAULT, precision: Precision::Double }
    }
}

impl OutputControls {
    /// Whether the fields of run-wide increment `number` are written (`last_of_step`: it ends
    /// its step).
    pub fn writes_fields(&self, number: usize, last_of_step: bool) -> bool {
        last_of_step || number.is_multiple_of(self.every)
    }
}
