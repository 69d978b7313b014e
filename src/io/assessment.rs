//! The bellows code check in the results file, `/assessment`: one scalar dataset per quantity,
//! each with its `units`, `description` and `source` ("code (computed coefficients)" or "code
//! (as given)" for the code's figures; the coefficients themselves "computed" or "as given"),
//! and the notes as the group's `notes` attribute. Written by rank 0 after the run (the file
//! is closed by then), read back by `slideline post --assessment`.

use super::h5::{describe_dataset, group_in, h5err};
use crate::assessment::code::{CodeCheck, Source};
use crate::assessment::coefficients::Coefficients;
use crate::assessment::fe_check::{FeCheck, Peak, StrainLife};
use crate::assessment::verdict::{Check, Sense, Verdict};
use crate::error::{Error, Result};
use hdf5::types::VarLenUnicode;
use std::path::Path;

/// The group's name.
pub const GROUP: &str = "assessment";

/// (dataset, units, description) of each value, in the order the check is read back.
const VALUES: [(&str, &str, &str); 17] = [
    ("C1", "-", "2 rm / w, the charts' first coordinate"),
    ("C2", "-", "1.82 rm / sqrt(Dm tp), the charts' second coordinate"),
    ("Cp", "-", "chart coefficient of the meridional bending stress from pressure"),
    ("Cf", "-", "chart coefficient of the axial rate and the meridional membrane stress from deflection"),
    ("Cd", "-", "chart coefficient of the meridional bending stress from deflection"),
    ("S1", "MPa", "hoop membrane stress in the tangent from pressure"),
    ("S2", "MPa", "hoop membrane stress in an intermediate convolution from pressure"),
    ("S3", "MPa", "meridional membrane stress from pressure"),
    ("S4", "MPa", "meridional bending stress from pressure"),
    ("S5", "MPa", "meridional membrane stress from the stroke"),
    ("S6", "MPa", "meridional bending stress from the stroke"),
    ("St", "MPa", "total stress range 0.7 (S3 + S4) + S5 + S6"),
    ("cycles", "-", "allowable cycles, as-formed austenitic curve (0: below its endurance range)"),
    ("axial_rate", "N/mm", "the bellows' axial spring rate, full ring"),
    ("column_instability_pressure", "MPa", "column instability (squirm) pressure, both ends held"),
    ("in_plane_instability_pressure", "MPa", "in-plane instability pressure, both ends held, as-formed effective yield 2.3 Sy"),
    ("coefficients_computed", "-", "1: the chart coefficients computed from the idealised convolution; 0: as given"),
];

fn values(c: &CodeCheck) -> [f64; 17] {
    let k = c.coefficients;
    [
        c.c1,
        c.c2,
        k.cp,
        k.cf,
        k.cd,
        c.s1,
        c.s2,
        c.s3,
        c.s4,
        c.s5,
        c.s6,
        c.stress_range,
        c.cycles.unwrap_or(0.0),
        c.axial_rate,
        c.column_instability,
        c.in_plane_instability,
        f64::from(u8::from(c.source == Source::Computed)),
    ]
}

fn text(s: &str, path: &Path) -> Result<VarLenUnicode> {
    s.parse().map_err(|_| Error::Output { path: path.to_path_buf(), message: format!("attribute text {s:?}") })
}

/// Writes `check` into the (closed) results file at `path` (one process).
pub fn write(path: &Path, check: &CodeCheck) -> Result<()> {
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    let g = file.create_group(GROUP).map_err(&err)?;
    let source = format!("code ({})", if check.source == Source::Computed { "computed coefficients" } else { "as given" });
    for ((name, units, description), value) in VALUES.iter().zip(values(check)) {
        let ds = g.new_dataset::<f64>().create(*name).map_err(&err)?;
        ds.write_scalar(&value).map_err(&err)?;
        describe_dataset(&ds, units, description, path)?;
        let from = if ["Cp", "Cf", "Cd"].contains(name) { check.source.label().to_string() } else { source.clone() };
        ds.new_attr::<VarLenUnicode>().create("source").map_err(&err)?.write_scalar(&text(&from, path)?).map_err(&err)?;
    }
    g.new_attr::<VarLenUnicode>().create("notes").map_err(&err)?.write_scalar(&text(&check.notes.join("\n"), path)?).map_err(&err)?;
    file.flush().map_err(&err)
}

/// The check stored in `file`, None where it has none.
pub fn read(file: &hdf5::File, path: &Path) -> Result<Option<CodeCheck>> {
    if !file.link_exists(GROUP) {
        return Ok(None);
    }
    let bad = |e: hdf5::Error| Error::input(format!("{}: /{GROUP}: {e}", path.display()));
    let g = file.group(GROUP).map_err(bad)?;
    let mut v = [0.0; 17];
    for (slot, (name, _, _)) in v.iter_mut().zip(VALUES) {
        // S2 and the in-plane instability came later: NaN (printed "-") in older files
        *slot = match g.link_exists(name) {
            true => g.dataset(name).and_then(|d| d.read_scalar::<f64>()).map_err(bad)?,
            false if ["S2", "in_plane_instability_pressure"].contains(&name) => f64::NAN,
            false => return Err(bad(hdf5::Error::from(format!("no dataset {name}").as_str()))),
        };
    }
    let notes = g.attr("notes").and_then(|a| a.read_scalar::<VarLenUnicode>()).map_err(bad)?.to_string();
    Ok(Some(CodeCheck {
        coefficients: Coefficients { cp: v[2], cf: v[3], cd: v[4] },
        source: if v[16] == 1.0 { Source::Computed } else { Source::Given },
        c1: v[0],
        c2: v[1],
        s1: v[5],
        s2: v[6],
        s3: v[7],
        s4: v[8],
        s5: v[9],
        s6: v[10],
        stress_range: v[11],
        cycles: (v[12] > 0.0).then_some(v[12]),
        axial_rate: v[13],
        column_instability: v[14],
        in_plane_instability: v[15],
        notes: notes.lines().filter(|l| !l.is_empty()).map(str::to_string).collect(),
    }))
}

/// The finite-element side's subgroup of `/assessment`.
pub const FINITE_ELEMENT: &str = "assessment/finite_element";

/// (dataset, units, description) of the finite-element figures, in the order read back.
const FE_VALUES: [(&str, &str, &str); 18] = [
    ("S2", "MPa", "hoop membrane stress from pressure, averaged over a convolution's meridian, worst convolution"),
    ("S3", "MPa", "largest meridional membrane stress from pressure"),
    ("S4", "MPa", "largest meridional bending stress from pressure"),
    ("S5", "MPa", "largest meridional membrane stress from the stroke"),
    ("S6", "MPa", "largest meridional bending stress from the stroke"),
    ("St", "MPa", "largest 0.7 (|S3| + |S4|) + |S5| + |S6| at one point"),
    ("axial_rate", "N/mm", "axial rate of the joint from the stroke analysis' end reaction, full ring"),
    ("cycles", "-", "allowable cycles from St, as-formed austenitic curve (0: below its endurance range)"),
    ("end_S3", "MPa", "largest meridional membrane stress from pressure where the pack leaves the tubes"),
    ("end_S4", "MPa", "largest meridional bending stress from pressure where the pack leaves the tubes"),
    ("end_S5", "MPa", "largest meridional membrane stress from the stroke where the pack leaves the tubes"),
    ("end_S6", "MPa", "largest meridional bending stress from the stroke where the pack leaves the tubes"),
    ("strain_range", "-", "the elastic-plastic run's largest effective total strain range over the plies, stroke start to end (NaN: not computed)"),
    ("strain_range_r", "mm", "where: r in the undeformed mesh"),
    ("strain_range_z", "mm", "where: z in the undeformed mesh"),
    ("strain_cycles", "-", "allowable cycles for the pseudo-elastic range E x strain range, as-formed austenitic curve (0: below its endurance range)"),
    (
        "column_instability",
        "MPa",
        "column instability (squirm) pressure by a buckling analysis (mode 1) of the joint at rest, both ends held (NaN: none found)",
    ),
    ("in_plane_instability", "MPa", "in-plane instability pressure by a buckling analysis (mode 0) of the joint at rest, both ends held (NaN: none found)"),
];

/// The datasets with a place (the `where` attribute), in [`FeCheck`]'s order.
const PEAKS: [&str; 10] = ["S2", "S3", "S4", "S5", "S6", "St", "end_S3", "end_S4", "end_S5", "end_S6"];

/// Writes the finite-element figures into the (closed) results file at `path` (one process).
pub fn write_finite_element(path: &Path, fe: &FeCheck, life: Option<&StrainLife>) -> Result<()> {
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    group_in(&file, GROUP, path)?;
    let g = file.create_group(FINITE_ELEMENT).map_err(&err)?;
    let nan = f64::NAN;
    let values = [
        fe.s2.value,
        fe.s3.value,
        fe.s4.value,
        fe.s5.value,
        fe.s6.value,
        fe.stress_range.value,
        fe.axial_rate,
        fe.cycles.unwrap_or(0.0),
        fe.ends[0].value,
        fe.ends[1].value,
        fe.ends[2].value,
        fe.ends[3].value,
        life.map_or(nan, |l| l.strain_range),
        life.map_or(nan, |l| l.at[0]),
        life.map_or(nan, |l| l.at[1]),
        life.map_or(nan, |l| l.cycles.unwrap_or(0.0)),
        fe.column_instability,
        fe.in_plane_instability,
    ];
    let peaks = [&fe.s2, &fe.s3, &fe.s4, &fe.s5, &fe.s6, &fe.stress_range, &fe.ends[0], &fe.ends[1], &fe.ends[2], &fe.ends[3]];
    for ((name, units, description), value) in FE_VALUES.iter().zip(values) {
        let ds = g.new_dataset::<f64>().create(*name).map_err(&err)?;
        ds.write_scalar(&value).map_err(&err)?;
        describe_dataset(&ds, units, description, path)?;
        ds.new_attr::<VarLenUnicode>().create("source").map_err(&err)?.write_scalar(&text("finite element", path)?).map_err(&err)?;
        if let Some(peak) = PEAKS.iter().position(|n| n == name).map(|i| peaks[i]) {
            ds.new_attr::<VarLenUnicode>().create("where").map_err(&err)?.write_scalar(&text(&peak.at, path)?).map_err(&err)?;
        }
    }
    // the modulus that turned the strain range into the curve's pseudo-elastic stress, MPa
    g.new_attr::<f64>().create("modulus").map_err(&err)?.write_scalar(&life.map_or(nan, |l| l.pseudo_stress / l.strain_range)).map_err(&err)?;
    file.flush().map_err(&err)
}

/// The finite-element figures stored in `file`, None where it has none.
pub fn read_finite_element(file: &hdf5::File, path: &Path) -> Result<Option<(FeCheck, Option<StrainLife>)>> {
    if !file.link_exists(FINITE_ELEMENT) {
        return Ok(None);
    }
    let bad = |e: hdf5::Error| Error::input(format!("{}: /{FINITE_ELEMENT}: {e}", path.display()));
    let g = file.group(FINITE_ELEMENT).map_err(bad)?;
    let value = |name: &str| g.dataset(name).and_then(|d| d.read_scalar::<f64>()).map_err(bad);
    let peak = |name: &str| -> Result<Peak> {
        let at = g.dataset(name).and_then(|d| d.attr("where")).and_then(|a| a.read_scalar::<VarLenUnicode>()).map_err(bad)?.to_string();
        Ok(Peak { value: value(name)?, at })
    };
    let modulus = g.attr("modulus").and_then(|a| a.read_scalar::<f64>()).map_err(bad)?;
    let counted = |n: f64| (n > 0.0).then_some(n);
    let fe = FeCheck {
        s2: peak("S2")?,
        s3: peak("S3")?,
        s4: peak("S4")?,
        s5: peak("S5")?,
        s6: peak("S6")?,
        stress_range: peak("St")?,
        cycles: counted(value("cycles")?),
        ends: [peak("end_S3")?, peak("end_S4")?, peak("end_S5")?, peak("end_S6")?],
        axial_rate: value("axial_rate")?,
        // files written before the buckling analyses have none
        column_instability: value("column_instability").unwrap_or(f64::NAN),
        in_plane_instability: value("in_plane_instability").unwrap_or(f64::NAN),
    };
    let strain_range = value("strain_range")?;
    let life = match strain_range.is_nan() {
        true => None,
        false => Some(StrainLife {
            strain_range,
            at: [value("strain_range_r")?, value("strain_range_z")?],
            pseudo_stress: modulus * strain_range,
            cycles: counted(value("strain_cycles")?),
        }),
    };
    Ok(Some((fe, life)))
}

/// The group of the tables the run printed after its closing table.
pub const TABLES: &str = "tables";

/// Writes `tables` (name, text as printed) into the (closed) results file at `path` (one
/// process) as `/tables/NAME` strings, replacing a restarted run's: `slideline post FILE` prints
/// them again, word for word.
pub fn write_tables(path: &Path, tables: &[(&str, String)]) -> Result<()> {
    if tables.is_empty() {
        return Ok(());
    }
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    if file.link_exists(TABLES) {
        file.unlink(TABLES).map_err(&err)?;
    }
    let g = file.create_group(TABLES).map_err(&err)?;
    // the order the run printed them in (HDF5 lists members alphabetically)
    let order = tables.iter().map(|(name, _)| *name).collect::<Vec<_>>().join(",");
    g.new_attr::<VarLenUnicode>().create("order").map_err(&err)?.write_scalar(&text(&order, path)?).map_err(&err)?;
    for (name, table) in tables {
        let ds = g.new_dataset::<VarLenUnicode>().create(*name).map_err(&err)?;
        ds.write_scalar(&text(table, path)?).map_err(&err)?;
        ds.new_attr::<VarLenUnicode>().create("description").map_err(&err)?.write_scalar(&text("the table as the run printed it", path)?).map_err(&err)?;
    }
    file.flush().map_err(&err)
}

/// The tables `file` holds (name, text), in the order the run printed them.
pub fn read_tables(file: &hdf5::File, path: &Path) -> Result<Vec<(String, String)>> {
    let Ok(g) = file.group(TABLES) else { return Ok(Vec::new()) };
    let bad = |e: hdf5::Error| Error::input(format!("{}: /{TABLES}: {e}", path.display()));
    let order = g.attr("order").and_then(|a| a.read_scalar::<VarLenUnicode>()).map_err(bad)?.to_string();
    order
        .split(',')
        .filter(|name| !name.is_empty())
        .map(|name| Ok((name.to_string(), g.dataset(name).and_then(|d| d.read_scalar::<VarLenUnicode>()).map_err(bad)?.to_string())))
        .collect()
}

/// A design specification's verdict, `/assessment/verdict`: per check (in the table's order)
/// its `name`, `rule`, `value`, `limit`, `unit`, `sense` ("at most", "at least"), `ratio` and
/// `verdict` as one-dimensional datasets; the figures beside them as scalar datasets with their
/// units; the verdict line, the conditions of applicability violated, and the specification's
/// text with its SHA-256 as the group's attributes.
pub const VERDICT: &str = "verdict";

/// The verdict's scalar figures: (attribute, units, what it is).
const VERDICT_FIGURES: [(&str, &str, &str); 5] = [
    ("movement_per_convolution", "mm", "equivalent axial movement per convolution"),
    ("equivalent_movement", "mm", "equivalent axial movement of the whole bellows"),
    ("effective_area", "mm^2", "effective area pi Dm^2 / 4"),
    ("pressure_thrust", "N", "pressure thrust P x effective area"),
    ("allowable_cycles", "-", "allowable cycles of the fatigue check"),
];

fn verdict_figures(v: &Verdict) -> [f64; 5] {
    [v.movement_per_convolution, v.equivalent_movement, v.effective_area, v.pressure_thrust, v.allowable_cycles]
}

/// Writes `verdict` of the specification `spec` (its text) into the (closed) results file at
/// `path` (one process), replacing a restarted run's.
pub fn write_verdict(path: &Path, verdict: &Verdict, spec: &str, sha256: &str) -> Result<()> {
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    let parent = group_in(&file, GROUP, path)?;
    if parent.link_exists(VERDICT) {
        parent.unlink(VERDICT).map_err(&err)?;
    }
    let g = parent.create_group(VERDICT).map_err(&err)?;
    let strings = |name: &str, values: Vec<String>| -> Result<()> {
        let values: Vec<VarLenUnicode> = values.iter().map(|s| text(s, path)).collect::<Result<_>>()?;
        g.new_dataset_builder().with_data(&values).create(name).map_err(&err)?;
        Ok(())
    };
    let checks = &verdict.checks;
    strings("name", checks.iter().map(|c| c.name.clone()).collect())?;
    strings("rule", checks.iter().map(|c| c.rule.clone()).collect())?;
    strings("unit", checks.iter().map(|c| c.unit.clone()).collect())?;
    strings("sense", checks.iter().map(|c| if c.sense == Sense::AtMost { "at most" } else { "at least" }.to_string()).collect())?;
    strings("verdict", checks.iter().map(|c| if c.passes() { "PASS" } else { "FAIL" }.to_string()).collect())?;
    for (name, values) in [
        ("value", checks.iter().map(|c| c.value).collect::<Vec<_>>()),
        ("limit", checks.iter().map(|c| c.limit).collect()),
        ("ratio", checks.iter().map(|c| c.ratio()).collect()),
    ] {
        g.new_dataset_builder().with_data(&values).create(name).map_err(&err)?;
    }
    for ((name, units, what), value) in VERDICT_FIGURES.iter().zip(verdict_figures(verdict)) {
        let ds = g.new_dataset::<f64>().create(*name).map_err(&err)?;
        ds.write_scalar(&value).map_err(&err)?;
        describe_dataset(&ds, units, what, path)?;
    }
    for (name, value) in [
        ("summary", verdict.summary()),
        ("outside", verdict.outside.join("\n")),
        ("specification", spec.to_string()),
        ("specification_sha256", sha256.to_string()),
    ] {
        g.new_attr::<VarLenUnicode>().create(name).map_err(&err)?.write_scalar(&text(&value, path)?).map_err(&err)?;
    }
    file.flush().map_err(&err)
}

/// The verdict `file` holds with the specification's text and SHA-256, None where it has none.
pub fn read_verdict(file: &hdf5::File, path: &Path) -> Result<Option<(Verdict, String, String)>> {
    let name = format!("{GROUP}/{VERDICT}");
    if !file.link_exists(GROUP) || !file.link_exists(&name) {
        return Ok(None);
    }
    let bad = |e: hdf5::Error| Error::input(format!("{}: /{name}: {e}", path.display()));
    let g = file.group(&name).map_err(bad)?;
    let strings =
        |n: &str| -> Result<Vec<String>> { Ok(g.dataset(n).and_then(|d| d.read_raw::<VarLenUnicode>()).map_err(bad)?.iter().map(|s| s.to_string()).collect()) };
    let numbers = |n: &str| g.dataset(n).and_then(|d| d.read_raw::<f64>()).map_err(bad);
    let attr = |n: &str| g.attr(n).and_then(|a| a.read_scalar::<VarLenUnicode>()).map(|s| s.to_string()).map_err(bad);
    let (names, rules, units, senses) = (strings("name")?, strings("rule")?, strings("unit")?, strings("sense")?);
    let (values, limits) = (numbers("value")?, numbers("limit")?);
    let checks = (0..names.len())
        .map(|k| Check {
            name: names[k].clone(),
            rule: rules[k].clone(),
            value: values[k],
            limit: limits[k],
            unit: units[k].clone(),
            sense: if senses[k] == "at most" { Sense::AtMost } else { Sense::AtLeast },
        })
        .collect();
    let figure = |n: &str| g.dataset(n).and_then(|d| d.read_scalar::<f64>()).map_err(bad);
    let outside = attr("outside")?;
    let verdict = Verdict {
        checks,
        movement_per_convolution: figure("movement_per_convolution")?,
        equivalent_movement: figure("equivalent_movement")?,
        effective_area: figure("effective_area")?,
        pressure_thrust: figure("pressure_thrust")?,
        allowable_cycles: figure("allowable_cycles")?,
        outside: outside.lines().map(str::to_string).filter(|l| !l.is_empty()).collect(),
    };
    Ok(Some((verdict, attr("specification")?, attr("specification_sha256")?)))
}
