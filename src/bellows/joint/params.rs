//! The bellows' parameters: the joint's geometry, mesh sizes, material, loads and stepping, with
//! the paper's DN300 case as defaults, read from TOML by field name and checked before a mesh
//! is made.

use crate::error::{Error, Result};

/// Parameters of the joint and of the analysis. Lengths in mm, stresses in MPa. Read from
/// TOML by field name (`BellowsParams::from_toml_file`), missing fields at their defaults.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct BellowsParams {
    pub tube_inner_radius: f64,
    pub tube_thickness: f64,
    pub length: f64,
    /// Axial length of tube A (tube B is as long, at the other end).
    pub tube_length: f64,
    pub convolutions: usize,
    pub pitch: f64,
    /// Convolution height w: radial extent of the ply-pack mid-surface (root bottom to crest
    /// top), 2 torus radii plus the sidewall.
    pub height: f64,
    /// Mid-surface radius of the root tori (and of the crest tori, unless `crest_radius`).
    pub torus_radius: f64,
    /// Mid-surface radius of the crest tori where it differs from the root's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crest_radius: Option<f64>,
    pub plies: usize,
    pub ply_thickness: f64,
    /// Length of each cylindrical tangent.
    pub tangent_length: f64,
    pub sleeve_thickness: f64,
    /// Sleeve overlap with tube A (bonded) and tube B (sliding), from the tube ends.
    pub sleeve_overlap: f64,
    /// The sleeve's entry is crowned: its outside falls by this much (mm) over its last
    /// `sleeve_crown_length`, a parabola tangent to the cylinder (0: a sharp end).
    pub sleeve_crown: f64,
    pub sleeve_crown_length: f64,
    // material
    pub youngs_modulus: f64,
    pub poissons_ratio: f64,
    pub thermal_expansion: f64,
    pub yield_stress: f64,
    pub hardening_modulus: f64,
    /// t/mm^3 (so that N, mm and s stay consistent): the natural frequencies' mass.
    pub density: f64,
    // loads
    pub temperature: f64,
    pub pressure: f64,
    /// Axial compression of tube B's end, mm (positive shortens the joint).
    pub displacement: f64,
    pub heat_increments: usize,
    pub increments: usize,
    /// Contact penalty, N/mm^3.
    pub penalty: f64,
    /// Coulomb friction coefficient between the plies (and of a ply's folds on each other).
    pub friction_plies: f64,
    /// Coulomb friction coefficient between the sleeve and tube B's bore.
    pub friction_sleeve: f64,
    /// Tangential penalty of the friction, MPa/mm of elastic slip.
    pub tangential_penalty: f64,
    /// Instead of the tangential penalty, the elastic slip (mm) at the Coulomb limit: eps_T =
    /// mu p / elastic_slip.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elastic_slip: Option<f64>,
    /// After the compression, a further step takes tube B's end back to where it started.
    pub cycle: bool,
    /// The code check's chart coefficients [Cp, Cf, Cd], read off the code's charts; without
    /// them they are computed from the idealised convolution.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coefficients: Option<[f64; 3]>,
    /// How Newton's convergence is judged.
    pub convergence: crate::model::Convergence,
    // mesh
    /// Elements through each ply's thickness.
    pub ply_elements: usize,
    /// Element length along the ply meridian, mm.
    pub ply_element_length: f64,
    /// Elements through the tube and sleeve walls.
    pub wall_elements: usize,
    /// Element length along tubes and sleeve, mm.
    pub wall_element_length: f64,
    // output
    /// Fields of every N-th increment in the results file (and of the last of each step).
    pub output_every: usize,
    /// The width of the visualisation fields' floats.
    pub output_precision: crate::model::Precision,
}

impl Default for BellowsParams {
    fn default() -> Self {
        BellowsParams {
            tube_inner_radius: 150.0,
            tube_thickness: 10.0,
            length: 400.0,
            tube_length: 128.0,
            convolutions: 6,
            pitch: 24.0,
            height: 20.0,
            torus_radius: 6.0,
            crest_radius: None,
            plies: 2,
            ply_thickness: 1.0,
            tangent_length: 20.0,
            sleeve_thickness: 10.0,
            sleeve_overlap: 40.0,
            // a sharp end presses into tube B's bore between two of its nodes, and the fit's
            // force then alternates with the end's place between them: with sleeve friction
            // the quick joint's end reaction zig-zagged by 0.26 % from increment to increment
            // (0.03 % crowned; docs/performance.md)
            sleeve_crown: 0.2,
            sleeve_crown_length: 8.0,
            youngs_modulus: 200_000.0,
            poissons_ratio: 0.3,
            thermal_expansion: 1.875e-5,
            yield_stress: 300.0,
            hardening_modulus: 1000.0,
            // AISI 304: 8.00 g/cm^3 (ASM Handbook)
            density: 8.0e-9,
            temperature: 200.0,
            pressure: 0.6,
            displacement: 70.0,
            heat_increments: 2,
            increments: 240,
            penalty: 1.0e4,
            friction_plies: 0.0,
            friction_sleeve: 0.0,
            // measured on the quick joint's cycle with mu = 0.2 between the plies (cutbacks,
            // against 4 frictionless): 1e4 (the normal penalty) fails at 98 % of the stroke,
            // 1000 takes 31, 300 takes 17, 100 takes 15. At 300 the elastic slip at the Coulomb
            // limit, mu p / eps_T, is 0.7 % of the quick mesh's 2 mm ply elements at p = 10 MPa,
            // about Abaqus' default allowance (0.5 % of the element length)
            tangential_penalty: 300.0,
            elastic_slip: None,
            coefficients: None,
            convergence: crate::model::Convergence::default(),
            cycle: false,
            ply_elements: 2,
            output_every: 1,
            output_precision: crate::model::Precision::Single,
            ply_element_length: 1.0,
            wall_elements: 3,
            wall_element_length: 4.0,
        }
    }
}

impl BellowsParams {
    /// Whether this is the seed paper's joint: its geometry and material, whatever the loads,
    /// mesh, stepping, contact, friction and output parameters (a shorter stroke, a penalty
    /// study or a quick mesh of the seed is still the seed, and its table keeps the paper's
    /// column, each row saying where it is read).
    pub fn is_seed_joint(&self) -> bool {
        let seed = BellowsParams {
            sleeve_crown: self.sleeve_crown,
            sleeve_crown_length: self.sleeve_crown_length,
            density: self.density,
            temperature: self.temperature,
            pressure: self.pressure,
            displacement: self.displacement,
            heat_increments: self.heat_increments,
            increments: self.increments,
            penalty: self.penalty,
            friction_plies: self.friction_plies,
            friction_sleeve: self.friction_sleeve,
            tangential_penalty: self.tangential_penalty,
            elastic_slip: self.elastic_slip,
            cycle: self.cycle,
            coefficients: self.coefficients,
            convergence: self.convergence,
            ply_elements: self.ply_elements,
            ply_element_length: self.ply_element_length,
            wall_elements: self.wall_elements,
            wall_element_length: self.wall_element_length,
            output_every: self.output_every,
            output_precision: self.output_precision,
            ..BellowsParams::default()
        };
        *self == seed
    }

    /// Total thickness of the ply pack.
    pub fn pack_thickness(&self) -> f64 {
        self.plies as f64 * self.ply_thickness
    }

    /// The parameters as a TOML parameter file (`slideline bellows --params FILE` runs the same
    /// model again), headed by a comment saying so: the deck text a results file keeps.
    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).unwrap_or_else(|e| format!("# (parameters not writable as TOML: {e})\n"));
        format!("# {}\n# slideline bellows --params THIS_FILE runs this model again\n{body}", self.title())
    }

    /// One line naming the joint (an exported deck's heading).
    pub fn title(&self) -> String {
        format!(
            "slideline bellows: {} plies x {} mm, {} convolutions, pitch {}, height {}; {} MPa at {} degC, {} mm compression in {} increments, penalty {} N/mm^3",
            self.plies, self.ply_thickness, self.convolutions, self.pitch, self.height, self.pressure, self.temperature, self.displacement, self.increments, self.penalty
        )
    }

    /// Parameters from a TOML file of `field = value` lines (unknown fields are an error).
    pub fn from_toml_file(path: &std::path::Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
        Self::from_toml(&text, &path.display().to_string())
    }

    /// Parameters from TOML text; `origin` names where it came from in an error.
    pub fn from_toml(text: &str, origin: &str) -> Result<Self> {
        toml::from_str(text).map_err(|e| Error::input(format!("{origin}: {}", e.message())))
    }

    /// The coarse version of the same case (`--quick`): one element through each ply, 2 mm
    /// along the meridian, 8 mm along the walls, at most 40 requested increments.
    pub fn quick(mut self) -> Self {
        self.ply_elements = 1;
        self.ply_element_length = 2.0;
        self.wall_element_length = 8.0;
        self.wall_elements = 2;
        self.increments = self.increments.min(40);
        self
    }

    /// Checks the parameters describe a joint that can be built; names the offending value.
    pub fn validate(&self) -> Result<()> {
        let positive = [
            ("tube inner radius", self.tube_inner_radius),
            ("tube thickness", self.tube_thickness),
            ("length", self.length),
            ("tube length", self.tube_length),
            ("pitch", self.pitch),
            ("convolution height", self.height),
            ("torus radius", self.torus_radius),
            ("crest radius", self.crest()),
            ("ply thickness", self.ply_thickness),
            ("tangent length", self.tangent_length),
            ("sleeve thickness", self.sleeve_thickness),
            ("ply element length", self.ply_element_length),
            ("wall element length", self.wall_element_length),
            ("penalty", self.penalty),
            ("tangential penalty", self.tangential_penalty),
            ("Young's modulus", self.youngs_modulus),
            ("yield stress", self.yield_stress),
            ("density", self.density),
        ];
        let coefficients = self.coefficients.into_iter().flat_map(|c| [("coefficient Cp", c[0]), ("coefficient Cf", c[1]), ("coefficient Cd", c[2])]);
        let positive = positive.into_iter().chain(self.elastic_slip.map(|g| ("elastic slip", g))).chain(coefficients);
        for (name, v) in positive {
            if !(v > 0.0 && v.is_finite()) {
                return Err(Error::input(format!("bellows: {name} must be > 0, got {}", crate::error::shown(v))));
            }
        }
        if let Some(rule) = self.coefficients.and_then(|c| off_the_charts(&c)) {
            return Err(Error::input(format!("bellows: {rule}")));
        }
        for (name, v) in [
            ("temperature", self.temperature),
            ("pressure", self.pressure),
            ("thermal expansion", self.thermal_expansion),
            ("hardening modulus", self.hardening_modulus),
            ("sleeve overlap", self.sleeve_overlap),
            ("sleeve crown", self.sleeve_crown),
        ] {
            if !v.is_finite() {
                return Err(Error::input(format!("bellows: {name} must be a finite number, got {v}")));
            }
        }
        for (name, mu) in [("friction between the plies", self.friction_plies), ("friction of the sleeve", self.friction_sleeve)] {
            if !(mu >= 0.0 && mu.is_finite()) {
                return Err(Error::input(format!("bellows: {name} must be a coefficient >= 0, got {mu}")));
            }
        }
        for (name, n) in [
            ("plies", self.plies),
            ("convolutions", self.convolutions),
            ("increments", self.increments),
            ("heat increments", self.heat_increments),
            ("ply elements", self.ply_elements),
            ("wall elements", self.wall_elements),
            ("output every", self.output_every),
        ] {
            if n == 0 {
                return Err(Error::input(format!("bellows: {name} must be at least 1")));
            }
        }
        self.validate_convolution()?;
        let convoluted = self.convolutions as f64 * self.pitch;
        let gap = self.length - 2.0 * self.tube_length;
        if (gap - convoluted).abs() > 1e-6 {
            return Err(Error::input(format!(
                "bellows: {} convolutions of pitch {} span {convoluted} mm, but the tubes leave {gap} mm between them (length {} - 2 x tube length {})",
                self.convolutions, self.pitch, self.length, self.tube_length
            )));
        }
        if self.sleeve_crown < 0.0 || self.sleeve_crown >= self.sleeve_thickness / 2.0 {
            return Err(Error::input(format!(
                "bellows: sleeve crown must be >= 0 and below half the sleeve thickness ({} mm), got {}",
                self.sleeve_thickness / 2.0,
                self.sleeve_crown
            )));
        }
        if !(self.sleeve_crown_length > 0.0 && self.sleeve_crown_length <= self.sleeve_overlap) {
            return Err(Error::input(format!(
                "bellows: sleeve crown length must be > 0 and within the sleeve's overlap with tube B ({} mm), got {}",
                self.sleeve_overlap, self.sleeve_crown_length
            )));
        }
        if self.tangent_length > self.tube_length || self.sleeve_overlap > self.tube_length {
            return Err(Error::input("bellows: the tangents and the sleeve overlap must fit on the tubes"));
        }
        if self.sleeve_thickness >= self.tube_inner_radius {
            return Err(Error::input("bellows: the sleeve is thicker than the tube bore"));
        }
        if !(self.poissons_ratio > -1.0 && self.poissons_ratio < 0.5) {
            return Err(Error::input(format!("bellows: Poisson's ratio must lie in (-1, 0.5), got {}", self.poissons_ratio)));
        }
        if self.displacement.is_nan() || self.displacement.abs() >= convoluted {
            return Err(Error::input(format!("bellows: a displacement of {} mm exceeds the convoluted length {convoluted} mm", self.displacement)));
        }
        if self.elastic_slip.is_some() && self.friction_plies == 0.0 && self.friction_sleeve == 0.0 {
            return Err(Error::input(
                "bellows: --elastic-slip sets friction's stick stiffness, and no pair has friction (give --friction-plies or --friction-sleeve)",
            ));
        }
        // counted before anything is allocated: an absurd mesh is refused, not a memory failure
        let elements = self.element_estimate();
        if elements > crate::model::mesh::MAX_GENERATED_ELEMENTS as f64 {
            return Err(Error::input(format!(
                "bellows: the mesh would have about {elements:.3e} elements, more than {} (coarsen --ply-elements, --ply-element-length, --wall-elements or --wall-element-length)",
                crate::model::mesh::MAX_GENERATED_ELEMENTS
            )));
        }
        Ok(())
    }

    /// The U-shaped convolution's own checks: tori that hold the ply pack, sidewalls that do not
    /// fold back, a height that holds both tori; named as the user gave the radii.
    fn validate_convolution(&self) -> Result<()> {
        let (rr, rc) = (self.torus_radius, self.crest());
        let pack = self.pack_thickness();
        for (name, r) in [("torus radius", rr), ("crest radius", rc)] {
            if r <= pack / 2.0 {
                return Err(Error::input(format!("bellows: {name} {r} must exceed half the ply pack ({}): the inner ply would fold onto itself", pack / 2.0)));
            }
        }
        // radial sidewalls at q = 2 (rr + rc), tapered ones wider; narrower would fold them back
        if self.pitch < 2.0 * (rr + rc) - 1e-9 {
            // named as the user gave the radii: a torus radius alone, or the root's and crest's
            let radii = if self.crest_radius.is_some() { "2 (root radius + crest radius)" } else { "4 x the torus radius" };
            return Err(Error::input(format!(
                "bellows: a pitch of {} is less than {radii} = {}: U-shaped convolutions' sidewalls would fold back over each other",
                crate::error::shown(self.pitch),
                crate::error::shown(2.0 * (rr + rc))
            )));
        }
        if self.sidewall() < 0.0 {
            let torus = if self.crest_radius.is_some() { "the root and crest radii" } else { "two torus radii" };
            return Err(Error::input(format!("bellows: convolution height {} is less than {torus} ({})", self.height, rr + rc)));
        }
        Ok(())
    }

    /// About how many elements the joint's mesh has: the plies along their developed meridian
    /// (tangents, tori and sidewalls) and the three walls (tubes and sleeve) along the joint.
    fn element_estimate(&self) -> f64 {
        let tori = std::f64::consts::PI * (self.torus_radius + self.crest());
        let meridian = 2.0 * self.tangent_length + self.convolutions as f64 * (tori + 2.0 * self.sidewall_length());
        let plies = (self.plies * self.ply_elements) as f64 * (meridian / self.ply_element_length).ceil();
        let walls = 3.0 * self.wall_elements as f64 * (self.length / self.wall_element_length).ceil();
        plies + walls
    }

    /// The crest tori's mid-surface radius.
    pub fn crest(&self) -> f64 {
        self.crest_radius.unwrap_or(self.torus_radius)
    }

    /// The radial distance between the root's and the crest's torus centres: a radial
    /// sidewall's length.
    pub(super) fn sidewall(&self) -> f64 {
        self.height - self.torus_radius - self.crest()
    }

    /// The length of a sidewall, radial or tapered: the common tangent of the root and crest
    /// tori, whose centres lie q / 2 apart axially.
    pub(super) fn sidewall_length(&self) -> f64 {
        let d2 = (self.pitch / 2.0).powi(2) + self.sidewall().powi(2);
        (d2 - (self.torus_radius + self.crest()).powi(2)).max(0.0).sqrt()
    }

    /// Radius of the tubes' outside surface, where the ply pack's inside sits on the tangents.
    pub fn tube_outer_radius(&self) -> f64 {
        self.tube_inner_radius + self.tube_thickness
    }
}

/// What is wrong with chart coefficients [Cp, Cf, Cd] off the codes' charts, whose
/// coefficients lie between about 0.3 and 3 (for the flags and the specification alike).
pub fn off_the_charts(c: &[f64; 3]) -> Option<String> {
    let (name, v) = [("Cp", c[0]), ("Cf", c[1]), ("Cd", c[2])].into_iter().find(|(_, v)| !(0.1..=10.0).contains(v))?;
    Some(format!(
        "coefficient {name} {} is off the codes' charts: give 0.1 to 10 (the charts' coefficients lie between about 0.3 and 3)",
        crate::error::shown(v)
    ))
}
