//! The tables a bellows run prints after its closing one: the flexibility (lateral and angular
//! rates), the stability (the instability pressures over the harmonics) and the natural
//! frequencies, each at rest and operating, beside the codes' formulas.

use crate::assessment::code::CodeCheck;
use crate::bellows::flexibility::{Flexibility, Movements};
use crate::bellows::spec::DesignSpec;
use crate::bellows::stability::{column_estimates, Stability};
use crate::bellows::vibration::{estimates, Estimates, Frequencies, Mode};

/// The flexibility section: the lateral and angular spring rates and what the movements add,
/// by harmonic perturbations of the joint at rest and at the end of its run, each beside the
/// codes' beam analogy evaluated with the same state's axial rate (and, for the stresses, the
/// code check's S5 + S6 at the movement's equivalent axial movement per convolution).
pub fn flexibility_section(p: &DesignSpec, code: Option<&CodeCheck>, movements: Movements, rest: &Flexibility, operating: Option<&Flexibility>) -> String {
    let g = p.geometry();
    let (dm, lb, n) = (g.mean_diameter(), g.convolutions as f64 * g.pitch, g.convolutions as f64);
    // the axial movement the operating state has taken (the codes' Lb + x)
    let stroke = if p.joint.cycle { 0.0 } else { -p.displacement() };
    let states: Vec<(&str, &Flexibility, f64)> = std::iter::once(("at rest", rest, 0.0)).chain(operating.map(|f| ("operating", f, stroke))).collect();
    let mut t = format!(
        "\n  flexibility: harmonic perturbations (mode 1) of the joint, the guide sleeve's contact left out, beside the beam analogy\n  \
         (EJMA; lateral 3 K Dm^2 / (2 Lb^2), angular K Dm^2 pi / 1440, K the same state's axial rate by finite elements; Dm {dm:.1} mm, Lb {lb:.1} mm)\n"
    );
    t.push_str(&format!("  {:<52}", ""));
    for (name, _, _) in &states {
        t.push_str(&format!(" {:>11} {:>11} {:>7}", format!("{name} FE"), "code (FE K)", "FE/code"));
    }
    t.push('\n');
    let cell = |v: Option<f64>, digits: usize| v.filter(|v| v.is_finite()).map_or("-".to_string(), |v| format!("{v:.digits$}"));
    // (FE, code) of a row in a state of axial movement x
    type Pick<'a> = &'a dyn Fn(&Flexibility, f64) -> (Option<f64>, Option<f64>);
    let row = |what: &str, pick: Pick, digits: usize| {
        let mut t = format!("  {what:<52}");
        for (_, f, x) in &states {
            let (fe, code) = pick(f, *x);
            let ratio = match (fe, code) {
                (Some(a), Some(b)) if b != 0.0 && a.is_finite() => format!("{:.2}", a / b),
                _ => "-".into(),
            };
            t.push_str(&format!(" {:>11} {:>11} {ratio:>7}", cell(fe, digits), cell(code, digits)));
        }
        t + "\n"
    };
    t += &row("axial rate, N/mm full ring", &|f, _| (Some(f.axial_rate), None), 1);
    let lateral_code = |f: &Flexibility| crate::assessment::formulas::lateral_rate(f.axial_rate, dm, lb);
    let angular_code = |f: &Flexibility| crate::assessment::formulas::angular_rate_per_degree(f.axial_rate, dm);
    // the code check's S5 + S6 at the equivalent axial movement per convolution of a movement
    let code_stress = |e: f64| code.map(|c| g.s5(e, p.youngs_modulus(), c.coefficients.cf) + g.s6(e, p.youngs_modulus(), c.coefficients.cd));
    let (y, theta) = (movements.lateral, movements.angular.to_radians());
    let centre = crate::bellows::flexibility::centre(p);
    if rest.lateral.is_some() {
        let lateral = |f: &Flexibility| f.lateral.clone().expect("both states have the same steps");
        t.push_str(&format!("  lateral offset {y} mm of tube B's end, its rotation held:\n"));
        t += &row("  lateral rate, N/mm", &|f, _| (Some(lateral(f).rate), Some(lateral_code(f))), 1);
        t += &row("  force at the fixed end, N", &|f, _| (Some(lateral(f).fixed_force.abs()), Some(lateral_code(f) * y.abs())), 1);
        // the guided beam's inflection at the bellows' centre: M = F (z_centre - z_fixed)
        t += &row("  moment at the fixed end, N mm", &|f, _| (Some(lateral(f).fixed_moment.abs()), Some(lateral_code(f) * y.abs() * centre)), 0);
        let e = |x: f64| g.equivalent_axial_movement(x, y, 0.0) - x.abs() / n;
        t += &row("  meridional stress added at a crest, MPa (code S5 + S6)", &|f, x| (Some(lateral(f).crest.value), code_stress(e(x))), 1);
        t += &row("  meridional stress added at a root, MPa (code S5 + S6)", &|f, x| (Some(lateral(f).root.value), code_stress(e(x))), 1);
        t += &row("  lateral force the guide sleeve takes as built, N", &|f, _| (f.sleeve_force.map(f64::abs), None), 1);
    }
    if rest.angular.is_some() {
        let angular = |f: &Flexibility| f.angular.clone().expect("both states have the same steps");
        t.push_str(&format!("  rotation {} degrees of tube B's end about the bellows' centre:\n", movements.angular));
        t += &row("  angular rate, N mm/degree", &|f, _| (Some(angular(f).rate), Some(angular_code(f))), 0);
        t += &row("  moment at the fixed end, N mm", &|f, _| (Some(angular(f).fixed_moment.abs()), Some(angular_code(f) * movements.angular.abs())), 0);
        t += &row("  lateral force at the fixed end, N (the code's: none)", &|f, _| (Some(angular(f).fixed_force.abs()), None), 1);
        let e = g.equivalent_axial_movement(0.0, 0.0, theta);
        t += &row("  meridional stress added at a crest, MPa (code S5 + S6)", &|f, _| (Some(angular(f).crest.value), code_stress(e)), 1);
        t += &row("  meridional stress added at a root, MPa (code S5 + S6)", &|f, _| (Some(angular(f).root.value), code_stress(e)), 1);
    }
    t.push_str(
        "  at rest: no pressure, heat or stroke, elastic (the codes' assumption); operating: the end of the run's last step.\n  \
         the stresses are |membrane| + |bending| across a ply, the largest over the crests' and roots' stations; the code's are for\n  \
         the equivalent axial movement per convolution, 3 Dm y / (N (Lb + x)) and Dm theta / (2 N) (EJMA; ASME VIII-1 App. 26)\n",
    );
    t
}

/// The stability section: the buckling pressures of the joint at rest and at the end of its run
/// (both tubes' ends held) beside the codes' estimates with the same state's axial rate.
pub fn stability_section(p: &DesignSpec, code: Option<&CodeCheck>, rest: &Stability, operating: &Stability) -> String {
    stability_columns(p, code, &[("at rest", rest), ("operating", operating)])
}

/// The stability section over any states, one column each (`--form`'s: the idealised joint at
/// rest, the formed bellows at rest and operating).
pub fn stability_columns(p: &DesignSpec, code: Option<&CodeCheck>, states: &[(&str, &Stability)]) -> String {
    let mut t = String::from("\n  stability: buckling analyses of the joint (both tubes' ends held), the critical internal pressure, MPa\n");
    let width = if states.len() > 2 { 13 } else { 12 };
    let line = |what: &str, cells: Vec<String>| format!("  {what:<58}{}\n", cells.iter().map(|c| format!(" {c:>width$}")).collect::<String>());
    t.push_str(&line("", states.iter().map(|(name, _)| name.to_string()).collect()));
    let cell = |v: Option<f64>| v.filter(|v| v.is_finite()).map_or("-".to_string(), |v| format!("{v:.2}"));
    // a harmonic's critical pressure, or where its nearest eigenvalues were all external
    // pressures, the bound it lies above
    let mode = |s: &Stability, n: u32, critical: Option<f64>| match (critical, s.above.iter().find(|a| a.0 == n)) {
        (Some(p), _) => format!("{p:.2}"),
        (None, Some(&(_, b))) => format!("> {b:.1}"),
        (None, None) => "-".into(),
    };
    let mut row = |what: &str, pick: &dyn Fn(&Stability) -> String| {
        t.push_str(&line(what, states.iter().map(|(_, s)| pick(s)).collect()));
    };
    row("axial rate Kb by finite elements, N/mm full ring", &|s| cell(Some(s.axial_rate)));
    row("column instability (squirm), mode 1, finite elements", &|s| mode(s, 1, s.squirm));
    row("  EJMA column formula 0.34 pi Kb / (N q), the same Kb", &|s| cell(Some(column_estimates(p, s.axial_rate).0)));
    row("  the equivalent column, unfactored, 2 pi Kb / (N q)", &|s| cell(Some(column_estimates(p, s.axial_rate).1)));
    row("in-plane instability, mode 0, finite elements", &|s| mode(s, 0, s.in_plane));
    let in_plane_code = code.map(|c| c.in_plane_instability);
    row("  the code's in-plane formula (the code check's)", &|_| cell(in_plane_code));
    let harmonics: Vec<u32> = states.first().map(|(_, s)| s.higher.iter().map(|h| h.0).collect()).unwrap_or_default();
    for (k, &n) in harmonics.iter().enumerate() {
        row(&format!("crest and sidewall mode n = {n}, finite elements"), &|s| mode(s, n, s.higher.get(k).and_then(|h| h.1)));
    }
    let governing = |s: &Stability| s.governing().map_or("-".to_string(), |(n, p)| format!("n = {n}: {p:.2}"));
    t.push_str(&line("the lowest over the harmonics, finite elements", states.iter().map(|(_, s)| governing(s)).collect()));
    let highest = crate::bellows::stability::HIGHEST_HARMONIC;
    if states.iter().any(|(_, s)| s.governing().is_some_and(|(n, _)| n == highest)) {
        t.push_str(&format!("  note: the lowest pressure is the highest harmonic's (n = {highest}): those above it were not analysed\n"));
    }
    t.push_str(
        "  EJMA's 0.34 is 0.17 of the equivalent column's 2: the code's formula carries that margin on the beam analogy;\n  \
         the finite elements give the joint's own elastic buckling pressure, unfactored (the state's pressure plus the load factor);\n  \
         the code's in-plane pressure is a yield criterion (Sy* = 2.3 Sy), not an elastic bifurcation: the two are not the same limit\n",
    );
    t
}

/// The natural frequencies section: the lowest axial and lateral modes of the joint at rest and
/// at the end of its run (both tubes' ends held) beside the analogies of EJMA's frequency
/// formulas with the same state's axial rate, each with its ratio.
pub fn frequencies_section(p: &DesignSpec, rest: &Frequencies, operating: &Frequencies) -> String {
    frequencies_columns(p, &[("at rest", rest), ("operating", operating)])
}

/// The natural frequencies section over any states, one column each (`--form`'s: the idealised
/// joint at rest, the formed bellows at rest and operating).
pub fn frequencies_columns(p: &DesignSpec, columns: &[(&str, &Frequencies)]) -> String {
    let mut t = String::from("\n  natural frequencies: the joint with both tubes' ends held, Hz\n");
    let line = |what: &str, cells: Vec<String>| format!("  {what:<58}{}\n", cells.iter().map(|c| format!(" {c:>12}")).collect::<String>());
    t.push_str(&line("", columns.iter().map(|(name, _)| name.to_string()).collect()));
    let cell = |v: Option<f64>, digits: usize| v.filter(|v| v.is_finite()).map_or("-".to_string(), |v| format!("{v:.digits$}"));
    // each state's analogies once (the Rayleigh beam is a root search)
    let states: Vec<(&Frequencies, Estimates)> = columns.iter().map(|&(_, f)| (f, estimates(p, f))).collect();
    let mass = states.first().map_or(f64::NAN, |s| s.1.mass);
    let mut row = |what: &str, pick: &dyn Fn(&Frequencies, Estimates) -> Option<f64>, digits: usize| {
        t.push_str(&line(what, states.iter().map(|&(f, e)| cell(pick(f, e), digits)).collect()));
    };
    let ratio = |m: Option<Mode>, analogy: f64| m.map(|m| m.frequency / analogy);
    row("axial rate Kb by finite elements, N/mm full ring", &|f, _| Some(f.axial_rate), 1);
    row("convolved length Lb + x, mm", &|f, _| Some(f.convolved_length), 1);
    row("first axial mode (n = 0), finite elements", &|f, _| f.axial.map(|m| m.frequency), 1);
    row("  spring analogy (1/2) sqrt(Kb / m), the same Kb", &|_, e| Some(e.axial), 1);
    row("  ratio, finite elements / analogy", &|f, e| ratio(f.axial, e.axial), 3);
    row("  effective mass / live mass", &|f, e| f.axial.map(|m| m.effective_mass / e.mass), 3);
    row("first lateral mode (n = 1), finite elements", &|f, _| f.lateral.map(|m| m.frequency), 1);
    row("  clamped beam, (E I)eq = Kb Lb Dm^2 / 8 (EJMA's analogy)", &|_, e| Some(e.lateral), 1);
    row("  ratio, finite elements / analogy", &|f, e| ratio(f.lateral, e.lateral), 3);
    row("  the same beam with the rotary inertia m Dm^2 / 8", &|_, e| Some(e.lateral_rotary), 1);
    row("  ratio, finite elements / analogy", &|f, e| ratio(f.lateral, e.lateral_rotary), 3);
    row("  effective mass / live mass", &|f, e| f.lateral.map(|m| m.effective_mass / e.mass), 3);
    t.push_str(&format!(
        "  live mass m: the convolutions' metal, {:.3} kg at {:e} t/mm^3; the fluid's mass is left out (add it for a liquid line);\n  \
         a rod's first mode carries 8 / pi^2 = 0.81 of its mass, a clamped beam's 0.69 (less where the convolutions rock);\n  \
         EJMA's formulas, C sqrt(Kb / W) axially and C (Dm / Lb) sqrt(Kb / W) laterally, tend to the first two analogies for\n  \
         many convolutions; a bellows about as wide as it is long rocks more than it translates, so the rotary inertia they leave\n  \
         out lowers its lateral mode;\n  \
         the finite elements add the tangents' and tubes' mass and stiffness, the plies' contact and, operating, the state's stress;\n  \
         operating, where the folds bear on each other, the analogies are no longer the joint\n",
        mass * 1000.0,
        p.density()
    ));
    t
}
