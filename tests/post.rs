//! `slideline post`: on a 2-rank results file (a shrink fit with a contact pair, pushed in a
//! second step) it prints the history exactly as the run printed it, the CSV export reads back
//! to the same numbers, fields and series name their places, and bad input (not an HDF5 file,
//! a file without the results groups, an increment out of range, an unknown field or set)
//! gives one clear message and exit code 2.

mod common;
use common::{command_in, shrink_fit_deck};
use std::path::Path;

/// The shrink fit (penalty 1e5), then the outer tube's top face pushed down 0.01 mm.
fn deck() -> String {
    let push = r#"[[step]]
name = "push"
increments = 3
boundary = [ { set = "inner_bottom", uz = 0.0 }, { set = "inner_top", uz = 0.0 }, { set = "outer_bottom", uz = 0.0 }, { set = "outer_top", uz = -0.01 } ]
"#;
    shrink_fit_deck(true, "penalty = 1e5", push)
}

fn post(dir: &Path, args: &[&str]) -> std::process::Output {
    command_in(dir, 1).arg("post").args(args).output().expect("run slideline post")
}

/// Runs the deck on `ranks` ranks in `dir`: (results path, the run's output).
fn run_fit(dir: &Path, ranks: usize, extra: &[&str]) -> (std::path::PathBuf, std::process::Output) {
    let deck = dir.join("fit.toml");
    std::fs::write(&deck, self::deck()).unwrap();
    let h5 = dir.join("fit.h5");
    let run = command_in(dir, ranks).arg("run").arg(&deck).arg("-o").arg(&h5).args(extra).output().unwrap();
    (h5, run)
}

#[test]
fn post_reproduces_the_run_and_reports_fields() {
    let dir = tempfile::tempdir().unwrap();
    let (h5, run) = run_fit(dir.path(), 2, &[]);
    let printed = String::from_utf8_lossy(&run.stdout).into_owned();
    assert!(run.status.success(), "{printed}{}", String::from_utf8_lossy(&run.stderr));
    let h5s = h5.to_str().unwrap();

    // the history as printed during the run, line for line
    let out = post(dir.path(), &[h5s]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}");
    let run_lines: Vec<&str> = printed.lines().filter(|l| l.starts_with("step ") && l.contains(" inc ")).collect();
    let post_lines: Vec<&str> = text.lines().filter(|l| l.starts_with("step ") && l.contains(" inc ")).collect();
    assert_eq!(run_lines.len(), 5);
    assert_eq!(run_lines, post_lines);
    assert!(text.contains("on 2 rank(s)") && text.contains("5 converged"), "{text}");

    // CSV round trip: every column and value
    let csv = dir.path().join("fit.csv");
    assert!(post(dir.path(), &[h5s, "--csv", csv.to_str().unwrap()]).status.success());
    let table = std::fs::read_to_string(&csv).unwrap();
    // each column named "name [units]", the units the dataset carries
    let named: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let header: Vec<&str> = named.iter().map(|h| h.split(" [").next().unwrap()).collect();
    let file = hdf5::File::open(&h5).unwrap();
    for (k, name) in header.iter().enumerate() {
        let dataset = file.dataset(&format!("history/{name}")).unwrap();
        let units = dataset.attr("units").unwrap().read_scalar::<hdf5::types::VarLenUnicode>().unwrap();
        assert_eq!(named[k], format!("{name} [{units}]"));
        let stored = dataset.read_raw::<f64>().unwrap();
        let read: Vec<f64> = table.lines().skip(1).map(|l| l.split(',').nth(k).unwrap().parse().unwrap()).collect();
        assert_eq!(stored.len(), read.len(), "{name}");
        for (a, b) in stored.iter().zip(&read) {
            assert!(a == b || (a.is_nan() && b.is_nan()), "{name}: {a} vs {b}");
        }
    }
    assert!(header.contains(&"contact_fit_max_penetration") && header.contains(&"reaction_outer_top_z_ring"));
    assert!(named.contains(&"reaction_outer_top_z_ring [N]") && named.contains(&"reaction_outer_top_z [N per radian]"), "{named:?}");
    // the full ring's reaction before the per-radian one
    let place = |name: &str| header.iter().position(|h| *h == name).unwrap();
    assert!(place("reaction_outer_top_z_ring") < place("reaction_outer_top_z"));
    // the prescribed displacement beside its reaction: 0 in the fit, then -0.01 mm x the push's load factor
    let column = |name: &str| -> Vec<f64> { table.lines().skip(1).map(|l| l.split(',').nth(place(name)).unwrap().parse().unwrap()).collect() };
    let (uz, step, lambda) = (column("displacement_outer_top_z"), column("step"), column("load_factor"));
    for k in 0..uz.len() {
        let prescribed = if step[k] == 2.0 { -0.01 * lambda[k] } else { 0.0 };
        assert!((uz[k] - prescribed).abs() < 1e-15, "row {k}: {} against {prescribed}", uz[k]);
    }
    assert_eq!(named[place("displacement_outer_top_z")], "displacement_outer_top_z [mm]");
    // counts are integers
    let first: Vec<&str> = table.lines().nth(1).unwrap().split(',').collect();
    let at = |name: &str| first[header.iter().position(|h| *h == name).unwrap()];
    assert_eq!((at("step"), at("increment")), ("1", "1"), "{table}");
    assert!(at("newton_iterations").parse::<u32>().is_ok() && at("contact_fit_active_nodes").parse::<u32>().is_ok(), "{table}");

    // --field defaults to the last increment; --plot draws the reactions against the
    // prescribed displacement at the path given
    let out = post(dir.path(), &[h5s, "--field", "displacement"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("at increment 5 "), "{}", String::from_utf8_lossy(&out.stdout));
    let png = dir.path().join("pictures_fd.png");
    let out = post(dir.path(), &[h5s, "--plot", png.to_str().unwrap()]);
    assert!(out.status.success() && std::fs::metadata(&png).is_ok_and(|m| m.len() > 10_000), "{}", String::from_utf8_lossy(&out.stderr));

    // a field at an increment: min and max with a place; a set's reaction series
    let out = post(dir.path(), &[h5s, "--field", "von_mises", "--increment", "5"]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success() && text.contains("max") && text.contains("at element"), "{text}");
    let out = post(dir.path(), &[h5s, "--set", "outer_top"]);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(text.contains("reaction of node set outer_top") && text.lines().count() == 2 + 5, "{text}");
    // the full ring first, per radian beside it (2 pi apart), and the set's mean displacement
    // (it had only the per-radian forces and no displacement)
    let header: Vec<&str> = text.lines().nth(1).unwrap().split("  ").map(str::trim).filter(|h| !h.is_empty()).collect();
    assert_eq!(header, ["increment", "time", "u_r (mm)", "u_z (mm)", "F_r (N ring)", "F_z (N ring)", "F_r (N/rad)", "F_z (N/rad)"], "{text}");
    let last: Vec<f64> = text.lines().last().unwrap().split_whitespace().map(|v| v.parse().unwrap()).collect();
    assert!((last[5] - 2.0 * std::f64::consts::PI * last[7]).abs() <= 1e-7 * last[5].abs(), "{text}");
    let file = hdf5::File::open(&h5).unwrap();
    let set: Vec<u64> = file.dataset("mesh/node_sets/outer_top").unwrap().read_raw().unwrap();
    let u: Vec<f64> = file.dataset("increments/000005/nodal/displacement").unwrap().read_raw().unwrap();
    let uz = set.iter().map(|&n| u[3 * n as usize + 1]).sum::<f64>() / set.len() as f64;
    assert!((last[3] - uz).abs() <= 1e-7 * uz.abs().max(1e-9), "mean u_z {} against {uz}", last[3]);

    // every dataset says its units and what it is
    fn undescribed(g: &hdf5::Group, out: &mut Vec<String>) {
        for ds in g.datasets().unwrap() {
            let attrs = ds.attr_names().unwrap();
            if !(attrs.contains(&"units".to_string()) && attrs.contains(&"description".to_string())) {
                out.push(ds.name());
            }
        }
        for sub in g.groups().unwrap() {
            undescribed(&sub, out);
        }
    }
    let mut missing = Vec::new();
    undescribed(&file.group("/").unwrap(), &mut missing);
    assert!(missing.is_empty(), "datasets without units or description: {missing:?}");
    let units = |path: &str| file.dataset(path).unwrap().attr("units").unwrap().read_scalar::<hdf5::types::VarLenUnicode>().unwrap().to_string();
    assert_eq!((units("increments/000001/stress").as_str(), units("history/reaction_outer_top_z_ring").as_str()), ("MPa", "N"));

    // a run of another model is refused by --compare unless forced
    let other = dir.path().join("other.h5");
    let small = "[mesh]\nrectangle = { r = [1.0, 2.0], z = [0.0, 1.0], divisions = [2, 1] }\n[[material]]\nname = \"steel\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\n[[step]]\nboundary = [ { set = \"bottom\", uz = 0.0 }, { set = \"top\", uz = -0.001 } ]\n";
    std::fs::write(dir.path().join("other.toml"), small).unwrap();
    assert!(command_in(dir.path(), 1).arg("run").arg(dir.path().join("other.toml")).arg("-o").arg(&other).arg("-q").output().unwrap().status.success());
    let out = post(dir.path(), &[h5s, "--compare", other.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("different models; --force"), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(post(dir.path(), &[h5s, "--compare", other.to_str().unwrap(), "--force"]).status.success());

    // bad input: one message each, exit 2
    let not_h5 = dir.path().join("fit.toml");
    let empty = dir.path().join("empty.h5");
    hdf5::File::create(&empty).unwrap();
    // a run killed between creating its file and the first flush leaves 0 bytes
    let nothing = dir.path().join("nothing.h5");
    std::fs::write(&nothing, b"").unwrap();
    for (args, needle) in [
        (vec![not_h5.to_str().unwrap()], "not a slideline results file (not HDF5)"),
        (vec![nothing.to_str().unwrap()], "incomplete: the run writing it stopped while creating it"),
        (vec![empty.to_str().unwrap()], "no /mesh group"),
        (vec![h5s, "--field", "von_mises", "--increment", "6"], "increment 6 out of range"),
        (vec![h5s, "--field", "strain", "--increment", "1"], "unknown field"),
        (vec![h5s, "--set", "nowhere"], "no node set \"nowhere\""),
    ] {
        let out = post(dir.path(), &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle) && err.lines().count() == 1, "{args:?}: {err}");
    }
}

/// A run that died while writing leaves an increment without its completion mark and history
/// columns of unequal length: post reads the complete rows, says what it ignored, never panics.
#[test]
fn post_reads_a_file_cut_short_with_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let (h5, run) = run_fit(dir.path(), 1, &["--quiet"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    {
        let file = hdf5::File::open_rw(&h5).unwrap();
        // the last increment lost its mark; one history column lost its last two rows
        file.group("increments/000005").unwrap().delete_attr("complete").unwrap();
        let history = file.group("history").unwrap();
        let time = history.dataset("time").unwrap().read_raw::<f64>().unwrap();
        history.unlink("wall_time").unwrap();
        history.new_dataset::<f64>().shape(3).create("wall_time").unwrap().write_raw(&time[..3]).unwrap();
    }
    let h5s = h5.to_str().unwrap();
    let out = post(dir.path(), &[h5s]);
    let (text, err) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{text}{err}");
    assert!(err.contains("000005") && err.contains("not completely written"), "{err}");
    assert!(err.contains("differ in length") && err.contains("wall_time"), "{err}");
    assert_eq!(text.lines().filter(|l| l.starts_with("step ") && l.contains(" inc ")).count(), 3, "{text}");
    let out = post(dir.path(), &[h5s, "--field", "von_mises", "--increment", "5"]);
    assert_eq!(out.status.code(), Some(2), "the incomplete increment is not offered");
    // a CSV that cannot be written is named as such, not as HDF5 output
    let out = post(dir.path(), &[h5s, "--csv", "/nonexistent/dir/h.csv"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cannot write /nonexistent/dir/h.csv") && !err.contains("HDF5"), "{err}");
}

/// `[output] every = 3, fields = ["von_mises"]`: the displacement and von Mises stress of
/// increments 3, 6 and 7 (the last of the step), the history of all 7; post, the XDMF sidecar
/// and meshio follow the run's numbering; an unknown field is refused by name.
#[test]
fn output_every_n_keeps_the_fields_of_every_nth_and_the_last_increment() {
    let dir = tempfile::tempdir().unwrap();
    let deck = "[output]\nevery = 3\nfields = [\"von_mises\"]\n[mesh]\nrectangle = { r = [1.0, 2.0], z = [0.0, 1.0], divisions = [2, 1] }\n[[material]]\nname = \"steel\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\n[[step]]\nincrements = 7\nboundary = [ { set = \"bottom\", uz = 0.0 }, { set = \"top\", uz = -0.007 } ]\n";
    std::fs::write(dir.path().join("d.toml"), deck).unwrap();
    let h5 = dir.path().join("d.h5");
    let run = command_in(dir.path(), 2).arg("run").arg(dir.path().join("d.toml")).arg("-o").arg(&h5).arg("-q").output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let file = hdf5::File::open(&h5).unwrap();
    assert_eq!(file.group("increments").unwrap().member_names().unwrap(), vec!["000003", "000006", "000007"]);
    assert_eq!(file.dataset("history/time").unwrap().read_raw::<f64>().unwrap().len(), 7);
    // fields = ["von_mises"]: beside the displacement, von Mises only
    let mut kept = file.group("increments/000003").unwrap().member_names().unwrap();
    kept.sort();
    // (and the restart state, which every increment written keeps)
    assert_eq!(kept, vec!["nodal", "residual_norms", "state", "von_mises", "von_mises_mean"]);
    assert_eq!(file.group("increments/000003/nodal").unwrap().member_names().unwrap(), vec!["displacement", "reaction_force", "von_mises"]);
    let xmf = std::fs::read_to_string(h5.with_extension("xmf")).unwrap();
    assert_eq!(xmf.matches("<Grid Name=\"increment").count(), 3);
    let h5s = h5.to_str().unwrap();
    let out = post(dir.path(), &[h5s, "--field", "displacement", "--increment", "4"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && err.contains("increment 4 has no fields") && err.contains("3, 6, 7"), "{err}");
    let out = post(dir.path(), &[h5s, "--field", "displacement"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("at increment 7 "), "{}", String::from_utf8_lossy(&out.stdout));
    let out = post(dir.path(), &[h5s]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.lines().filter(|l| l.starts_with("step ") && l.contains(" inc ")).count(), 7, "{text}");
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_xdmf.py");
    let check = common::python().arg(script).arg(h5.with_extension("xmf")).output().unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    assert!(
        check.status.success() && text.contains("3 increment steps after the t = 0 frame (of 7 history rows)"),
        "{text}{}",
        String::from_utf8_lossy(&check.stderr)
    );
    // the force-displacement curve has a point per history row, at the prescribed displacement
    // (before, the 3 written increments' displacements were paired with the first 3 rows' forces)
    let reader = slideline::io::reader::ResultsReader::open(&h5).unwrap();
    let plot = slideline::post::force_curves(&reader).unwrap();
    let top = plot.curves.iter().find(|c| c.label.starts_with("top:")).unwrap();
    let reaction = file.dataset("history/reaction_top_z_ring").unwrap().read_raw::<f64>().unwrap();
    assert_eq!(top.points.len(), 7);
    for (k, &(u, f)) in top.points.iter().enumerate() {
        assert!((u - 0.001 * (k + 1) as f64).abs() < 1e-15 && (f + reaction[k]).abs() <= 1e-12 * f.abs(), "point {k}: ({u}, {f})");
    }
    assert!(plot.x_label.starts_with("u_z of top, mm"), "{}", plot.x_label);
    std::fs::write(dir.path().join("bad.toml"), deck.replace("\"von_mises\"", "\"strains\"")).unwrap();
    let out = command_in(dir.path(), 1).arg("run").arg(dir.path().join("bad.toml")).arg("-o").arg(dir.path().join("bad.h5")).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && err.contains("unknown field \"strains\""), "{err}");
}

/// A results file another process holds locked (HDF5 takes a flock) is waited for, up to 3 s,
/// then refused with a message that says so instead of "not an HDF5 file". The lock is held by
/// flock(1), a process of its own: an HDF5 handle of this test process would leak its lock into
/// every child process spawned meanwhile (HDF5 opens files without close-on-exec).
#[test]
fn post_waits_for_a_locked_file_then_names_the_lock() {
    let dir = tempfile::tempdir().unwrap();
    let (h5, run) = run_fit(dir.path(), 1, &["--quiet"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let h5s = h5.to_str().unwrap().to_string();
    let hold = |seconds: &str| std::process::Command::new("flock").args(["-x", &h5s, "sleep", seconds]).spawn().expect("flock(1)");
    // held for 1 s: post waits and reads it
    let mut holder = hold("1");
    std::thread::sleep(std::time::Duration::from_millis(300));
    let out = post(dir.path(), &[&h5s]);
    holder.wait().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // held for longer than post waits: refused, naming the lock
    let mut holder = hold("6");
    std::thread::sleep(std::time::Duration::from_millis(300));
    let out = post(dir.path(), &[&h5s]);
    holder.kill().unwrap();
    holder.wait().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("locked by another process") && !err.contains("not an HDF5 file"), "{err}");
}

/// post as docs/results.md documents it, each point seen failing before: `--plot` without a name
/// writes FILE_force.png; a reader closing the pipe early ends post quietly with exit 0; output
/// paths are checked before any work (a missing directory, the results file itself under
/// another name: exit 2, "cannot write"); `--increment` and `--force` where they mean nothing
/// are refused; set names are matched without regard to case, as .inp set names are; the
/// `--compare` table fits in 120 columns and names the largest difference; a directory or a
/// FIFO is refused at once (a FIFO's read would block).
#[test]
fn post_commands_work_as_documented() {
    let dir = tempfile::tempdir().unwrap();
    let (h5, run) = run_fit(dir.path(), 1, &["--quiet"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let h5s = h5.to_str().unwrap();
    let out = post(dir.path(), &[h5s, "--plot"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.path().join("fit_force.png").exists(), "{}", String::from_utf8_lossy(&out.stdout));

    // | head: the reader closes the pipe after a line; post must not panic (exit 101)
    for _ in 0..5 {
        let mut child =
            command_in(dir.path(), 1).arg("post").arg(&h5).stdout(std::process::Stdio::piped()).stderr(std::process::Stdio::piped()).spawn().unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    }

    let link = dir.path().join("alias.h5");
    std::fs::hard_link(&h5, &link).unwrap();
    let before = std::fs::read(&h5).unwrap();
    for (args, needle) in [
        (vec![h5s, "--plot", "/nonexistent/dir/p.png"], "cannot write /nonexistent/dir/p.png"),
        (vec![h5s, "--csv", link.to_str().unwrap()], "which this command reads"),
        (vec![h5s, "--plot", h5s], "which this command reads"),
        (vec![h5s, "--node", "1", "--increment", "2"], "--increment goes with --field or --linearize"),
        (vec![h5s, "--force"], "--force goes with --compare"),
        (vec![dir.path().to_str().unwrap()], "a directory"),
    ] {
        let out = post(dir.path(), &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle) && err.lines().count() == 1, "{args:?}: {err}");
    }
    assert_eq!(std::fs::read(&h5).unwrap(), before, "the results file is untouched");
    let fifo = dir.path().join("fifo");
    if std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
        let out = post(dir.path(), &[fifo.to_str().unwrap()]);
        assert!(out.status.code() == Some(2) && String::from_utf8_lossy(&out.stderr).contains("not a regular file"));
    }

    // --field knows the nodal fields ParaView shows: the maximum it names is the dataset's
    let file = hdf5::File::open(&h5).unwrap();
    for (field, dataset) in [("nodal_von_mises", "von_mises"), ("strain_zz", "strain_zz"), ("contact_pressure", "contact_pressure")] {
        let out = post(dir.path(), &[h5s, "--field", field]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{field}: {}", String::from_utf8_lossy(&out.stderr));
        let max = file.dataset(&format!("increments/000005/nodal/{dataset}")).unwrap().read_raw::<f64>().unwrap().into_iter().fold(f64::MIN, f64::max);
        assert!(text.contains(&format!("max {:>14.6e}", max)) && text.contains("per node"), "{field}: {text}");
    }

    // set names without regard to case
    let upper = post(dir.path(), &[h5s, "--set", "OUTER_TOP"]);
    let lower = post(dir.path(), &[h5s, "--set", "outer_top"]);
    assert!(upper.status.success() && upper.stdout == lower.stdout, "{}", String::from_utf8_lossy(&upper.stderr));

    // --compare: 120 columns at most (the file names aside), the largest difference named
    let out = post(dir.path(), &[h5s, "--compare", link.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let widest = text.lines().filter(|l| !l.starts_with("A = ") && !l.starts_with("B = ")).map(str::len).max().unwrap();
    assert!(widest <= 120, "a {widest}-character line:\n{text}");
    assert!(text.contains("largest difference: reaction_") && text.contains("0.0000e0 N per radian"), "{text}");
    // two round-off values (an unloaded step's reactions, both below 1e-9 of the largest
    // reaction compared) show no ratio; every other row does
    let two = dir.path().join("two");
    std::fs::create_dir(&two).unwrap();
    let (h5_two, run) = run_fit(&two, 2, &["--quiet"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let out = post(dir.path(), &[h5s, "--compare", h5_two.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let rows: Vec<Vec<&str>> =
        text.split("\n\n").filter(|b| b.starts_with("reaction_")).flat_map(|b| b.lines().skip(2)).map(|l| l.split_whitespace().collect::<Vec<_>>()).collect();
    let value = |r: &Vec<&str>, k: usize| r[k].parse::<f64>().unwrap().abs();
    let scale = rows.iter().map(|r| value(r, 3)).fold(0.0f64, f64::max);
    let (tiny, loaded): (Vec<&Vec<&str>>, Vec<&Vec<&str>>) = rows.iter().partition(|r| value(r, 3).max(value(r, 4)) <= 1e-9 * scale);
    assert!(!tiny.is_empty() && !loaded.is_empty(), "{text}");
    assert!(tiny.iter().all(|r| r[6] == "-"), "two round-off values show a ratio:\n{text}");
    assert!(loaded.iter().all(|r| r[6].parse::<f64>().is_ok()), "{text}");
    // a Gauss-point field the file does not hold is named, with how to ask for it
    let out = post(dir.path(), &[h5s, "--field", "element_nodal_stress"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && err.contains("holds no element_nodal_stress: it is written only on request") && !err.contains("H5D"), "{err}");
}

/// A file that lost an increment's group says so (it said nothing), and a connectivity row that
/// names a node the mesh has not is refused by name (`post --linearize` panicked on it).
#[test]
fn post_names_a_missing_increment_and_a_corrupt_connectivity() {
    let dir = tempfile::tempdir().unwrap();
    let (h5, run) = run_fit(dir.path(), 1, &["--quiet"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let h5s = h5.to_str().unwrap();
    hdf5::File::open_rw(&h5).unwrap().group("increments").unwrap().unlink("000003").unwrap();
    let out = post(dir.path(), &[h5s]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.contains("increment(s) 3 should be in the file and are not"), "{err}");
    // a deck's run has no bellows code check
    let out = post(dir.path(), &[h5s, "--assessment"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && err.contains("no code check in the file"), "{err}");
    {
        let file = hdf5::File::open_rw(&h5).unwrap();
        let ds = file.dataset("mesh/connectivity").unwrap();
        let mut conn = ds.read_raw::<i64>().unwrap();
        conn[9] = 1_000_000;
        ds.write_raw(&conn).unwrap();
    }
    let out = post(dir.path(), &[h5s, "--linearize", "100,2:110,2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("mesh/connectivity names node row 1000000 in element row 1") && !err.contains("panicked"), "{err}");
}

/// A plane model's lines and `post` name its directions x and y and give its forces over the
/// thickness, in N, never per radian or around a ring: a plane-strain block of 2 x 1 elements
/// on rollers, pressed 0.01 mm on its top in 2 increments (the run's short lines, the Newton
/// monitor, `post` itself, `--set`, `--field`, `--node`, `--compare` and `--plot`).
#[test]
fn a_plane_model_is_reported_in_x_y_and_newtons_over_its_thickness() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("block.toml");
    std::fs::write(
        &deck,
        r#"geometry = "plane_strain"
thickness = 2.0
[mesh]
rectangle = { r = [0.0, 20.0], z = [0.0, 10.0], divisions = [2, 1] }
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[step]]
increments = 2
boundary = [ { set = "bottom", uy = 0.0 }, { set = "inner", ux = 0.0 }, { set = "top", uy = -0.01 } ]
"#,
    )
    .unwrap();
    let h5 = dir.path().join("block.h5");
    let run = command_in(dir.path(), 1).arg("run").arg(&deck).arg("-o").arg(&h5).arg("--monitor").output().unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout).to_string();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let line = stdout.lines().find(|l| l.starts_with("step 1/1")).expect("a progress line");
    assert!(line.contains(" F_y ") && line.ends_with(" s") && line.contains(" N ") && !stdout.contains("N/rad"), "{stdout}");
    assert!(stdout.lines().any(|l| l.trim_start().starts_with("newton  1") && l.contains(" N (bound")), "{stdout}");
    let h5s = h5.to_str().unwrap();
    for (args, wanted, unwanted) in [
        (vec![h5s], "F_y", "N/rad"),
        (vec![h5s, "--set", "top"], "F_y (N)", "ring"),
        (vec![h5s, "--field", "displacement"], "deformed (x, y)", "u_r"),
        (vec![h5s, "--field", "stress"], "s_xy", "s_rz"),
        (vec![h5s, "--node", "1"], "u_x (mm)", "u_r"),
        (vec![h5s, "--compare", h5s], "N over the thickness", "per radian"),
    ] {
        let out = post(dir.path(), &args);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success() && text.contains(wanted) && !text.contains(unwanted), "{args:?}: {text}{}", String::from_utf8_lossy(&out.stderr));
    }
    let out = post(dir.path(), &[h5s, "--plot"]);
    assert!(out.status.success() && dir.path().join("block_force.png").exists(), "{}", String::from_utf8_lossy(&out.stderr));
    // the file's own units, as h5py and ParaView show them: no dataset or attribute per radian
    let file = hdf5::File::open(&h5).unwrap();
    let units = |path: &str| file.dataset(path).unwrap().attr("units").unwrap().read_scalar::<hdf5::types::VarLenUnicode>().unwrap().to_string();
    let reaction = format!("increments/{:06}/nodal/reaction_force", 2);
    assert_eq!([units("history/reaction_top_z").as_str(), units(&reaction).as_str(), units("history/energy_external_work").as_str()], ["N", "N", "N mm"]);
    let sidecar = std::fs::read_to_string(dir.path().join("block.xmf")).unwrap();
    assert!(sidecar.contains("reaction_force: N") && !sidecar.contains("radian"), "{sidecar}");
}
