//! The design report (`bellows --spec FILE --report FILE.html`), tested as a person would use
//! it: the DN200 joint of examples/dn200_joint.toml run (quick, 2 ranks) with its report,
//! rendered by headless Chromium (Debian's `chromium`, which `./run.sh test` installs): the
//! screenshot is not blank, every number of the code check's tables equals the results file's
//! `/assessment/verdict` to the digits shown, the specification's SHA-256 is the file's, a PDF
//! prints, and `slideline post FILE --report` writes the same file again.

mod common;
use common::command_in;
use std::path::Path;
use std::process::Command;

/// The cells of the rows of the HTML table `id` (text between tags, entities for the
/// comparison signs kept as they are).
fn table_rows(html: &str, id: &str) -> Vec<Vec<String>> {
    let start = html.find(&format!("<table id=\"{id}\">")).unwrap_or_else(|| panic!("no table {id}"));
    let table = &html[start..start + html[start..].find("</table>").unwrap()];
    table
        .split("<tr")
        .skip(1)
        .map(|row| row.split("<td").skip(1).map(|cell| cell[cell.find('>').unwrap() + 1..cell.find("</td>").unwrap()].to_string()).collect::<Vec<_>>())
        .filter(|cells| !cells.is_empty())
        .collect()
}

/// Whether `shown` is `value` to the digits shown.
fn shown_as(shown: &str, value: f64) -> bool {
    let number: f64 = shown.trim_start_matches("&le; ").trim_start_matches("&ge; ").parse().unwrap_or_else(|_| panic!("not a number: {shown:?}"));
    let decimals = shown.split('.').nth(1).map_or(0, str::len) as i32;
    (number - value).abs() <= 0.5 * 10f64.powi(-decimals) * (1.0 + 1e-9)
}

fn chromium(args: &[&str]) -> std::process::Output {
    Command::new("timeout")
        .arg("120")
        .arg("chromium")
        .args(["--headless", "--no-sandbox", "--disable-gpu"])
        .args(args)
        .output()
        .expect("chromium: ./run.sh test installs it (Debian's chromium package)")
}

#[test]
fn the_report_renders_and_its_numbers_are_the_files() {
    let dir = tempfile::tempdir().unwrap();
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/dn200_joint.toml");
    let run = command_in(dir.path(), 2)
        .current_dir(dir.path())
        .args(["bellows", "--spec", spec.to_str().unwrap(), "--quick", "--quiet", "-o", "r.h5", "--report", "r.html"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}{}", String::from_utf8_lossy(&run.stdout), String::from_utf8_lossy(&run.stderr));
    let html = std::fs::read_to_string(dir.path().join("r.html")).unwrap();
    assert!(!html.contains("http://") && !html.contains("https://"), "the report needs no network");

    // rendered: a screenshot with ink on it (text, tables and pictures; a blank page is white)
    let shot = dir.path().join("shot.png");
    let url = format!("file://{}", dir.path().join("r.html").display());
    let out = chromium(&[&format!("--screenshot={}", shot.display()), "--window-size=1200,2400", &url]);
    assert!(shot.exists(), "no screenshot: {}", String::from_utf8_lossy(&out.stderr));
    let decoder = png::Decoder::new(std::fs::File::open(&shot).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).unwrap();
    let channels = info.line_size / info.width as usize;
    let inked = pixels[..info.buffer_size()].chunks(channels).filter(|p| p[..3].iter().any(|&c| c < 200)).count();
    let share = inked as f64 / (info.width * info.height) as f64;
    assert!(share > 0.02, "the rendered report is blank: {:.4} of its pixels inked", share);

    // every number of the checks' and figures' tables is the file's
    let file = hdf5::File::open(dir.path().join("r.h5")).unwrap();
    let g = file.group("assessment/verdict").unwrap();
    let numbers = |n: &str| g.dataset(n).unwrap().read_raw::<f64>().unwrap();
    let (values, limits, ratios) = (numbers("value"), numbers("limit"), numbers("ratio"));
    let rows = table_rows(&html, "checks");
    assert_eq!(rows.len(), values.len(), "{rows:?}");
    for (k, row) in rows.iter().enumerate() {
        assert!(
            shown_as(&row[1], values[k]) && shown_as(&row[2], limits[k]) && shown_as(&row[4], ratios[k]),
            "{row:?} against {} {} {}",
            values[k],
            limits[k],
            ratios[k]
        );
        assert_eq!(row[5], if ratios[k] <= 1.0 { "PASS" } else { "FAIL" }, "{row:?}");
    }
    let figures = table_rows(&html, "figures");
    for (row, name) in figures.iter().zip(["movement_per_convolution", "equivalent_movement", "effective_area", "pressure_thrust"]) {
        let value = g.dataset(name).unwrap().read_scalar::<f64>().unwrap();
        assert!(shown_as(&row[0], value), "{name}: {row:?} against {value}");
    }
    let summary = g.attr("summary").unwrap().read_scalar::<hdf5::types::VarLenUnicode>().unwrap().to_string();
    assert!(html.contains(&format!("Verdict: {summary}</p>")), "{summary}");
    let sha = g.attr("specification_sha256").unwrap().read_scalar::<hdf5::types::VarLenUnicode>().unwrap().to_string();
    let text = std::fs::read(&spec).unwrap();
    use sha2::Digest;
    let expected: String = sha2::Sha256::digest(&text).iter().map(|b| format!("{b:02x}")).collect();
    assert_eq!(sha, expected, "the specification's SHA-256");
    assert!(html.contains(&format!("<code id=\"sha256\">{sha}</code>")));

    // a PDF prints; post writes the same report again from the file
    let pdf = dir.path().join("r.pdf");
    chromium(&[&format!("--print-to-pdf={}", pdf.display()), "--no-pdf-header-footer", &url]);
    assert!(std::fs::read(&pdf).map(|b| b.starts_with(b"%PDF")).unwrap_or(false), "no PDF printed");
    let post = command_in(dir.path(), 1).current_dir(dir.path()).args(["post", "r.h5", "--report", "again.html"]).output().unwrap();
    assert!(post.status.success(), "{}", String::from_utf8_lossy(&post.stderr));
    assert_eq!(std::fs::read_to_string(dir.path().join("again.html")).unwrap(), html, "post's report against the run's");
}
