//! The bellows' lateral and angular spring rates by harmonic perturbation steps (mode 1) about a
//! state of the joint (`solve::procedures::perturbation`), beside the codes' beam analogy evaluated with the
//! joint's own axial rate (a mode 0 perturbation about the same state):
//! - `axial`: the moving end pushed 1 mm along the axis, twist held at both ends;
//! - `lateral`: the moving end offset sideways, its rotation held (the ends parallel, the codes'
//!   lateral case); the fixed end held;
//! - `angular`: the moving end rotated about a diameter through the bellows' centre: the end
//!   moves as a joint bent to an arc by a moment alone, with little shear left (the codes'
//!   angular case), and its moment is reported about that centre;
//! - `lateral_as_built`: the lateral offset with the guide sleeve's contact kept, for the force
//!   the sleeve takes in the joint as built.
//!
//! The first three leave the sleeve's contact out: the codes' rates are the bellows' own. The
//! state is either the joint at rest (no pressure, heat or stroke: the codes' assumption; a
//! run of its own, [`at_rest`]) or the end of the joint's own run (its last general step, the
//! operating state: [`from_run`]).

use super::stations::{stations_of, PieceStations};
use crate::assessment::fe_check::Peak;
use crate::bellows::joint::convolution_pieces;
use crate::bellows::spec::DesignSpec;
use crate::error::Result;
use crate::io::reader::ResultsReader;
use crate::model::perturbation::{Analysis, HarmonicComponent, HarmonicDisplacement, Perturbation, RingMotion};
use crate::petsc::PetscSession;
use crate::records::perturbation::PerturbationAnswer;

pub const AXIAL: &str = "axial";
pub const LATERAL: &str = "lateral";
pub const ANGULAR: &str = "angular";
pub const LATERAL_AS_BUILT: &str = "lateral_as_built";
/// The contact pair of the guide sleeve in the joint's model.
const SLEEVE: &str = "sleeve";

/// The movements of the moving end the perturbations apply: a lateral offset (mm) and a
/// rotation (degrees); a zero one is left out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Movements {
    pub lateral: f64,
    pub angular: f64,
}

impl Movements {
    /// The movements asked (`--lateral` mm, `--angular` degrees), if any, for joint `p`: what
    /// the codes' beam analogy and a linear perturbation describe, an offset up to the
    /// convoluted length and a rotation up to 45 degrees, nonzero.
    pub fn checked(lateral: Option<f64>, angular: Option<f64>, p: &DesignSpec) -> Result<Option<Self>> {
        if lateral.is_none() && angular.is_none() {
            return Ok(None);
        }
        let length = p.bellows.convolutions as f64 * p.bellows.pitch;
        for (flag, v, units, most) in [("--lateral", lateral, "mm", length), ("--angular", angular, "degrees", 45.0)] {
            if let Some(v) = v.filter(|v| !v.is_finite() || *v == 0.0 || v.abs() > most) {
                return Err(crate::error::Error::input(format!(
                    "{flag} {}: give a nonzero movement of at most {most} {units} in size",
                    crate::error::shown(v)
                )));
            }
        }
        Ok(Some(Movements { lateral: lateral.unwrap_or(0.0), angular: angular.unwrap_or(0.0) }))
    }
}

/// One movement's answers (full ring).
#[derive(Clone, Debug, PartialEq)]
pub struct MovementResponse {
    /// N/mm (lateral) or N mm per degree (angular).
    pub rate: f64,
    /// The fixed end's reactions: lateral force (N) and moment about its centre (N mm).
    pub fixed_force: f64,
    pub fixed_moment: f64,
    /// The largest meridional stress, |membrane| + |bending|, the movement adds at a crest and
    /// at a root (MPa; the amplitude, at theta = 0).
    pub crest: Peak,
    pub root: Peak,
}

/// The joint's flexibility about one state.
#[derive(Clone, Debug, PartialEq)]
pub struct Flexibility {
    /// The axial rate of the same state (N/mm, full ring), for the codes' beam analogy.
    pub axial_rate: f64,
    pub lateral: Option<MovementResponse>,
    pub angular: Option<MovementResponse>,
    /// The lateral force the guide sleeve takes in the joint as built (N): the as-built offset's
    /// force at the moving end less the bellows' own.
    pub sleeve_force: Option<f64>,
}

/// The z of the bellows' centre: the middle of its convolutions.
pub fn centre(p: &DesignSpec) -> f64 {
    let pieces = convolution_pieces(p);
    let (a, b) = (pieces[0].piece.at(0.0).0[1], pieces[pieces.len() - 1].piece.at(1.0).0[1]);
    0.5 * (a + b)
}

/// The perturbation steps of `movements` on joint `p`.
pub fn steps(p: &DesignSpec, movements: Movements) -> Vec<Perturbation> {
    let held = |set: &str| {
        [HarmonicComponent::R, HarmonicComponent::Z, HarmonicComponent::T].map(|component| HarmonicDisplacement { node_set: set.into(), component, value: 0.0 })
    };
    let step = |name: &str, mode: u32, displacements: Vec<HarmonicDisplacement>, rings: Vec<RingMotion>, sleeve: bool| Perturbation {
        name: name.into(),
        mode,
        displacements,
        rings,
        pressures: Vec::new(),
        without_contact: if sleeve { Vec::new() } else { vec![SLEEVE.into()] },
        analysis: Analysis::Response,
    };
    let amplitude = |set: &str, component, value| HarmonicDisplacement { node_set: set.into(), component, value };
    let mut out = vec![step(
        AXIAL,
        0,
        vec![
            amplitude("fixed_end", HarmonicComponent::Z, 0.0),
            amplitude("fixed_end", HarmonicComponent::T, 0.0),
            amplitude("moving_end", HarmonicComponent::Z, -1.0),
            amplitude("moving_end", HarmonicComponent::T, 0.0),
        ],
        Vec::new(),
        false,
    )];
    let ring = |lateral: f64, rotation: f64, pivot: Option<f64>| vec![RingMotion { node_set: "moving_end".into(), lateral, rotation, pivot }];
    if movements.lateral != 0.0 {
        out.push(step(LATERAL, 1, held("fixed_end").to_vec(), ring(movements.lateral, 0.0, None), false));
    }
    if movements.angular != 0.0 {
        // about the bellows' centre where the state has it: the stroke shortens the
        // convolutions alone, so the centre has moved by half of it (the heat's few tenths of a
        // millimetre left out); the moving end's moment is then the bellows' own
        let stroke = if p.joint.cycle { 0.0 } else { p.displacement() };
        out.push(step(ANGULAR, 1, held("fixed_end").to_vec(), ring(0.0, movements.angular.to_radians(), Some(centre(p) - stroke / 2.0)), false));
    }
    if movements.lateral != 0.0 {
        out.push(step(LATERAL_AS_BUILT, 1, held("fixed_end").to_vec(), ring(movements.lateral, 0.0, None), true));
    }
    out
}

/// Resultant `name` of set `set` in the answer of perturbation step `step`.
fn resultant_in(answers: &[(String, PerturbationAnswer)], step: &str, set: &str, name: &str) -> Option<f64> {
    let (_, answer) = answers.iter().find(|(s, _)| s == step)?;
    let reaction = answer.reactions.iter().find(|x| x.set == set)?;
    reaction.resultants.iter().find(|(n, _, _)| *n == name).map(|(_, v, _)| *v)
}

/// The axial rate (N/mm, full ring) from the answer of the [`AXIAL`] step.
pub(super) fn axial_rate(answers: &[(String, PerturbationAnswer)]) -> Result<f64> {
    let force = resultant_in(answers, AXIAL, "moving_end", "axial_force_ring");
    force.map(f64::abs).ok_or_else(|| crate::error::Error::input("the perturbation steps ran without the axial rate's"))
}

/// The flexibility from the perturbation answers of a run of the joint `p` with [`steps`], its
/// stresses from the run's results file `r`.
pub fn from_run(p: &DesignSpec, movements: Movements, answers: &[(String, PerturbationAnswer)], r: &ResultsReader) -> Result<Flexibility> {
    let resultant = |step: &str, set: &str, name: &str| resultant_in(answers, step, set, name);
    let missing = |what: &str| crate::error::Error::Output { path: r.path().to_path_buf(), message: format!("no {what} in the perturbation steps") };
    let axial_rate = axial_rate(answers)?;
    let pieces = convolution_pieces(p);
    let response = |step: &str, per: f64| -> Result<Option<MovementResponse>> {
        if per == 0.0 {
            return Ok(None);
        }
        let (force, moment) = (resultant(step, "moving_end", "lateral_force_ring"), resultant(step, "moving_end", "moment_ring"));
        let (Some(force), Some(moment)) = (force, moment) else { return Err(missing(step)) };
        let fixed = |name: &str| resultant(step, "fixed_end", name).ok_or_else(|| missing(step));
        // the stress amplitudes' first four components: [rr, zz, tt, rz] at theta = 0
        let stress: Vec<[[f64; 4]; 9]> =
            r.perturbation_field(step, "stress")?.chunks_exact(54).map(|c| std::array::from_fn(|q| std::array::from_fn(|k| c[6 * q + k]))).collect();
        let stations = stations_of(r, &stress, p, &pieces)?;
        let (crest, root) = peaks(&pieces, &stations);
        let rate = if step == ANGULAR { moment / per } else { force / per };
        Ok(Some(MovementResponse { rate: rate.abs(), fixed_force: fixed("lateral_force_ring")?, fixed_moment: fixed("moment_ring")?, crest, root }))
    };
    let lateral = response(LATERAL, movements.lateral)?;
    let angular = response(ANGULAR, movements.angular)?;
    let sleeve_force = match (resultant(LATERAL_AS_BUILT, "moving_end", "lateral_force_ring"), resultant(LATERAL, "moving_end", "lateral_force_ring")) {
        (Some(built), Some(own)) => Some(built - own),
        _ => None,
    };
    Ok(Flexibility { axial_rate, lateral, angular, sleeve_force })
}

/// The largest |membrane| + |bending| over the crests' and the roots' stations (the pieces at
/// the tubes left out, as in the code check).
fn peaks(pieces: &[crate::bellows::joint::ConvolutionPiece], stations: &[PieceStations]) -> (Peak, Peak) {
    let (mut crest, mut root) = (Peak::default(), Peak::default());
    for (piece, stations) in pieces.iter().zip(stations).filter(|(piece, _)| !piece.end) {
        let peak = match piece.label.split(' ').next() {
            Some("crest") => &mut crest,
            Some("root") => &mut root,
            _ => continue,
        };
        for &(ply, s) in stations.iter().flatten() {
            peak.offer(s.membrane.abs() + s.bending.abs(), || format!("{}, ply {}", piece.label, ply + 1));
        }
    }
    (crest, root)
}

/// The joint `p` at rest (no pressure, heat or stroke, elastic: the codes' assumption) and the
/// perturbations of `movements` about it (collective; the run's file goes to a temporary
/// directory and is removed).
pub fn at_rest(session: &PetscSession, p: &DesignSpec, movements: Movements) -> Result<Flexibility> {
    super::at_rest(
        session,
        p,
        "flexibility",
        |rest| steps(rest, movements),
        |rest, summary, file| from_run(rest, movements, &summary.perturbations, &ResultsReader::open(file)?),
    )
}
