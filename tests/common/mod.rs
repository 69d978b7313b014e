//! Helpers shared by the integration tests: run the built binary (optionally under
//! `mpirun -n 2`) on a deck written to a temporary directory, and read the results file.
#![allow(dead_code)]

use hdf5::types::TypeDescriptor;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub struct Run {
    pub dir: tempfile::TempDir,
    pub output: Output,
    pub h5: PathBuf,
}

impl Run {
    pub fn stdout(&self) -> String {
        String::from_utf8_lossy(&self.output.stdout).into_owned()
    }
    pub fn stderr(&self) -> String {
        String::from_utf8_lossy(&self.output.stderr).into_owned()
    }
    pub fn code(&self) -> i32 {
        self.output.status.code().unwrap_or(-1)
    }
    /// Panics with the program's output unless it exited 0.
    pub fn assert_ok(&self) -> &Self {
        assert!(self.output.status.success(), "slideline failed ({}):\n{}\n{}", self.code(), self.stdout(), self.stderr());
        self
    }
}

pub fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

/// The seed paper's steel as a deck's only material "steel": J2, E 200 GPa, nu 0.3, yield 300 MPa,
/// linear hardening 1000 MPa.
pub const PLASTIC_STEEL: &str = r#"[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
yield_stress = 300.0
hardening_modulus = 1000.0
"#;

/// `slideline run` flags for the residual convergence test (||F|| down by 1e-10 or to
/// round-off), for tests that check an answer or Newton's convergence rate to round-off; the
/// default field test stops where engineering answers have settled (0.1 % and better).
pub const TIGHT: &[&str] = &["--convergence", "residual"];

/// `slideline run` flags for the fields as computed (64-bit): tests that read a stress,
/// temperature or contact traction from the file to 1e-8 and finer (by default the file keeps
/// them as 32-bit floats, 6e-8 of each value).
pub const DOUBLE: &[&str] = &["--output-precision", "double"];

/// The slideline binary under `mpirun -n ranks` (or alone for one rank), with OpenMPI's session
/// directory under `dir`: concurrently starting OpenMPI 4.1 singletons race to create the
/// shared one in /tmp and fail with "mkdir ... File exists".
/// The Python that has meshio, h5py and numpy: `SLIDELINE_PYTHON` (run.sh sets Debian's
/// /usr/bin/python3, where its packages are installed), else `python3` from PATH.
pub fn python() -> Command {
    Command::new(std::env::var_os("SLIDELINE_PYTHON").unwrap_or_else(|| "python3".into()))
}

pub fn command_in(dir: &Path, ranks: usize) -> Command {
    let mut cmd = command(ranks);
    cmd.env("OMPI_MCA_orte_tmpdir_base", dir);
    cmd
}

fn command(ranks: usize) -> Command {
    let exe = env!("CARGO_BIN_EXE_slideline");
    let mut cmd = if ranks > 1 {
        // a hang (ranks waiting in different collectives) fails the test instead of CI
        let mut c = Command::new("timeout");
        c.args(["600", "mpirun", "-n", &ranks.to_string(), "--oversubscribe", exe]);
        c
    } else {
        Command::new(exe)
    };
    cmd.env("OMPI_ALLOW_RUN_AS_ROOT", "1").env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1").env("OPENBLAS_NUM_THREADS", "1");
    cmd
}

/// Writes `deck` (with `files` beside it) into a fresh directory and runs
/// `slideline run deck.toml -o out.h5 [extra...]` on `ranks` ranks.
pub fn run_deck(deck: &str, files: &[(&str, &Path)], ranks: usize, extra: &[&str]) -> Run {
    run_deck_file("deck.toml", deck, files, ranks, extra)
}

/// [`run_deck`] with the deck written as `name` (`deck.inp` for a CalculiX deck).
pub fn run_deck_file(name: &str, deck: &str, files: &[(&str, &Path)], ranks: usize, extra: &[&str]) -> Run {
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, src) in files {
        std::fs::copy(src, dir.path().join(name)).expect("copy test file");
    }
    let deck_path = dir.path().join(name);
    std::fs::write(&deck_path, deck).expect("write deck");
    let h5 = dir.path().join("out.h5");
    let output = command_in(dir.path(), ranks).arg("run").arg(&deck_path).arg("-o").arg(&h5).arg("--quiet").args(extra).output().expect("run slideline");
    Run { dir, output, h5 }
}

/// The results of a finished run, read back with the hdf5 crate.
pub struct Results {
    pub file: hdf5::File,
}

impl Results {
    pub fn open(path: &Path) -> Self {
        Results { file: hdf5::File::open(path).expect("open results") }
    }
    pub fn f64s(&self, name: &str) -> Vec<f64> {
        self.file.dataset(name).unwrap_or_else(|e| panic!("{name}: {e}")).read_raw::<f64>().unwrap()
    }
    pub fn u64s(&self, name: &str) -> Vec<u64> {
        self.file.dataset(name).unwrap_or_else(|e| panic!("{name}: {e}")).read_raw::<u64>().unwrap()
    }
    pub fn u8s(&self, name: &str) -> Vec<u8> {
        self.file.dataset(name).unwrap_or_else(|e| panic!("{name}: {e}")).read_raw::<u8>().unwrap()
    }
    pub fn i64s(&self, name: &str) -> Vec<i64> {
        self.file.dataset(name).unwrap_or_else(|e| panic!("{name}: {e}")).read_raw::<i64>().unwrap()
    }
    /// (u_r, u_z) of every node at increment group `inc` ("increments/NNNNNN"), flattened.
    pub fn displacement(&self, inc: &str) -> Vec<f64> {
        self.f64s(&format!("{inc}/nodal/displacement")).chunks(3).flat_map(|u| [u[0], u[1]]).collect()
    }
    pub fn last_increment(&self) -> String {
        let names = self.file.group("increments").unwrap().member_names().unwrap();
        format!("increments/{}", names.iter().max().expect("at least one increment"))
    }
    /// (r, z) coordinates and (u_r, u_z) of every node at the last increment.
    pub fn nodes(&self) -> Vec<([f64; 2], [f64; 2])> {
        let x = self.f64s("mesh/coordinates");
        let u = self.displacement(&self.last_increment());
        x.chunks(2).zip(u.chunks(2)).map(|(x, u)| ([x[0], x[1]], [u[0], u[1]])).collect()
    }
}

impl Results {
    /// History column `name` (one value per converged increment).
    pub fn history(&self, name: &str) -> Vec<f64> {
        self.f64s(&format!("history/{name}"))
    }

    /// Stress component `component` ([rr, zz, tt, rz]) at radius `r0` on a mesh of the
    /// structured block generator, extrapolated from the Gauss points of the element whose
    /// first corner lies at `r0`: quadratic Lagrange through the three points of its middle
    /// Gauss row (xi = -sqrt(3/5), 0, sqrt(3/5)) evaluated at xi = -1.
    pub fn stress_at_inner_edge(&self, increment: &str, r0: f64, component: usize) -> f64 {
        let stress = self.f64s(&format!("{increment}/stress"));
        let conn = self.i64s("mesh/connectivity");
        let coords = self.f64s("mesh/coordinates");
        let e = (0..conn.len() / 8).find(|&e| (coords[2 * conn[8 * e] as usize] - r0).abs() < 1e-9).expect("an element at r0");
        let g = 0.6f64.sqrt();
        let pts = [-g, 0.0, g];
        let mut value = 0.0;
        for i in 0..3 {
            let mut w = 1.0;
            for j in 0..3 {
                if i != j {
                    w *= (-1.0 - pts[j]) / (pts[i] - pts[j]);
                }
            }
            value += w * stress[(e * 9 + 3 + i) * 4 + component];
        }
        value
    }

    /// Sorted increment group paths ("increments/000001", ...).
    pub fn increments(&self) -> Vec<String> {
        let mut names = self.file.group("increments").unwrap().member_names().unwrap();
        names.sort();
        names.into_iter().map(|n| format!("increments/{n}")).collect()
    }
}

impl Results {
    /// Final displacement of every node by its external id.
    pub fn displacement_by_node_id(&self) -> std::collections::HashMap<u64, [f64; 2]> {
        self.u64s("mesh/node_ids").into_iter().zip(self.nodes().into_iter().map(|(_, u)| u)).collect()
    }
}

/// Largest difference between two runs' final displacements (by node id), and the largest
/// displacement of the first (the scale for a relative comparison).
pub fn displacement_difference(a: &Results, b: &Results) -> (f64, f64) {
    let (ua, ub) = (a.displacement_by_node_id(), b.displacement_by_node_id());
    assert_eq!(ua.len(), ub.len(), "the runs have different meshes");
    let scale = ua.values().fold(0.0f64, |m, u| m.max(u[0].abs()).max(u[1].abs()));
    let worst = ua.iter().map(|(id, u)| (u[0] - ub[id][0]).abs().max((u[1] - ub[id][1]).abs())).fold(0.0f64, f64::max);
    (worst, scale)
}

/// The ratios ||J - J_fd||_F / ||J||_F that PETSc's -snes_test_jacobian printed.
pub fn jacobian_test_ratios(stdout: &str) -> Vec<f64> {
    stdout
        .lines()
        .filter_map(|l| l.trim().strip_prefix("||J - Jfd||_F/||J||_F = "))
        .map(|rest| rest.split(',').next().unwrap().trim().parse().expect("ratio"))
        .collect()
}

/// Runs `deck` on 1 rank and on 2 ranks (both must succeed) and opens both results.
pub fn run_serial_and_parallel(deck: &str, extra: &[&str]) -> (Run, Results, Run, Results) {
    let serial = run_deck(deck, &[], 1, extra);
    serial.assert_ok();
    let parallel = run_deck(deck, &[], 2, extra);
    parallel.assert_ok();
    let (r1, r2) = (Results::open(&serial.h5), Results::open(&parallel.h5));
    (serial, r1, parallel, r2)
}

/// The shrink-fit compound cylinder (inner tube r 100..110, outer r 109.95..125, 6 x 2 and
/// 9 x 3 Q8, steel, both faces of both tubes held axially) with contact pair "fit" (outer's bore
/// on inner's outside, plus the `contact` lines) fitted in one step of 2 increments, then
/// `more_steps` (TOML `[[step]]` tables).
pub fn shrink_fit_deck(nlgeom: bool, contact: &str, more_steps: &str) -> String {
    format!(
        r#"nlgeom = {nlgeom}
[[mesh.block]]
name = "inner"
r = [100.0, 110.0]
z = [0.0, 4.0]
divisions = [6, 2]
[[mesh.block]]
name = "outer"
r = [109.95, 125.0]
z = [0.0, 4.0]
divisions = [9, 3]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "fit"
slave = "outer_inner"
master = "inner_outer"
{contact}
[[step]]
name = "fit"
increments = 2
boundary = [ {{ set = "inner_bottom", uz = 0.0 }}, {{ set = "inner_top", uz = 0.0 }}, {{ set = "outer_bottom", uz = 0.0 }}, {{ set = "outer_top", uz = 0.0 }} ]
{more_steps}"#
    )
}

/// Bad input: exit code 2 and one `error:` line naming every needle, no panic or PETSc trace.
pub fn assert_rejected(run: &Run, needles: &[&str]) {
    let err = run.stderr();
    assert_eq!(run.code(), 2, "exit code for bad input; stderr:\n{err}");
    for n in needles {
        assert!(err.contains(n), "message should name {n:?}:\n{err}");
    }
    assert_eq!(err.lines().filter(|l| l.starts_with("error:")).count(), 1, "one message:\n{err}");
    assert!(!err.contains("panicked") && !err.contains("PETSC ERROR"), "{err}");
}

/// Every dataset under `group` of `a` and `b`, compared bit for bit (floats by their bits).
pub fn assert_same_datasets(a: &hdf5::Group, b: &hdf5::Group) {
    let names = a.member_names().unwrap();
    assert_eq!(names, b.member_names().unwrap(), "{}: members", a.name());
    for name in names {
        if let Ok(g) = a.group(&name) {
            assert_same_datasets(&g, &b.group(&name).unwrap());
            continue;
        }
        let (x, y) = (a.dataset(&name).unwrap(), b.dataset(&name).unwrap());
        let what = format!("{}/{name}", a.name());
        assert_eq!(x.shape(), y.shape(), "{what}");
        match x.dtype().unwrap().to_descriptor().unwrap() {
            TypeDescriptor::Float(_) => {
                let (p, q) = (x.read_raw::<f64>().unwrap(), y.read_raw::<f64>().unwrap());
                assert!(p.iter().zip(&q).all(|(u, v)| u.to_bits() == v.to_bits()), "{what} differs");
            }
            TypeDescriptor::Unsigned(hdf5::types::IntSize::U1) => assert_eq!(x.read_raw::<u8>().unwrap(), y.read_raw::<u8>().unwrap(), "{what}"),
            TypeDescriptor::Unsigned(_) => assert_eq!(x.read_raw::<u64>().unwrap(), y.read_raw::<u64>().unwrap(), "{what}"),
            other => panic!("{what}: unexpected type {other:?}"),
        }
    }
}

/// `continued` (restarted from increment `from`) holds the uninterrupted run's history (but
/// the wall time) and, from increment from + 1 on, its increments bit for bit.
pub fn assert_continues(full: &Path, continued: &Path, from: usize) {
    let (a, b) = (Results::open(full), Results::open(continued));
    let columns = a.file.group("history").unwrap().member_names().unwrap();
    assert_eq!(columns, b.file.group("history").unwrap().member_names().unwrap());
    for name in columns.iter().filter(|c| *c != "wall_time") {
        let (x, y) = (a.history(name), b.history(name));
        let same = x.len() == y.len() && x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits());
        assert!(same, "history {name}: {x:?} vs {y:?}");
    }
    let later: Vec<String> = a.file.group("increments").unwrap().member_names().unwrap().into_iter().filter(|n| n.parse::<usize>().unwrap() > from).collect();
    assert!(!later.is_empty(), "the run went on after {from}");
    assert_eq!(b.file.group("increments").unwrap().member_names().unwrap(), later, "the continued file holds the increments after the restart");
    for name in &later {
        let g = format!("increments/{name}");
        assert_same_datasets(&a.file.group(&g).unwrap(), &b.file.group(&g).unwrap());
    }
    assert!(b.file.attr("restarted_from").is_ok());
}

/// A ring (r 109.95..125) shrunk on a tube (r 100..110, 0.05 mm interference), both 4 mm
/// long, node-to-segment penalty contact 1e5 with `friction` lines; step 1 fits it with both
/// faces of each held axially (`tube` holds the tube), step 2 pushes the ring's faces by `push`
/// mm in `increments` increments.
pub fn pushed_fit_deck(push: f64, increments: usize, friction: &str, tube: &str) -> String {
    format!(
        r#"[[mesh.block]]
name = "tube"
r = [100.0, 110.0]
z = [0.0, 4.0]
divisions = [6, 4]
[[mesh.block]]
name = "ring"
r = [109.95, 125.0]
z = [0.0, 4.0]
divisions = [9, 4]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "fit"
slave = "ring_inner"
master = "tube_outer"
integration = "node-to-segment"
penalty = 1.0e5
{friction}
[[step]]
name = "fit"
increments = 1
boundary = [ {tube}, {{ set = "ring_bottom", uz = 0.0 }}, {{ set = "ring_top", uz = 0.0 }} ]
[[step]]
name = "push"
increments = {increments}
boundary = [ {{ set = "ring_bottom", uz = {push} }}, {{ set = "ring_top", uz = {push} }} ]
"#
    )
}

/// The contact patch test's deck (tests/contact_patch_test.rs): two stacked blocks on
/// r in [0, 10], lower z in [0, 5] (5 x 2), upper z in [5, 10] (7 x 2), touching through the
/// pair `interface` only, 10 MPa on the upper face; `triangles` splits both meshes into T6.
pub fn patch_test_deck(integration: &str, two_pass: bool, triangles: bool) -> String {
    format!(
        r#"nlgeom = false
[[mesh.block]]
name = "lower"
r = [0.0, 10.0]
z = [0.0, 5.0]
divisions = [5, 2]
triangles = {triangles}
[[mesh.block]]
name = "upper"
r = [0.0, 10.0]
z = [5.0, 10.0]
divisions = [7, 2]
triangles = {triangles}
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "interface"
slave = "upper_bottom"
master = "lower_top"
two_pass = {two_pass}
integration = "{integration}"
penalty = 1.0e6
[[step]]
boundary = [ {{ set = "lower_bottom", uz = 0.0 }}, {{ set = "lower_inner", ur = 0.0 }}, {{ set = "upper_inner", ur = 0.0 }} ]
pressure = [ {{ surface = "upper_top", value = 10.0 }} ]
"#
    )
}

/// A CalculiX deck's mesh of one row of CAX8 elements across a wall r in [a, b], height `h`:
/// `*NODE, NSET=NALL` and `*ELEMENT, TYPE=CAX8, ELSET=WALL` (elements 1..=n along r), and each
/// node's (id, r, z). Three rows of nodes (z = 0, h/2, h), the middle one only at the corners'
/// columns.
pub fn cax8_wall(a: f64, b: f64, elements: usize, h: f64) -> (String, Vec<(u64, f64, f64)>) {
    use std::fmt::Write as _;
    let columns = 2 * elements + 1;
    let id = |row: usize, col: usize| (row * columns + col + 1) as u64;
    let dr = (b - a) / elements as f64;
    let nodes: Vec<(u64, f64, f64)> = (0..3)
        .flat_map(|row| (0..columns).filter(move |c| row != 1 || c % 2 == 0).map(move |col| (row, col)))
        .map(|(row, col)| (id(row, col), a + col as f64 * dr / 2.0, row as f64 * h / 2.0))
        .collect();
    let mut w = String::from("*NODE, NSET=NALL\n");
    for (n, r, z) in &nodes {
        let _ = writeln!(w, "{n}, {r:.12}, {z:.12}");
    }
    w.push_str("*ELEMENT, TYPE=CAX8, ELSET=WALL\n");
    for e in 0..elements {
        let c = 2 * e;
        let slots = [id(0, c), id(0, c + 2), id(2, c + 2), id(2, c), id(0, c + 1), id(1, c + 2), id(2, c + 1), id(1, c)];
        let _ = writeln!(w, "{}, {}", e + 1, slots.map(|n| n.to_string()).join(", "));
    }
    (w, nodes)
}

/// The ids of `nodes` (as [`cax8_wall`] lists them) that `keep` selects by (r, z), joined for
/// a *NSET line.
pub fn node_list(nodes: &[(u64, f64, f64)], keep: impl Fn(f64, f64) -> bool) -> String {
    nodes.iter().filter(|(_, r, z)| keep(*r, *z)).map(|(n, _, _)| n.to_string()).collect::<Vec<_>>().join(", ")
}
