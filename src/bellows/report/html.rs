//! The design report: one self-contained HTML file (inline CSS, pictures as PNG data URIs, no
//! network) an engineer can hand over, written from the results file alone, so that the run
//! (`bellows --report`) and `slideline post FILE --report` write the same: the specification
//! and its material, the code's verdict with its allowables, the finite-element tables beside
//! it, the mesh, the pictures the run drew next to the file, the software's version and the
//! input's SHA-256. `chromium --headless --print-to-pdf` makes a PDF of it (docs/bellows-spec.md).

use super::code_tables::figure;
use crate::assessment::verdict::{Sense, Verdict};
use crate::bellows::spec::DesignSpec;
use crate::error::Result;
use crate::io::reader::ResultsReader;
use base64::Engine;
use std::path::Path;

/// The report's page style: print-friendly, no external resources.
const STYLE: &str = "body{font-family:'DejaVu Sans',Arial,sans-serif;max-width:1100px;margin:2em auto;color:#222;font-size:14px}\
h1{font-size:22px;border-bottom:2px solid #333}h2{font-size:17px;margin-top:1.6em;border-bottom:1px solid #999}\
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #bbb;padding:3px 8px;text-align:left}\
td.n{text-align:right;font-variant-numeric:tabular-nums}.pass{color:#165f16;font-weight:bold}.fail{color:#a40000;font-weight:bold}\
.verdict{font-size:18px;padding:.5em;border:2px solid #333;display:inline-block}pre{font-size:12px;background:#f6f6f6;padding:.6em;overflow-x:auto}\
figure{margin:1em 0;page-break-inside:avoid}img{max-width:100%}figcaption{font-size:12px;color:#555}";

/// Text for HTML.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// The report of the bellows run whose results file `reader` reads, its closing table `closing`
/// (as printed), as HTML text.
pub fn design_report(reader: &ResultsReader, closing: Option<&str>) -> Result<String> {
    let verdict = reader.verdict()?;
    let spec = match &verdict {
        Some((_, text, _)) => Some(DesignSpec::from_text(text, reader.path())?),
        None => None,
    };
    let by_analysis = crate::dba::read(reader.path())?;
    // a deck's checks (`slideline check`) are of any model, not a bellows
    let untitled = match by_analysis.is_some() && !reader.has_mesh() && spec.is_none() {
        true => format!("The deck checked into {}", reader.path().file_name().unwrap_or_default().to_string_lossy()),
        false => "Bellows expansion joint".into(),
    };
    let title = spec.as_ref().map(|s| s.title.clone()).filter(|t| !t.is_empty()).unwrap_or(untitled);
    let mut h =
        format!("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}</style></head><body>\n", escape(&title));
    h += &format!("<h1>{}: design report</h1>\n", escape(&title));
    h += &format!(
        "<p>slideline {} &middot; results file <code>{}</code>",
        env!("CARGO_PKG_VERSION"),
        escape(&reader.path().file_name().unwrap_or_default().to_string_lossy())
    );
    if let Some((_, _, sha)) = &verdict {
        h += &format!(" &middot; specification SHA-256 <code id=\"sha256\">{sha}</code>");
    }
    h += "</p>\n";
    match (&verdict, &spec) {
        (Some((v, _, _)), Some(s)) => {
            h += &format!("<p class=\"verdict\" id=\"verdict\">Verdict: {}</p>\n", escape(&v.summary()));
            if let Some(d) = &by_analysis {
                h += &format!("<p class=\"verdict\" id=\"dba-verdict\">Design by analysis: {}</p>\n", d.summary());
            }
            h += &specification_section(s)?;
            h += &verdict_section(v, s)?;
        }
        _ => h += "<p>No design specification: the run was not given one (<code>--spec</code>), and there is no code verdict.</p>\n",
    }
    if let Some(d) = &by_analysis {
        h += &dba_section(d);
    }
    h += "<h2>Finite-element analysis</h2>\n";
    if let Some(t) = closing {
        h += &format!("<h3>The run's closing table</h3>\n<pre id=\"closing\">{}</pre>\n", escape(t.trim_end()));
    }
    for (name, text) in reader.printed_tables()?.iter().filter(|(n, _)| n != super::CODE_VERDICT) {
        h += &format!("<h3>{}</h3>\n<pre id=\"table-{}\">{}</pre>\n", escape(name), escape(name), escape(text.trim_matches('\n')));
    }
    h += &mesh_section(reader, by_analysis.as_ref())?;
    h += &pictures_section(reader.path())?;
    if let Some((_, text, sha)) = &verdict {
        h += &format!("<h2>The specification file</h2>\n<p>SHA-256 {sha}</p>\n<pre id=\"specification\">{}</pre>\n", escape(text));
    }
    h += "</body></html>\n";
    Ok(h)
}

/// [`design_report`] written to `path`.
pub fn write_design_report(reader: &ResultsReader, closing: Option<&str>, path: &Path) -> Result<()> {
    let html = design_report(reader, closing)?;
    std::fs::write(path, html).map_err(|e| crate::error::Error::Output { path: path.to_path_buf(), message: e.to_string() })
}

/// The bellows, its material and the design conditions, as the specification gives them.
fn specification_section(s: &DesignSpec) -> Result<String> {
    let b = &s.bellows;
    let (modulus, yield_stress, allowable) = s.at_temperature()?;
    let allowables = s.allowables()?;
    let g = s.geometry();
    let rows: Vec<(&str, String)> = vec![
        ("inside diameter Db", format!("{} mm", b.inside_diameter)),
        ("convolution height w, pitch q", format!("{} mm, {} mm", b.convolution_height, b.pitch)),
        ("crest and root radii (inside) ric, rir", format!("{} mm, {} mm", b.crest_radius, b.root_radius)),
        ("convolutions N; plies n x thickness t", format!("{}; {} x {} mm", b.convolutions, b.plies, b.ply_thickness)),
        ("tangent length Lt", format!("{} mm", b.tangent_length)),
        ("forming", b.forming.label().into()),
        ("mean diameter Dm, formed ply thickness", format!("{:.2} mm, {}", g.mean_diameter(), super::code_tables::formed_thickness_label(&g))),
    ];
    let m = &s.material;
    let material: Vec<(&str, String)> = vec![
        ("material", m.name.clone()),
        ("source of the data", if m.source.is_empty() { "not given".into() } else { m.source.clone() }),
        ("elastic modulus Eb at the design temperature", format!("{modulus:.0} MPa")),
        ("elastic modulus Eo at room temperature", format!("{:.0} MPa", allowables.room_modulus)),
        ("yield stress Sy at the design temperature", format!("{yield_stress:.1} MPa")),
        ("allowable stress S at the design temperature", format!("{allowable:.1} MPa")),
    ];
    let d = &s.design;
    let axial = match s.axial() {
        x if x < 0.0 => format!("compression {} mm", -x),
        x => format!("extension {x} mm"),
    };
    let conditions: Vec<(&str, String)> = vec![
        ("design pressure (internal)", format!("{} MPa", d.pressure)),
        ("design temperature", format!("{} degC", d.temperature)),
        ("axial movement", axial),
        ("lateral offset, angular rotation", format!("{} mm, {} deg", d.lateral, d.angular)),
        ("cycles required", d.cycles.map_or("-".into(), |n| format!("{n}"))),
    ];
    let table = |rows: &[(&str, String)]| rows.iter().map(|(k, v)| format!("<tr><th>{}</th><td>{}</td></tr>", escape(k), escape(v))).collect::<String>();
    Ok(format!(
        "<h2>Specification</h2>\n<h3>Bellows</h3><table>{}</table>\n<h3>Material</h3><table>{}</table>\n<h3>Design conditions</h3><table>{}</table>\n",
        table(&rows),
        table(&material),
        table(&conditions)
    ))
}

/// The code's checks as a table, with the figures beside them and the life's basis.
fn verdict_section(v: &Verdict, s: &DesignSpec) -> Result<String> {
    let allowables = s.allowables()?;
    let mut h = format!("<h2>Code check</h2>\n<p>{}.</p>\n", escape(super::EDITION));
    h += "<table id=\"checks\"><tr><th>check</th><th>value</th><th>limit</th><th>unit</th><th>ratio</th><th>verdict</th><th>rule</th></tr>\n";
    for c in &v.checks {
        let (class, word) = if c.passes() { ("pass", "PASS") } else { ("fail", "FAIL") };
        let limit = match c.sense {
            Sense::AtMost => format!("&le; {}", figure(c.limit)),
            Sense::AtLeast => format!("&ge; {}", figure(c.limit)),
        };
        h += &format!(
            "<tr class=\"check\"><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{limit}</td><td>{}</td><td class=\"n\">{:.2}</td><td class=\"{class}\">{word}</td><td>{}</td></tr>\n",
            escape(&c.name),
            figure(c.value),
            escape(&c.unit),
            c.ratio(),
            escape(&c.rule)
        );
    }
    h += "</table>\n<table id=\"figures\">";
    for (what, value, unit) in [
        ("equivalent axial movement per convolution", v.movement_per_convolution, "mm"),
        ("equivalent axial movement, whole bellows", v.equivalent_movement, "mm"),
        ("effective area", v.effective_area, "mm^2"),
        ("pressure thrust", v.pressure_thrust, "N"),
    ] {
        h += &format!("<tr><th>{what}</th><td class=\"n\">{}</td><td>{unit}</td></tr>", figure(value));
    }
    h += "</table>\n";
    h += &format!(
        "<p>The design's life is the fatigue check's: {} with {}; {}. The finite-element lives (<code>--assess</code>) are a cross-check.</p>\n",
        escape(allowables.fatigue_curve.name()),
        escape(&allowables.fatigue_curve.factors(allowables.fatigue_factor, allowables.room_modulus, s.at_temperature()?.0)),
        escape(allowables.fatigue_curve.basis())
    );
    for outside in &v.outside {
        h += &format!("<p>Outside the code's conditions of applicability: {}</p>\n", escape(outside));
    }
    Ok(h)
}

/// The design-by-analysis checks (ASME VIII-2 Part 5) as a verdict file holds them: the table
/// as printed, and each check's own results file (beside the verdict file).
fn dba_section(v: &crate::dba::Verdict) -> String {
    let mut h = String::from(
        "<h2>Design by analysis</h2>\n<p>ASME Section VIII Division 2, Part 5: each check by an analysis of its own (docs/design-by-analysis.md).</p>\n",
    );
    h += "<table id=\"dba\"><tr><th>check</th><th>criterion</th><th>figure</th><th>limit</th><th>unit</th><th>verdict</th><th>rule</th></tr>\n";
    for r in &v.rows {
        let [figure, limit, word] = r.cells();
        let class = match word.as_str() {
            "PASS" | "holds" => "pass",
            "FAIL" | "fails" => "fail",
            _ => "",
        };
        h += &format!(
            "<tr class=\"dba-check\"><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td><td class=\"{class}\">{word}</td><td>{}</td></tr>\n",
            escape(&r.check),
            escape(&r.criterion),
            escape(&figure),
            escape(&limit),
            escape(&r.unit),
            escape(&r.rule)
        );
    }
    h += &format!("</table>\n<p>Verdict: <span class=\"{}\">{}</span>.", if v.passes() { "pass" } else { "fail" }, v.summary());
    for (name, check_file) in &v.files {
        h += &format!(
            " The {} analysis: <code>{}</code>.",
            escape(&name.replace('_', " ")),
            escape(&check_file.file_name().unwrap_or_default().to_string_lossy())
        );
    }
    h + "</p>\n"
}

/// The mesh: its size, and the element sizes the joint was built with (a verdict file's, from
/// its first check's results file, beside it).
fn mesh_section(reader: &ResultsReader, verdict: Option<&crate::dba::Verdict>) -> Result<String> {
    if !reader.has_mesh() {
        let Some((_, first)) = verdict.and_then(|v| v.files.first()) else { return Ok(String::new()) };
        let beside = reader.path().with_file_name(first.file_name().unwrap_or_default());
        return mesh_section(&ResultsReader::open(&beside)?, None);
    }
    let (nodes, elements) = (reader.coordinates()?.len(), reader.connectivity()?.len());
    let deck = reader.text_attr("deck")?;
    let sizes = crate::bellows::spec::DesignSpec::from_deck(&deck, "the results file's deck")
        .map(|p| {
            format!(
                " Quadratic 8-node axisymmetric elements: {} through each ply, {} mm along it; {} through the tubes' and sleeve's walls, {} mm along them.",
                p.joint.ply_elements, p.joint.ply_element_length, p.joint.wall_elements, p.joint.wall_element_length
            )
        })
        .unwrap_or_default();
    Ok(format!("<h2>Mesh</h2>\n<p id=\"mesh\">{nodes} nodes, {elements} elements.{sizes}</p>\n"))
}

/// The pictures the run drew next to its results file (`STEM_*.png`), inline.
fn pictures_section(results: &Path) -> Result<String> {
    let stem = results.file_stem().unwrap_or_default().to_string_lossy().to_string();
    let dir = results.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut pictures: Vec<_> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "png") && p.file_stem().is_some_and(|s| s.to_string_lossy().starts_with(&format!("{stem}_"))))
                .collect()
        })
        .unwrap_or_default();
    pictures.sort();
    let mut h = String::from("<h2>Pictures</h2>\n");
    if pictures.is_empty() {
        h += "<p>No pictures next to the results file.</p>\n";
    }
    for p in pictures {
        let bytes = std::fs::read(&p).map_err(|source| crate::error::Error::Read { path: p.clone(), source })?;
        let name = p.file_name().unwrap_or_default().to_string_lossy().to_string();
        h += &format!(
            "<figure><img alt=\"{0}\" src=\"data:image/png;base64,{1}\"><figcaption>{0}</figcaption></figure>\n",
            escape(&name),
            base64::engine::general_purpose::STANDARD.encode(bytes)
        );
    }
    Ok(h)
}
