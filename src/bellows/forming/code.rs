//! The code check of the formed bellows: the code's formulas with the ply thickness the forming
//! left, at the crests (the thinnest: the stresses' side) and at the roots, beside EJMA's
//! tp = t sqrt(Db / Dm), each with the chart coefficients of its own C2 and, for a design
//! specification, its verdict. The target's w and q stay: only tp changes.

use crate::assessment::code::CodeCheck;
use crate::assessment::verdict::Verdict;

/// The name of the table in the forming's results file.
pub const TABLE: &str = "code check with the formed thickness";

/// One tp and what the code makes of it.
pub struct Column {
    pub label: &'static str,
    pub tp: f64,
    pub check: CodeCheck,
    pub verdict: Option<Verdict>,
}

/// The table: a row a figure, a column a tp; the verdicts below it.
pub fn table(columns: &[Column]) -> String {
    let mut out = String::from("the code's figures with the formed ply thickness (the target's w and q; the chart coefficients computed for each tp):\n");
    let line = |what: &str, cells: Vec<String>| format!("  {what:<52}{}\n", cells.iter().map(|c| format!(" {c:>12}")).collect::<String>());
    out += &line("", columns.iter().map(|c| c.label.to_string()).collect());
    let mut row = |what: &str, digits: usize, pick: &dyn Fn(&Column) -> Option<f64>| {
        out += &line(what, columns.iter().map(|c| pick(c).filter(|v| v.is_finite()).map_or("-".into(), |v| format!("{v:.digits$}"))).collect());
    };
    row("ply thickness tp, mm", 4, &|c| Some(c.tp));
    row("S2 hoop membrane, pressure, MPa", 1, &|c| Some(c.check.s2));
    row("S3 meridional membrane, pressure, MPa", 2, &|c| Some(c.check.s3));
    row("S4 meridional bending, pressure, MPa", 1, &|c| Some(c.check.s4));
    row("S5 meridional membrane, movement, MPa", 1, &|c| Some(c.check.s5));
    row("S6 meridional bending, movement, MPa", 1, &|c| Some(c.check.s6));
    row("St = 0.7 (S3 + S4) + (S5 + S6), MPa", 1, &|c| Some(c.check.stress_range));
    row("allowable cycles", 0, &|c| c.verdict.as_ref().map_or(c.check.cycles, |v| Some(v.allowable_cycles)));
    row("axial rate Kb, N/mm", 1, &|c| Some(c.check.axial_rate));
    row("column instability Psc, MPa", 3, &|c| Some(c.check.column_instability));
    row("in-plane instability Psi, MPa", 3, &|c| Some(c.check.in_plane_instability));
    for c in columns {
        if let Some(v) = &c.verdict {
            out += &format!("  verdict with {}: {}\n", c.label, v.summary());
        }
    }
    out += "  the crest is the thinnest: the pressure's stresses and the instabilities are on its side (the movement's stresses fall\n  \
            with tp, the life rises); EJMA's tp is the thinning at the mean diameter\n";
    out
}
