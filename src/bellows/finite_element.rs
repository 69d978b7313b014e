//! The finite-element side of the bellows assessment: the stresses the code's formulas
//! estimate (S2 .. S6, St, the axial rate, the cycles), computed on the joint itself by two
//! linear elastic analyses as the codes define them:
//! - the design pressure alone, both ends held;
//! - the stroke alone, no pressure (the codes' movement per convolution is the stroke over N).
//!
//! Each is the joint's own model (mesh, contact between the plies, the sleeve) with the
//! plasticity and the heat left out, its load applied at [`LOAD_FRACTION`] of the design value
//! and the answers scaled back up: a linear analysis, as the codes' formulas are. At nine
//! stations along every piece of every convolution (crest, root, both sidewalls; the
//! mid-sidewall, crest and root apexes among them) each ply's meridional membrane stress is its
//! force over its area, from the elements' nodal forces ([`super::membrane`]), and its bending
//! and hoop stresses are linearised across it (`fe::linearize`); the worst over the stations
//! and the plies is reported with where it is. The
//! quarter tori where the pack leaves the tubes are reported apart: the codes' formulas are
//! for the convolutions between.
//!
//! The instability pressures and the axial rate come from the perturbations of the joint at rest
//! (`stability::at_rest`): one axial rate in every table.
//!
//! For the elastic-plastic run itself (the seed case's stroke yields the plies far past what the
//! code's elastic formulas are for) [`strain_life`] gives the life from the total strain range.

use super::membrane::PlyMembrane;
use super::stations::{stations_of, PieceStations, STATIONS};
use crate::assessment::fe_check::{effective_strain_range, FeCheck, Peak, StrainLife};
use crate::assessment::formulas::{cycles_as_formed_austenitic, PSI_PER_MPA};
use crate::bellows::joint::{convolution_pieces, ConvolutionPiece};
use crate::bellows::spec::DesignSpec;
use crate::error::{Error, Result};
use crate::io::reader::ResultsReader;
use crate::model::{Component, GeneralStep, PrescribedDisplacement, Pressure, Step};
use crate::petsc::PetscSession;
use crate::solve::run;
use std::path::Path;

/// The share of the design pressure and stroke the linear analyses apply (then scaled by its
/// inverse): small enough that the large-deformation solver answers linearly.
pub const LOAD_FRACTION: f64 = 0.01;

/// The two linear analyses of joint `p` and their linearised stresses (collective: every rank
/// calls it; the analyses' files go to a temporary directory and are removed), with the
/// instability pressures of `stability` (the joint's buckling analyses at rest).
pub fn analyse(session: &PetscSession, p: &DesignSpec, stability: &super::stability::Stability) -> Result<FeCheck> {
    // the stroke analysis runs without a stroke too (a pressure-only assessment), for the rate
    let nominal = if p.displacement() == 0.0 { 1.0 } else { p.displacement().abs() };
    let stroke = LOAD_FRACTION * nominal;
    let pieces = convolution_pieces(p);
    super::in_scratch(session, "assess", |dir| {
        let pressed = dir.join("pressure.h5");
        let model = linear_analysis(p, "pressure", 0.0, LOAD_FRACTION * p.design.pressure)?;
        run(session, &model, &super::quiet_run(&pressed))?;
        let from_pressure = stations(&pressed, &model, p, &pieces, 1.0 / LOAD_FRACTION)?;
        let stroked = dir.join("stroke.h5");
        let model = stroke_analysis(p, stroke)?;
        run(session, &model, &super::quiet_run(&stroked))?;
        let from_stroke = stations(&stroked, &model, p, &pieces, p.displacement().abs() / stroke)?;
        // the rate is the joint's tangent at rest (the axial perturbation of the stability
        // analyses), the figure the flexibility and stability tables give: the stroke
        // analysis' secant over its 1 % of the stroke moves with the stroke (0.5 % between
        // 10 and 70 mm on the quick joint: the plies' contact and the geometry)
        let mut fe = combine(p, &pieces, &from_pressure, &from_stroke, stability.axial_rate);
        fe.column_instability = stability.squirm.unwrap_or(f64::NAN);
        fe.in_plane_instability = stability.in_plane.unwrap_or(f64::NAN);
        Ok(fe)
    })
}

/// The joint's model for the linear analysis of the stroke alone: tube B's end moved by
/// `stroke` towards tube A (mm), tube A's end held.
pub fn stroke_analysis(p: &DesignSpec, stroke: f64) -> Result<crate::model::Model> {
    linear_analysis(p, "stroke", stroke, 0.0)
}

/// The joint's model, elastic and without the heat, with one step: tube A's end held, tube B's
/// moved by `stroke` towards it (mm), `pressure` (MPa) on the wetted surface.
fn linear_analysis(p: &DesignSpec, name: &str, stroke: f64, pressure: f64) -> Result<crate::model::Model> {
    let hold = |set: &str, value: f64| PrescribedDisplacement { node_set: set.into(), component: Component::Z, value };
    let pressures = if pressure == 0.0 { vec![] } else { vec![Pressure { surface: "wetted".into(), value: pressure }] };
    let mut m = super::elastic_model(p)?;
    let displacements = vec![hold("fixed_end", 0.0), hold("moving_end", -stroke)];
    m.steps = vec![Step::General(GeneralStep { pressures, ..GeneralStep::new(name, 1, displacements) })];
    m.output.every = 1;
    m.output.precision = crate::model::Precision::Double;
    Ok(m)
}

/// The linearised stresses of every station of every piece, through the pack's thickness ply
/// by ply (indexed [piece][station][k], with the ply's number from 0), from the last increment
/// of `file` (a run of `model`), multiplied by `scale` (from the applied load to the
/// design's). The membrane stress is the ply's meridional force over its area, from the
/// elements' nodal forces ([`PlyMembrane`]); the bending and hoop stresses are linearised.
fn stations(file: &Path, model: &crate::model::Model, p: &DesignSpec, pieces: &[ConvolutionPiece], scale: f64) -> Result<Vec<PieceStations>> {
    let r = ResultsReader::open(file)?;
    let last = r.increments()?.pop().ok_or_else(|| Error::Output { path: file.to_path_buf(), message: "no increment".into() })?;
    let stress: Vec<[[f64; 4]; 9]> =
        r.field(&last, "stress")?.chunks_exact(36).map(|c| std::array::from_fn(|q| std::array::from_fn(|k| c[4 * q + k] * scale))).collect();
    let membrane = PlyMembrane::from_file(&r, &last, model, p, pieces, scale)?;
    let mut out = stations_of(&r, &stress, p, pieces)?;
    for (i, piece) in out.iter_mut().enumerate() {
        for (j, station) in piece.iter_mut().enumerate() {
            for (ply, s) in station.iter_mut() {
                s.membrane = membrane.at(*ply, i, (j as f64 + 0.5) / STATIONS as f64);
            }
        }
    }
    Ok(out)
}

/// The worst values over the stations, and S2 as the hoop membrane averaged over each
/// convolution's meridian (a root shared by two convolutions counts half to each).
fn combine(p: &DesignSpec, pieces: &[ConvolutionPiece], pressure: &[PieceStations], stroke: &[PieceStations], axial_rate: f64) -> FeCheck {
    let (mut s3, mut s4, mut s5, mut s6, mut st) = Default::default();
    let mut ends: [Peak; 4] = Default::default();
    let mut hoop = vec![(0.0, 0.0); p.bellows.convolutions];
    for (i, piece) in pieces.iter().enumerate() {
        let weight = piece.piece.length() / STATIONS as f64;
        for j in 0..STATIONS {
            for k in 0..p.bellows.plies {
                let ((ply, a), (_, b)) = (pressure[i][j][k], stroke[i][j][k]);
                let at = || format!("{}, ply {}", piece.label, ply + 1);
                if piece.end {
                    for (end, value) in ends.iter_mut().zip([a.membrane, a.bending, b.membrane, b.bending]) {
                        end.offer(value.abs(), at);
                    }
                } else {
                    Peak::offer(&mut s3, a.membrane.abs(), at);
                    Peak::offer(&mut s4, a.bending.abs(), at);
                    Peak::offer(&mut s5, b.membrane.abs(), at);
                    Peak::offer(&mut s6, b.bending.abs(), at);
                    Peak::offer(&mut st, 0.7 * (a.membrane.abs() + a.bending.abs()) + b.membrane.abs() + b.bending.abs(), at);
                }
                for &(c, share) in &piece.convolutions {
                    hoop[c].0 += share * weight * a.hoop;
                    hoop[c].1 += share * weight;
                }
            }
        }
    }
    let mut s2 = Peak::default();
    for (c, (sum, length)) in hoop.iter().enumerate() {
        s2.offer(sum / length, || format!("convolution {}", c + 1));
    }
    let cycles = cycles_as_formed_austenitic(st.value * PSI_PER_MPA);
    FeCheck { s2, s3, s4, s5, s6, stress_range: st, cycles, ends, axial_rate, column_instability: f64::NAN, in_plane_instability: f64::NAN }
}

/// The strain-based life of the run in `r` (a `slideline bellows` file): the effective total
/// strain range between the end of step 1 (heat and pressure) and the end of step 2 (the
/// stroke) at every ply node, the worst converted to the pseudo-elastic St = E x range the
/// codes' curves are written in (EJMA's curve is fitted to strain-controlled tests so plotted),
/// and the as-formed austenitic curve's cycles for it. None where the file lacks the strains.
pub fn strain_life(r: &ResultsReader, modulus: f64) -> Result<Option<StrainLife>> {
    strain_life_between(r, modulus, 1, 2)
}

/// [`strain_life`] between the ends of general steps `from` and `to` (1-based; the formed
/// bellows' service: its pressure and its stroke, after the forming's steps).
pub fn strain_life_between(r: &ResultsReader, modulus: f64, from: usize, to: usize) -> Result<Option<StrainLife>> {
    let names = r.increments()?;
    let end_of =
        |step: f64| names.iter().rev().find(|n| r.increment_attr(n, "step").ok() == Some(step) && r.increment_attr(n, "load_factor").ok() == Some(1.0));
    let (Some(start), Some(end)) = (end_of(from as f64), end_of(to as f64)) else { return Ok(None) };
    if !r.nodal_fields(end)?.iter().any(|n| n == "strain_rr") {
        return Ok(None);
    }
    let strain = |inc: &str| -> Result<Vec<[f64; 4]>> {
        let c = ["rr", "zz", "tt", "rz"].map(|k| r.field(inc, &format!("nodal/strain_{k}")));
        let [a, b, c, d] = c;
        let (a, b, c, d) = (a?, b?, c?, d?);
        Ok((0..a.len()).map(|n| [a[n], b[n], c[n], d[n]]).collect())
    };
    let (e0, e1) = (strain(start)?, strain(end)?);
    let (coords, conn) = (r.coordinates()?, r.connectivity()?);
    let mut best: Option<StrainLife> = None;
    for set in r.element_set_names()?.iter().filter(|s| s.starts_with("ply")) {
        for e in r.element_set(set)? {
            for &n in &conn[e] {
                let range = effective_strain_range(std::array::from_fn(|k| e1[n][k] - e0[n][k]));
                if best.as_ref().is_none_or(|b| range > b.strain_range) {
                    let pseudo = modulus * range;
                    best = Some(StrainLife {
                        strain_range: range,
                        at: coords[n],
                        pseudo_stress: pseudo,
                        cycles: cycles_as_formed_austenitic(pseudo * PSI_PER_MPA),
                    });
                }
            }
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The effective strain range: a uniaxial incompressible strain (e, -e/2, -e/2) gives e; an
    /// elastic uniaxial stress s (s/E, -nu s/E, -nu s/E) gives (1 + nu) s / (1.5 E); pure shear
    /// gamma = 2 e_rz gives gamma / sqrt 3.
    #[test]
    fn effective_strain_range_of_textbook_states() {
        let e = 0.01;
        assert!((effective_strain_range([e, -e / 2.0, -e / 2.0, 0.0]) - e).abs() < 1e-15);
        let (s, modulus, nu) = (300.0, 200_000.0, 0.3);
        let elastic = effective_strain_range([s / modulus, -nu * s / modulus, -nu * s / modulus, 0.0]);
        assert!((elastic - (1.0 + nu) * s / (1.5 * modulus)).abs() < 1e-15);
        assert!((effective_strain_range([0.0, 0.0, 0.0, e]) - 2.0 * e / 3f64.sqrt()).abs() < 1e-15);
    }
}
