//! The formed bellows in service: what the design pressure and the stroke did to it, read from
//! the service's file (which continues the forming's), and its table.

use super::FORMING_STEPS;
use crate::bellows::spec::DesignSpec;
use crate::error::{Error, Result};
use crate::io::reader::ResultsReader;
use std::f64::consts::PI;

/// The name of the service's table in the forming's results file.
pub const TABLE: &str = "formed bellows in service";

/// The formed bellows under the design pressure and through the stroke (forces over the full
/// ring, N; rates N/mm).
#[derive(Clone, Debug, PartialEq)]
pub struct Service {
    /// The largest plastic strain the design pressure added to what forming left.
    pub pressure_strain: f64,
    /// The axial force the bellows bears on the far tangent (positive pushing it away, the
    /// reaction's opposite) at the stroke's start (the pressure's thrust) and end.
    pub force_before: f64,
    pub force_after: f64,
    /// The axial rate over the stroke's first increment, and the secant over the whole stroke.
    pub initial_rate: f64,
    pub secant_rate: f64,
    /// The largest plastic strain the stroke added.
    pub stroke_strain: f64,
    /// The stroke's largest effective strain range and its life by EJMA's as-formed curve (at
    /// the forming's modulus).
    pub life: Option<crate::assessment::fe_check::StrainLife>,
}

/// The last complete increment of general step `step` (1-based) in `reader`.
fn end_of_step(reader: &ResultsReader, step: usize) -> Result<String> {
    let names = reader.increments()?;
    names
        .iter()
        .rev()
        .find(|n| reader.increment_attr(n, "step").ok() == Some(step as f64))
        .cloned()
        .ok_or_else(|| Error::input(format!("{}: no increment of step {step}", reader.path().display())))
}

/// Gauss point field `values` of file `from` in file `to`'s element order (by element number).
fn in_order_of(to: &ResultsReader, from: &ResultsReader, values: &[f64]) -> Result<Vec<f64>> {
    let (theirs, ours) = (from.element_ids()?, to.element_ids()?);
    let points = values.len() / theirs.len().max(1);
    let at: std::collections::HashMap<u64, usize> = theirs.iter().enumerate().map(|(i, &id)| (id, i)).collect();
    let mut out = Vec::with_capacity(values.len());
    for id in ours {
        let i = *at.get(&id).ok_or_else(|| Error::input(format!("{}: element {id} is not in {}", to.path().display(), from.path().display())))?;
        out.extend_from_slice(&values[i * points..(i + 1) * points]);
    }
    Ok(out)
}

/// The largest increase of the equivalent plastic strain at a Gauss point from `before` to `after`.
fn added_strain(before: &[f64], after: &[f64]) -> f64 {
    before.iter().zip(after).map(|(a, b)| b - a).fold(0.0, f64::max)
}

impl Service {
    /// From the forming's file `formed` and the service's `service` (its steps the forming's
    /// [`FORMING_STEPS`], then `SERVICE_STEPS`).
    pub fn read(p: &DesignSpec, formed: &ResultsReader, service: &ResultsReader) -> Result<Service> {
        let ep = |r: &ResultsReader, inc: &str| r.field(inc, "equivalent_plastic_strain");
        let formed_end = formed.increments()?.pop().ok_or_else(|| Error::input("the forming's file has no increment"))?;
        let (pressure, stroke) = (FORMING_STEPS + 1, FORMING_STEPS + 2);
        let (pressed, stroked) = (end_of_step(service, pressure)?, end_of_step(service, stroke)?);
        // the forming's field in the service file's element order: each file keeps its own
        // (the order its run's partition wrote; seen differing between the two, which once
        // read as 15.8 % plastic strain added by the pressure)
        let e0 = in_order_of(service, formed, &ep(formed, &formed_end)?)?;
        let (e1, e2) = (ep(service, &pressed)?, ep(service, &stroked)?);
        let history: Vec<crate::io::HistoryRow> = service.history_rows()?.into_iter().map(|(_, r)| r).collect();
        let rows: Vec<&crate::io::HistoryRow> = history.iter().filter(|r| r.step == stroke).collect();
        let at = |r: &crate::io::HistoryRow| -> Option<(f64, f64)> {
            let f = r.reactions.iter().find(|(s, _)| s == "tangent_b")?.1[1];
            let u = r.set_displacements.iter().find(|(s, _)| s == "tangent_b")?.1[1];
            Some((2.0 * PI * f, u))
        };
        let points: Vec<(f64, f64)> = rows.iter().filter_map(|r| at(r)).collect();
        let start = history
            .iter()
            .rev()
            .find(|r| r.step == pressure)
            .and_then(at)
            .ok_or_else(|| Error::input(format!("{}: no end of the pressure step", service.path().display())))?;
        let (first, last) = match (points.first(), points.last()) {
            (Some(&a), Some(&b)) => (a, b),
            _ => return Err(Error::input(format!("{}: the stroke has no increment", service.path().display()))),
        };
        // the force the bellows bears on the far tangent (the reaction's opposite): the
        // pressure's thrust, then the stroke's compression on top
        let rate = |(f0, u0): (f64, f64), (f1, u1): (f64, f64)| (f1 - f0) / (u1 - u0);
        Ok(Service {
            pressure_strain: added_strain(&e0, &e1),
            force_before: -start.0,
            force_after: -last.0,
            initial_rate: rate(start, first),
            secant_rate: rate(start, last),
            stroke_strain: added_strain(&e1, &e2),
            life: crate::bellows::finite_element::strain_life_between(service, p.forming_modulus()?, pressure, stroke)?,
        })
    }
}

/// The service's table.
pub fn table(p: &DesignSpec, s: &Service) -> String {
    let mut out = format!(
        "the formed bellows in service (its tangents clamped, {} MPa inside, then {} mm of stroke; the forming's material, its\n  \
         thickness, cold work and residual stress carried on):\n",
        crate::error::shown(p.design.pressure),
        crate::error::shown(p.displacement())
    );
    let row = |label: &str, value: String| format!("  {label:<62} {value}\n");
    out += &row("plastic strain the design pressure added, %", format!("{:.4}", 100.0 * s.pressure_strain));
    out += &row("end force, N: under the pressure, at the stroke's end", format!("{:.1}, {:.1}", s.force_before, s.force_after));
    out += &row("axial rate, N/mm: the stroke's first increment, its secant", format!("{:.1}, {:.1}", s.initial_rate, s.secant_rate));
    out += &row("plastic strain the stroke added (largest), %", format!("{:.2}", 100.0 * s.stroke_strain));
    if let Some(life) = &s.life {
        let cycles = life.cycles.map_or("above the curve's endurance".to_string(), |n| format!("{n:.0}"));
        out += &row(
            "the stroke's effective strain range, %: E x it, MPa; cycles",
            format!(
                "{:.3}: {:.0}; {cycles} (EJMA's as-formed curve, at r {:.1}, z {:.1} mm before forming)",
                100.0 * life.strain_range,
                life.pseudo_stress,
                life.at[0],
                life.at[1]
            ),
        );
    }
    out
}
