//! The manual says what the program does: the history columns docs/results.md names exist in a
//! results file (it named `contact_PAIR_normal_force` where the file has `contact_PAIR_force`),
//! and the quick joint's time is one figure in the README, docs/bellows.md and `--help` (the
//! help said "about a minute", the README "about 6 s"; measured 3.9 s on 2 ranks, with start-up).

mod common;
use common::{command_in, run_deck};

fn manual(name: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(name)).unwrap()
}

#[test]
fn the_documented_contact_history_columns_are_in_the_file() {
    let fit = manual("examples/shrink_fit.toml");
    let run = run_deck(&fit, &[], 1, &[]);
    run.assert_ok();
    let columns: Vec<String> = hdf5::File::open(&run.h5).unwrap().group("history").unwrap().member_names().unwrap();
    let pair =
        columns.iter().find_map(|c| c.strip_prefix("contact_").and_then(|c| c.strip_suffix("_active_nodes"))).expect("a contact pair's columns").to_string();
    let results = manual("docs/results.md");
    let documented: Vec<String> = results
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.starts_with("contact_PAIR_"))
        .map(|w| w.replace("PAIR", &pair))
        .collect();
    assert!(documented.len() >= 4, "{documented:?}");
    for name in &documented {
        assert!(columns.contains(name), "docs/results.md names {name}, the file has {columns:?}");
    }
}

#[test]
fn the_quick_joint_takes_one_stated_time() {
    let dir = tempfile::tempdir().unwrap();
    let help = command_in(dir.path(), 1).args(["bellows", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout).to_string();
    let stated = "about 5 s";
    let quick = help.lines().skip_while(|l| !l.contains("--quick")).take(3).collect::<Vec<_>>().join(" ");
    assert!(quick.contains(stated), "--help: {quick}");
    assert!(manual("README.md").contains(&format!("coarse mesh in {stated}")), "README");
    assert!(manual("docs/bellows.md").contains(&format!("({stated} on 2 ranks)")), "docs/bellows.md");
}

/// The README's verdict table is what `slideline bellows --spec examples/dn200_joint.toml
/// --check-only` prints, line for line.
#[test]
fn the_readme_verdict_table_is_the_programs() {
    let readme = manual("README.md");
    let block = readme.split("```text\n").find(|b| b.contains("code check: ASME VIII-1")).expect("a verdict table in the README");
    let block = &block[..block.find("```").unwrap()];
    let dir = tempfile::tempdir().unwrap();
    let spec = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/dn200_joint.toml");
    let out = command_in(dir.path(), 1).args(["bellows", "--spec", spec.to_str().unwrap(), "--check-only"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(String::from_utf8_lossy(&out.stdout), block, "the README's table against the program's");
}
