//! The code check's tables: its section of the closing table (the code's figures at the joint's
//! pressure and stroke), and a specification's verdict, the specification in one paragraph, then
//! each check with its value, limit, utilisation, PASS or FAIL and rule, and the verdict line
//! naming the failing checks.

use crate::assessment::code::{CodeCheck, Source};
use crate::assessment::formulas::UBellows;
use crate::assessment::verdict::{Sense, Verdict};
use crate::bellows::spec::DesignSpec;
use crate::error::Result;

/// The name of a specification's verdict among the tables a results file keeps.
pub const CODE_VERDICT: &str = "code_verdict";

/// Where the rules come from, said once above the table.
pub const EDITION: &str = "ASME VIII-1 Mandatory Appendix 26 (2013 edition), unreinforced U-shaped bellows; EJMA's equation numbers";

/// The verdict table of `spec`, whose code check is `check` and verdict `verdict`.
pub fn verdict_table(spec: &DesignSpec, check: &CodeCheck, verdict: &Verdict) -> Result<String> {
    let b = spec.geometry();
    let (modulus, yield_stress, allowable) = spec.at_temperature()?;
    let allowables = spec.allowables()?;
    let (rc, rr) = spec.mid_surface_radii();
    let mut out = String::new();
    let mut line = |s: String| {
        out.push_str(&s);
        out.push('\n');
    };
    if !spec.title.is_empty() {
        line(spec.title.clone());
    }
    line(format!("code check: {EDITION}"));
    let bs = &spec.bellows;
    line(format!(
        "  bellows: Db {} mm, w {}, q {}, N {}, {} {} x {} mm, crest and root radii {} and {} mm inside (rm {:.3} mid-surface), {}; Dm {:.2} mm, {}",
        bs.inside_diameter,
        bs.convolution_height,
        bs.pitch,
        bs.convolutions,
        bs.plies,
        if bs.plies == 1 { "ply" } else { "plies" },
        bs.ply_thickness,
        bs.crest_radius,
        bs.root_radius,
        (rc + rr) / 2.0,
        bs.forming.label(),
        b.mean_diameter(),
        formed_thickness_label(&b)
    ));
    let m = &spec.material;
    let source = if m.source.is_empty() { String::new() } else { format!(" ({})", m.source) };
    line(format!(
        "  material: {} at {} degC: Eb {modulus:.0} MPa (Eo {:.0}), Sy {yield_stress:.1} MPa, allowable S {allowable:.1} MPa{source}",
        m.name, spec.design.temperature, allowables.room_modulus
    ));
    let k = check.coefficients;
    line(format!("  chart coefficients (C1 {:.3}, C2 {:.3}): Cp {:.4}, Cf {:.4}, Cd {:.4} {}", check.c1, check.c2, k.cp, k.cf, k.cd, check.source.label()));
    if check.source == Source::Computed {
        line(format!("    ({})", crate::bellows::convolution::computed_note()));
    }
    let d = &spec.design;
    let axial = match spec.axial() {
        x if x < 0.0 => format!("axial compression {} mm", -x),
        x => format!("axial extension {x} mm"),
    };
    line(format!(
        "  movements: {axial}, lateral {} mm, angular {} deg: equivalent axial movement {:.4} mm per convolution, {:.2} mm in all",
        d.lateral, d.angular, verdict.movement_per_convolution, verdict.equivalent_movement
    ));
    line(format!(
        "  effective area {:.0} mm^2; pressure thrust {:.0} N at {} MPa; axial rate Kb {:.1} N/mm; stresses S1 {:.1}, S2 {:.1}, S3 {:.2}, S4 {:.1}, S5 {:.1}, S6 {:.1} MPa, St {:.1} MPa",
        verdict.effective_area,
        verdict.pressure_thrust,
        d.pressure,
        check.axial_rate,
        check.s1,
        check.s2,
        check.s3,
        check.s4,
        check.s5,
        check.s6,
        check.stress_range
    ));
    line(format!("  {:<30} {:>11} {:>13} {:<7} {:>6}  {:<7} rule", "check", "value", "limit", "unit", "ratio", "verdict"));
    for c in &verdict.checks {
        let limit = match c.sense {
            Sense::AtMost => format!("<= {}", figure(c.limit)),
            Sense::AtLeast => format!(">= {}", figure(c.limit)),
        };
        let pass = if c.passes() { "PASS" } else { "FAIL" };
        line(format!("  {:<30} {:>11} {:>13} {:<7} {:>6.2}  {:<7} {}", c.name, figure(c.value), limit, c.unit, c.ratio(), pass, c.rule));
    }
    let curve = allowables.fatigue_curve;
    line(format!(
        "  the design's life is the fatigue check's: {} with {}; {}",
        curve.name(),
        curve.factors(allowables.fatigue_factor, allowables.room_modulus, modulus),
        curve.basis()
    ));
    for outside in &verdict.outside {
        line(format!("  note: outside the code's conditions of applicability: {outside}"));
    }
    line(format!("verdict: {}", verdict.summary()));
    Ok(out)
}

/// A figure for the table: four significant digits, whole numbers as they are.
pub(super) fn figure(v: f64) -> String {
    if !v.is_finite() {
        return "unlimited".into();
    }
    if v.abs() >= 1000.0 {
        format!("{v:.0}")
    } else if v.abs() >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.3}")
    }
}

/// The code check's section of the closing table: the EJMA figures at the joint's pressure and
/// stroke, and the notes on where they do not apply.
pub fn code_section(c: &CodeCheck) -> String {
    let k = c.coefficients;
    let mut t = format!("\n  code check (EJMA; C1 {:.3}, C2 {:.3}; Cp {:.3}, Cf {:.3}, Cd {:.3} {}):\n", c.c1, c.c2, k.cp, k.cf, k.cd, c.source.label());
    if c.source == Source::Computed {
        t.push_str(&format!("  ({})\n", crate::bellows::convolution::computed_note()));
    }
    let mut line = |what: &str, value: String| t.push_str(&format!("  {what:<50} {value:>20}\n"));
    line("S1 hoop membrane in the tangent, pressure, MPa", format!("{:.1}", c.s1));
    // files written before S2 and the in-plane instability were computed hold NaN for them
    let known = |v: f64, digits: usize| if v.is_nan() { "-".to_string() } else { format!("{v:.digits$}") };
    line("S2 hoop membrane in the convolutions, pressure, MPa", known(c.s2, 1));
    line("S3 / S4 meridional membrane / bending, pressure, MPa", format!("{:.1} / {:.1}", c.s3, c.s4));
    line("S5 / S6 meridional membrane / bending, stroke, MPa", format!("{:.1} / {:.0}", c.s5, c.s6));
    line("St = 0.7 (S3 + S4) + S5 + S6, MPa", format!("{:.0}", c.stress_range));
    line("allowable cycles (as-formed austenitic curve)", c.cycles.map_or("endurance".into(), |n| format!("{n:.0}")));
    line("axial rate, N/mm full ring", format!("{:.1}", c.axial_rate));
    line("column instability pressure, MPa", format!("{:.2}", c.column_instability));
    line("in-plane instability pressure (Sy* = 2.3 Sy), MPa", known(c.in_plane_instability, 2));
    for note in &c.notes {
        t.push_str(&format!("  note: {note}\n"));
    }
    t
}

/// tp as the code check takes it: EJMA's, or the bellows' own beside EJMA's.
pub fn formed_thickness_label(b: &UBellows) -> String {
    match b.formed_ply_thickness {
        None => format!("tp {:.4} mm", b.formed_thickness()),
        Some(tp) => format!("tp {tp:.4} mm as formed (given; EJMA's t sqrt(Db / Dm) {:.4} mm)", b.ejma_formed_thickness()),
    }
}
