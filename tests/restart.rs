//! Restart: a run continued from an increment of its results file equals the uninterrupted run
//! bit for bit from there on (history and every field, the restart state included), on 1 and
//! on 2 ranks, after a SIGKILL too; it may continue with a deck that adds a step; and it is
//! refused, with a clear message, for a different mesh, a file without the state and its own
//! file as output.
//!
//! Case: the quick bellows compressed 20 mm in 10 increments (step 1 heats and pressurises,
//! step 2 compresses: 12 increments in all). On 2 ranks the linear solves go through PETSc's
//! redundant LU (each rank factors the whole matrix, sequentially): MUMPS's parallel
//! factorisation adds the ranks' contributions in message arrival order, so two uninterrupted
//! 2-rank runs with it may differ in the last bits (1.3e-11 of a contact force at this case's
//! last increment with the test suite loading the machine), and a continuation cannot be more
//! repeatable than the run it continues. Everything the restart carries per rank (partition,
//! history slabs, contact pattern, multipliers) is still distributed.

mod common;
use common::{assert_continues, command_in, Results, PLASTIC_STEEL};
use std::path::Path;
use std::process::Output;

const BELLOWS: [&str; 6] = ["--quick", "--displacement", "20", "--increments", "10", "--quiet"];

fn bellows(dir: &Path, ranks: usize, extra: &[&str]) -> Output {
    command_in(dir, ranks).current_dir(dir).arg("bellows").args(BELLOWS).args(extra).output().unwrap()
}

/// `slideline bellows --restart FILE ...`: the file's own joint (its parameters).
fn bellows_restart(dir: &Path, ranks: usize, file: &str, extra: &[&str]) -> Output {
    command_in(dir, ranks).current_dir(dir).args(["bellows", "--quiet", "--restart", file]).args(extra).output().unwrap()
}

fn ok(out: Output) -> Output {
    assert!(out.status.success(), "{}\n{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    out
}

/// PETSc options that make the linear solves repeatable on `ranks` ranks (see above).
fn repeatable_solver(ranks: usize) -> Vec<&'static str> {
    if ranks > 1 {
        vec!["--", "-ksp_type", "preonly", "-pc_type", "redundant", "-redundant_pc_type", "lu"]
    } else {
        Vec::new()
    }
}

fn bit_identical_continuation(ranks: usize) {
    let dir = tempfile::tempdir().unwrap();
    let solver = repeatable_solver(ranks);
    ok(bellows(dir.path(), ranks, &[&["-o", "full.h5"][..], &solver].concat()));
    // mid-step, and at the end of step 1 (the next step's loads start from the file's state)
    for from in [6, 1] {
        let name = format!("from{from}.h5");
        let increment = from.to_string();
        let out = ok(bellows_restart(dir.path(), ranks, "full.h5", &[&["--increment", increment.as_str(), "-o", &name][..], &solver].concat()));
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("end reaction"), "the continued run reports as the full one");
        // the report counts the whole file and says what this run added (it said "12
        // increments in 0.9 s", the restart's time beside the whole history's count)
        let added = 12 - from;
        assert!(text.contains(&format!("done: 12 increments, {added} of them in this run")) && text.contains(&format!("continuing #{from}")), "{text}");
        assert!(text.contains(&format!("a restart from #{from}: this run's increments, s")) && text.contains(&format!("{added} in ")), "{text}");
        let wall = Results::open(&dir.path().join(&name)).history("wall_time");
        let full_wall = Results::open(&dir.path().join("full.h5")).history("wall_time");
        assert!(wall[from] >= full_wall[from - 1], "the increments' clock goes on from the file's: {wall:?}");
        assert_continues(&dir.path().join("full.h5"), &dir.path().join(&name), from);
    }
}

#[test]
fn continuation_is_bit_identical_on_one_rank() {
    bit_identical_continuation(1);
}

#[test]
fn continuation_is_bit_identical_on_two_ranks() {
    bit_identical_continuation(2);
}

/// The extrapolation predictor starts each increment from the one before: a restart takes that
/// one's displacement from the file, from the file a continued run continues (a restart of a
/// restart), or, where the fields of every N-th increment only are written, from the state.
#[test]
fn a_restart_of_a_restart_and_one_from_sparse_output_are_bit_identical() {
    let dir = tempfile::tempdir().unwrap();
    ok(bellows(dir.path(), 1, &["-o", "full.h5"]));
    ok(bellows_restart(dir.path(), 1, "full.h5", &["--increment", "6", "-o", "from6.h5"]));
    // increment 7's predecessor, 6, is in full.h5 only
    ok(bellows_restart(dir.path(), 1, "from6.h5", &["--increment", "7", "-o", "from7.h5"]));
    assert_continues(&dir.path().join("full.h5"), &dir.path().join("from7.h5"), 7);
    // fields of every 3rd increment: 9's predecessor is in no file, its state keeps the increment
    ok(bellows(dir.path(), 1, &["--output-every", "3", "-o", "sparse.h5"]));
    let f = hdf5::File::open(dir.path().join("sparse.h5")).unwrap();
    assert!(f.link_exists("increments/000009/state/predictor_increment"), "the state keeps what the field of 8 would have given");
    assert!(!f.link_exists("increments/000003/state/predictor_increment"), "not at a step's first increment (from the step's start)");
    ok(bellows_restart(dir.path(), 1, "sparse.h5", &["--increment", "9", "-o", "from9.h5"]));
    assert_continues(&dir.path().join("sparse.h5"), &dir.path().join("from9.h5"), 9);
}

#[test]
fn a_killed_run_continues_from_its_last_complete_increment() {
    let dir = tempfile::tempdir().unwrap();
    ok(bellows(dir.path(), 1, &["-o", "full.h5"]));
    let mut child = command_in(dir.path(), 1).current_dir(dir.path()).arg("bellows").args(BELLOWS).args(["-o", "killed.h5"]).spawn().unwrap();
    // kill it once the status file shows a few increments of step 2 converged
    let status = dir.path().join("killed.sta");
    let started = std::time::Instant::now();
    loop {
        let rows = std::fs::read_to_string(&status).map(|t| t.lines().filter(|l| l.trim_start().starts_with(char::is_numeric)).count()).unwrap_or(0);
        if rows >= 4 {
            break;
        }
        assert!(child.try_wait().unwrap().is_none(), "the run ended before it could be killed");
        assert!(started.elapsed().as_secs() < 300, "no progress in the status file");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let held = slideline_increments(&dir.path().join("killed.h5"));
    assert!((4..12).contains(&held), "killed after {held} increments");
    ok(bellows_restart(dir.path(), 1, "killed.h5", &["-o", "continued.h5"]));
    assert_continues(&dir.path().join("full.h5"), &dir.path().join("continued.h5"), held);
}

/// Complete increments of a results file (as `slideline post` counts them).
fn slideline_increments(path: &Path) -> usize {
    let f = hdf5::File::open(path).unwrap();
    let g = f.group("increments").unwrap();
    g.member_names().unwrap().iter().filter(|n| g.group(n).unwrap().attr("complete").is_ok()).count()
}

fn plastic_cylinder() -> String {
    format!(
        r#"[mesh]
rectangle = {{ r = [100.0, 130.0], z = [0.0, 1.0], divisions = [8, 1] }}
{PLASTIC_STEEL}[[step]]
name = "load"
increments = 6
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = 0.0 }} ]
pressure = [ {{ surface = "inner", value = 84.0 }} ]
"#
    )
}

const UNLOAD: &str = r#"[[step]]
name = "unload"
increments = 3
pressure = [ { surface = "inner", value = 0.0 } ]
"#;

#[test]
fn a_continued_run_may_add_a_step_and_equals_the_run_of_the_longer_deck() {
    let dir = tempfile::tempdir().unwrap();
    let (short, long) = (dir.path().join("load.toml"), dir.path().join("cycle.toml"));
    std::fs::write(&short, plastic_cylinder()).unwrap();
    std::fs::write(&long, format!("{}{UNLOAD}", plastic_cylinder())).unwrap();
    let run = |args: &[&str]| ok(command_in(dir.path(), 1).current_dir(dir.path()).arg("run").args(args).arg("--quiet").output().unwrap());
    run(&[long.to_str().unwrap(), "-o", "cycle.h5"]);
    run(&[short.to_str().unwrap(), "-o", "load.h5"]);
    run(&[long.to_str().unwrap(), "--restart", "load.h5", "-o", "unload.h5"]);
    // the load step left plastic strain to carry over, and the unloading kept it
    let b = Results::open(&dir.path().join("unload.h5"));
    assert!(b.history("max_equivalent_plastic_strain").last().copied().unwrap() > 1e-4);
    assert_continues(&dir.path().join("cycle.h5"), &dir.path().join("unload.h5"), 6);
}

fn refused(out: Output, needle: &str) {
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(text.contains(needle), "{needle:?} not in: {text}");
    assert!(!text.contains("panicked") && text.lines().filter(|l| !l.trim().is_empty()).count() <= 2, "one clear message: {text}");
}

#[test]
fn restarts_that_cannot_continue_the_run_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    ok(bellows(dir.path(), 1, &["-o", "full.h5"]));
    // another mesh: the ply elements' length changed
    refused(bellows_restart(dir.path(), 1, "full.h5", &["--ply-element-length", "1.5", "-o", "other.h5"]), "cannot restart from full.h5: its mesh has");
    // an increment the file does not hold
    refused(
        bellows_restart(dir.path(), 1, "full.h5", &["--increment", "40", "-o", "other.h5"]),
        "increment 40 is not among its 12 restartable increments (1 .. 12",
    );
    // into itself
    refused(bellows_restart(dir.path(), 1, "full.h5", &["-o", "full.h5"]), "into itself");
    // a file without the state (as an older slideline wrote it)
    std::fs::copy(dir.path().join("full.h5"), dir.path().join("stateless.h5")).unwrap();
    {
        let f = hdf5::File::open_rw(dir.path().join("stateless.h5")).unwrap();
        for name in f.group("increments").unwrap().member_names().unwrap() {
            f.group(&format!("increments/{name}")).unwrap().unlink("state").unwrap();
        }
    }
    refused(bellows_restart(dir.path(), 1, "stateless.h5", &["-o", "other.h5"]), "holds no increment with a restart state");
    // a deck whose steps differ from the file's
    let deck = dir.path().join("deck.toml");
    std::fs::write(&deck, plastic_cylinder()).unwrap();
    let out =
        command_in(dir.path(), 1).current_dir(dir.path()).args(["run", deck.to_str().unwrap(), "--restart", "full.h5", "-o", "other.h5"]).output().unwrap();
    refused(out, "cannot restart from full.h5: its mesh has");
}

#[test]
fn a_finished_compression_carried_on_with_a_cycle_equals_the_cycle_run() {
    // `bellows --restart FILE --cycle`: the file's joint with a return step added, continued
    // from the end of the compression; the same as running the cycle at once
    let dir = tempfile::tempdir().unwrap();
    let compressed = ok(bellows(dir.path(), 1, &["-o", "compressed.h5"]));
    let cycle = ok(bellows(dir.path(), 1, &["--cycle", "-o", "cycle.h5"]));
    let carried = ok(bellows_restart(dir.path(), 1, "compressed.h5", &["--cycle", "-o", "carried.h5"]));
    let held = Results::open(&dir.path().join("compressed.h5")).history("step").len();
    assert_continues(&dir.path().join("cycle.h5"), &dir.path().join("carried.h5"), held);
    // the closing table's rows at the stroke are read at the stroke (#12: the fields of the
    // file the restart continues), not at the cycle's end, and say so
    let rows = |out: &Output| -> Vec<String> {
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter(|l| l.contains("max von Mises") || l.contains("max equivalent plastic strain"))
            .map(str::to_string)
            .collect()
    };
    let at_stroke = rows(&compressed);
    assert_eq!(at_stroke.len(), 2, "{at_stroke:?}");
    assert!(at_stroke[0].contains(&format!("at 20.0 mm (#{held})")), "{at_stroke:?}");
    assert_eq!(rows(&carried), at_stroke, "the carried-on cycle's rows");
    assert_eq!(rows(&cycle), at_stroke, "the cycle run's rows");
}

/// A restart reads nothing it has not checked: a state corrupted in any of these ways is refused
/// with exit 2 and one line naming the dataset, never a panic, a loop or a run from a wrong
/// state. Seen failing before: a slip reference on an edge that does not exist panicked (in
/// the contact evaluation), a displacement with rows missing panicked or was read as valid, a
/// Gauss point index out of range was read, NaN displacements and a negative next increment
/// exit 3 after the first attempt, a next increment of 0 looped forever.
#[test]
fn a_corrupt_restart_state_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let deck = common::pushed_fit_deck(2.0e-4, 4, "friction = 0.2", r#"{ set = "tube_bottom", uz = 0.0 }, { set = "tube_top", uz = 0.0 }"#)
        .replace("poissons_ratio = 0.3\n", "poissons_ratio = 0.3\nmodel = \"j2\"\nyield_stress = 20.0\nhardening_modulus = 1000.0\n");
    std::fs::write(dir.path().join("fit.toml"), &deck).unwrap();
    let run = |args: &[&str]| command_in(dir.path(), 1).current_dir(dir.path()).arg("run").arg("fit.toml").args(args).output().unwrap();
    ok(run(&["-o", "good.h5", "-q"]));
    type Corruption = fn(&hdf5::Group);
    let cases: [(&str, Corruption, &str); 6] = [
        (
            "slip edge",
            |g| {
                let ds = g.dataset("state/slip_pass0").unwrap();
                let mut v = ds.read_raw::<f64>().unwrap();
                v[0] = 1.0e6;
                ds.write_raw(&v).unwrap();
            },
            "slip_pass0",
        ),
        (
            "rows missing",
            |g| {
                let u = g.dataset("nodal/displacement").unwrap().read_raw::<f64>().unwrap();
                g.unlink("nodal/displacement").unwrap();
                g.new_dataset::<f64>().shape([u.len() / 3 - 3, 3]).create("nodal/displacement").unwrap().write_raw(&u[..u.len() - 9]).unwrap();
            },
            "displacement has",
        ),
        (
            "NaN displacement",
            |g| {
                let ds = g.dataset("nodal/displacement").unwrap();
                let mut v = ds.read_raw::<f64>().unwrap();
                v[3] = f64::NAN;
                ds.write_raw(&v).unwrap();
            },
            "displacement is not finite",
        ),
        (
            "Gauss point index",
            |g| {
                let ds = g.dataset("state/plastic_points").unwrap();
                let mut v = ds.read_raw::<u64>().unwrap();
                v[1] = 12;
                ds.write_raw(&v).unwrap();
            },
            "plastic_points",
        ),
        ("zero next increment", |g| g.group("state").unwrap().attr("next_increment_size").unwrap().write_scalar(&0.0f64).unwrap(), "next_increment_size is 0"),
        (
            "negative next increment",
            |g| g.group("state").unwrap().attr("next_increment_size").unwrap().write_scalar(&-0.25f64).unwrap(),
            "next_increment_size is -0.25",
        ),
    ];
    for (what, corrupt, needle) in cases {
        std::fs::copy(dir.path().join("good.h5"), dir.path().join("bad.h5")).unwrap();
        {
            let file = hdf5::File::open_rw(dir.path().join("bad.h5")).unwrap();
            corrupt(&file.group("increments/000005").unwrap());
        }
        let out = run(&["--restart", "bad.h5", "-o", "again.h5", "-q"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{what}: {err}");
        assert!(err.contains(needle) && err.contains("cannot restart from") && err.lines().filter(|l| l.starts_with("error:")).count() == 1, "{what}: {err}");
        assert!(!err.contains("panicked"), "{what}: {err}");
    }
}

/// A file whose writer was killed before the data it had announced reached the disk (the
/// superblock's end-of-file mark past the file's end: HDF5 refuses it as a "truncated file",
/// seen in 1 of 78 SIGKILLs of a rank): post and a restart repair it as `h5clear` does, with a
/// note, and read the increments completed before. Seen failing before: "truncated file".
#[test]
fn a_file_left_truncated_by_a_killed_writer_is_repaired_and_read() {
    let dir = tempfile::tempdir().unwrap();
    ok(bellows(dir.path(), 1, &["-o", "full.h5"]));
    let h5 = dir.path().join("full.h5");
    let size = std::fs::metadata(&h5).unwrap().len();
    std::fs::OpenOptions::new().write(true).open(&h5).unwrap().set_len(size - 100_000).unwrap();
    let out = command_in(dir.path(), 1).arg("post").arg(&h5).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.contains("repaired with h5clear"), "{err}");
    let continued = ok(bellows_restart(dir.path(), 1, "full.h5", &["-o", "more.h5"]));
    assert!(String::from_utf8_lossy(&continued.stdout).contains("end reaction"));
}

/// A writer killed while it flushed an increment can leave metadata past the end of
/// allocation its superblock records (reproduced: 1 of 30 SIGKILLs of rank 0 timed into the
/// file's writes; reading the increments fails with "addr overflow"). Made here by setting a
/// finished file's mark (superblock version 0, bytes 40..48) short of its last increments:
/// with the run's lock left by a process that is gone, post and a restart repair the file as
/// `h5clear --increment=0` does, with a note, and read every increment; with the lock of a live
/// process (a run that may still be writing) the file is not touched and post says a run is
/// still writing it (not that one stopped). Seen failing before: "addr overflow" from post;
/// then "were not completely written (the run stopped while writing them)" for a live run.
#[test]
fn a_file_whose_allocation_mark_a_killed_writer_left_short_is_repaired_and_read() {
    let dir = tempfile::tempdir().unwrap();
    ok(bellows(dir.path(), 1, &["-o", "full.h5"]));
    let h5 = dir.path().join("full.h5");
    let increments = slideline_increments(&h5);
    let mut bytes = std::fs::read(&h5).unwrap();
    assert_eq!(bytes[8], 0, "superblock version");
    let eoa = u64::from_le_bytes(bytes[40..48].try_into().unwrap());
    assert_eq!(eoa, bytes.len() as u64, "a finished file ends at its mark");
    bytes[40..48].copy_from_slice(&(eoa / 2).to_le_bytes());
    std::fs::write(&h5, &bytes).unwrap();
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap().trim().to_string();
    let lock = dir.path().join("full.lock");
    let post = || command_in(dir.path(), 1).arg("post").arg(&h5).output().unwrap();
    // a live process's lock: the file is left as it is; its links read (one object header),
    // the increments past the mark do not
    std::fs::write(&lock, format!("host {host} pid {}\n", std::process::id())).unwrap();
    let out = post();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !err.contains("repaired") && err.contains("a run is still writing this file"), "{err}");
    assert!(!err.contains("the run stopped"), "a live run's file is called a stopped run's: {err}");
    assert_eq!(std::fs::read(&h5).unwrap()[40..48], (eoa / 2).to_le_bytes(), "a file a run may be writing was changed");
    // the lock of a process that is gone: repaired, every increment read
    let gone = std::process::Command::new("true").spawn().unwrap();
    let pid = gone.id();
    gone.wait_with_output().unwrap();
    std::fs::write(&lock, format!("host {host} pid {pid}\n")).unwrap();
    let out = post();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.contains("end-of-allocation mark set"), "{err}");
    assert_eq!(slideline_increments(&h5), increments);
    let continued = ok(bellows_restart(dir.path(), 1, "full.h5", &["--increment", "5", "-o", "more.h5"]));
    assert!(String::from_utf8_lossy(&continued.stdout).contains("end reaction"));
}

/// The increments' links sit in one piece of metadata that each flush writes whole: the
/// group of the newer format (compact links, creation order tracked) with an object header
/// sized for 2048 of them at once. The older symbol table (a local heap and a B-tree of nodes
/// that split every few increments) was found torn by SIGKILLs timed into the writes: "bad heap
/// free list" (the heap's header and block from two flushes), and the links of increments 5 to
/// 9 lost (a B-tree node pointing at a symbol node never written). h5py reads the group as
/// before. Seen failing before: a 40-byte header (a symbol table message).
#[test]
fn the_increments_links_are_held_in_one_object_header() {
    let dir = tempfile::tempdir().unwrap();
    ok(bellows(dir.path(), 2, &["-o", "links.h5"]));
    let script = "import h5py, sys\n\
f = h5py.File(sys.argv[1], 'r'); g = f['increments']\n\
info = h5py.h5o.get_info(g.id)\n\
print(len(g), info.hdr.space.total, sorted(g) == list(g), g.id.get_create_plist().get_link_creation_order())\n";
    let out = common::python().arg("-c").arg(script).arg(dir.path().join("links.h5")).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    let words: Vec<&str> = text.split_whitespace().collect();
    assert!(out.status.success() && words.len() == 4, "{text} {}", String::from_utf8_lossy(&out.stderr));
    let (links, header): (usize, usize) = (words[0].parse().unwrap(), words[1].parse().unwrap());
    assert!(links >= 10, "{links} increments");
    assert!(header >= 2048 * 32, "the increments' object header holds {header} bytes");
    assert_eq!(words[2], "True", "h5py lists the increments in order");
    assert_ne!(words[3], "0", "the links' creation order is tracked (the newer group format)");
}

/// A restart continues the same problem (Abaqus's rule): restarting the plastic cylinder from
/// increment 3 of its load step with that step's pressure changed (84 -> 90 MPa) or with the
/// material's yield stress changed is refused (exit 2, naming what changed); changing the
/// unload step, not begun at increment 3, is allowed, and the continued file says which deck
/// each increment ran under.
#[test]
fn a_restart_may_change_only_the_steps_not_yet_begun() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: String| {
        std::fs::write(dir.path().join(name), text).unwrap();
        name.to_string()
    };
    let run = |args: &[&str]| command_in(dir.path(), 1).current_dir(dir.path()).arg("run").args(args).arg("--quiet").output().unwrap();
    let deck = write("cycle.toml", format!("{}{UNLOAD}", plastic_cylinder()));
    ok(run(&[&deck, "-o", "cycle.h5"]));
    let more = write("more.toml", format!("{}{}", plastic_cylinder().replace("value = 84.0", "value = 90.0"), UNLOAD));
    refused(
        run(&[&more, "--restart", "cycle.h5", "--increment", "3", "-o", "more.h5"]),
        "the deck changes step 1 pressures of the run it continues (increment 3 is in step 1)",
    );
    let softer = write("softer.toml", format!("{}{UNLOAD}", plastic_cylinder().replace("yield_stress = 300.0", "yield_stress = 250.0")));
    assert_ne!(
        std::fs::read_to_string(dir.path().join(&softer)).unwrap(),
        std::fs::read_to_string(dir.path().join(&deck)).unwrap(),
        "the material did not change"
    );
    refused(run(&[&softer, "--restart", "cycle.h5", "--increment", "3", "-o", "softer.h5"]), "the deck changes materials of the run it continues");
    // the unload step is not begun at increment 3: it may change
    let later = write("later.toml", format!("{}{}", plastic_cylinder(), UNLOAD.replace("increments = 3", "increments = 4")));
    ok(run(&[&later, "--restart", "cycle.h5", "--increment", "3", "-o", "later.h5"]));
    let f = hdf5::File::open(dir.path().join("later.h5")).unwrap();
    let decks: hdf5::types::VarLenUnicode = f.attr("deck_of_increments").unwrap().read_scalar().unwrap();
    assert!(
        decks.as_str().starts_with("increments 1 to 3: the deck of cycle.h5") && decks.as_str().ends_with("from 4: this file's deck"),
        "{}",
        decks.as_str()
    );
    // but once in the unload step, it may not
    refused(run(&[&later, "--restart", "cycle.h5", "--increment", "7", "-o", "late.h5"]), "the deck changes step 2 increments");
}

/// Kinematic hardening's backstresses are part of the restart state: the plastic cylinder with
/// two Armstrong-Frederick terms, loaded past yield, then taken to suction so that its bore
/// yields in reverse, continued from increment 8 (inside the reversal) equals the whole run
/// bit for bit. The state there holds backstresses (nonzero, `backstress_state`); a
/// continuation that lost them would yield in reverse at another load.
#[test]
fn backstresses_carry_over_a_restart_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let deck = plastic_cylinder()
        .replace("hardening_modulus = 1000.0\n", "hardening_modulus = 0.0\nbackstresses = [ { modulus = 20000.0, recall = 100.0 }, { modulus = 5000.0 } ]\n")
        + "[[step]]\nname = \"suction\"\nincrements = 4\npressure = [ { surface = \"inner\", value = -75.0 } ]\n";
    assert!(deck.contains("backstresses"));
    std::fs::write(dir.path().join("cycle.toml"), deck).unwrap();
    let run = |args: &[&str]| ok(command_in(dir.path(), 1).current_dir(dir.path()).arg("run").arg("cycle.toml").args(args).arg("--quiet").output().unwrap());
    run(&["-o", "cycle.h5"]);
    run(&["--restart", "cycle.h5", "--increment", "8", "-o", "rest.h5"]);
    let f = hdf5::File::open(dir.path().join("cycle.h5")).unwrap();
    let back = f.dataset("increments/000008/state/backstress_state").unwrap();
    assert_eq!(back.shape()[1], 13);
    let values = back.read_raw::<f64>().unwrap();
    assert!(values.iter().any(|v| v.abs() > 1.0), "backstresses of some MPa expected at increment 8");
    // the bore flowed again in the suction step: the equivalent plastic strain grew after 6
    let ep = Results::open(&dir.path().join("cycle.h5")).history("max_equivalent_plastic_strain");
    assert!(ep[9] > ep[5] * 1.01, "reverse yield expected in the suction step: {ep:?}");
    assert_continues(&dir.path().join("cycle.h5"), &dir.path().join("rest.h5"), 8);
}
