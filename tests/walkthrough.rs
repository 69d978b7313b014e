//! The README's walk-through runs as written: every command of its first shell block, from a
//! copy of the repository's examples, with the built binary for `target/release/slideline`;
//! each must succeed, and the files it names must appear. The fit's contact pressure is the
//! README's: 5.44 MPa at every slave node after the fit, 31.4 MPa with the bore pressure.

mod common;
use common::{command_in, Results};
use std::path::Path;

#[test]
fn the_readme_walk_through_runs_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let section = readme.split("## Walk-through").nth(1).expect("a walk-through section");
    let block = section.split("```sh\n").nth(1).and_then(|b| b.split("```").next()).expect("its shell block");
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("examples")).unwrap();
    std::fs::copy(root.join("examples/shrink_fit.toml"), dir.path().join("examples/shrink_fit.toml")).unwrap();
    let mut commands = 0;
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let command = line.split('#').next().unwrap().trim();
        let words: Vec<&str> = command.split_whitespace().collect();
        let (ranks, args) = match words.as_slice() {
            ["mpirun", "-n", n, "target/release/slideline", rest @ ..] => (n.parse().unwrap(), rest.to_vec()),
            ["target/release/slideline", rest @ ..] => (1, rest.to_vec()),
            _ => panic!("a walk-through line this test cannot run: {line}"),
        };
        let out = command_in(dir.path(), ranks).current_dir(dir.path()).args(&args).output().unwrap();
        assert!(out.status.success(), "{command}:\n{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        commands += 1;
    }
    assert_eq!(commands, 8, "{block}");
    for file in ["fit.h5", "fit.xmf", "fit.sta", "fit.csv", "fit_force.png"] {
        assert!(dir.path().join(file).exists(), "{file} was not written");
    }
    let res = Results::open(&dir.path().join("fit.h5"));
    for (increment, expected) in [("000002", 5.44), ("000005", 31.4)] {
        let p = res.f64s(&format!("increments/{increment}/contact/fit/pass0/pressure"));
        assert!(p.iter().all(|v| (v - expected).abs() < 0.005 * expected), "increment {increment}: {p:?}");
    }
}
