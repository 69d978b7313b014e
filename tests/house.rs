//! The house's measures hold on the source (scripts/house.py, docs/code.md): no import circle
//! between directories or files, no import against the layers, no function over 120 lines, no
//! file over 550 lines before its tests. And the check sees what it must: a circle closed
//! through a re-export (`pub use`) and a `use super::{...}` group, the way io/results.rs,
//! io/restart.rs and io/reader.rs once closed one unseen.

mod common;
use std::path::Path;

fn house(src: &Path) -> (bool, String) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/house.py");
    let out = common::python().arg(script).arg(src).output().expect("python3 runs scripts/house.py");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr))
}

#[test]
fn the_source_keeps_the_house_rules() {
    let (clean, report) = house(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    assert!(clean, "scripts/house.py finds:\n{report}");
}

#[test]
fn a_circle_through_a_reexport_and_a_super_group_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let io = dir.path().join("io");
    std::fs::create_dir_all(&io).unwrap();
    let write = |name: &str, text: &str| std::fs::write(io.join(name), text).unwrap();
    std::fs::write(dir.path().join("lib.rs"), "pub mod io;\n").unwrap();
    write("mod.rs", "pub mod reader;\npub mod restart;\npub mod results;\npub use results::HistoryRow;\n");
    write("results.rs", "pub struct HistoryRow;\npub fn f() { crate::io::restart::g(); }\n");
    write("restart.rs", "use super::{reader::{self, read}};\npub fn g() { read(); }\n");
    write("reader.rs", "use super::HistoryRow;\npub fn read() {}\n");
    let (clean, report) = house(dir.path());
    assert!(!clean, "{report}");
    assert!(report.contains("(3) io::reader, io::restart, io::results"), "{report}");
    // the same tree with the reader naming the row where it is defined: no circle through io/mod.rs
    write("reader.rs", "pub fn read() {}\n");
    let (clean, report) = house(dir.path());
    assert!(clean, "{report}");
}
