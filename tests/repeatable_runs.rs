//! Two runs of the same model on the same ranks give bit-identical results: Scotch partitions
//! with one thread, so the partition does not depend on how its threads interleave. Case: the
//! quick bellows joint compressed 20 mm in 10 increments, twice on 2 ranks, its linear solves
//! by PETSc's redundant LU. (With the default MUMPS they are not always: its parallel
//! factorisation adds the ranks' contributions in message arrival order, and the quick joint at
//! 70 mm differs from run to run by 1e-11 from increment #42 on; see docs/running.md.)

mod common;
use common::{command_in, Results};

#[test]
fn two_runs_on_two_ranks_are_bit_identical() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str| {
        let out = command_in(dir.path(), 2)
            .current_dir(dir.path())
            .args(["bellows", "--quick", "--displacement", "20", "--increments", "10", "--quiet", "-o", name])
            // the linear solves by redundant LU: MUMPS's parallel factorisation itself is not
            // bit-repeatable (it adds contributions in message arrival order)
            .args(["--", "-ksp_type", "preonly", "-pc_type", "redundant", "-redundant_pc_type", "lu"])
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        Results::open(&dir.path().join(name))
    };
    let (a, b) = (run("a.h5"), run("b.h5"));
    let columns = a.file.group("history").unwrap().member_names().unwrap();
    assert_eq!(columns, b.file.group("history").unwrap().member_names().unwrap());
    for name in columns.iter().filter(|c| *c != "wall_time") {
        let (x, y) = (a.history(name), b.history(name));
        let same = x.len() == y.len() && x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits());
        assert!(same, "{name}: {x:?} vs {y:?}");
    }
    let last = a.last_increment();
    for field in ["nodal/displacement", "stress"] {
        let (x, y) = (a.f64s(&format!("{last}/{field}")), b.f64s(&format!("{last}/{field}")));
        assert!(x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits()), "{field} differs");
    }
}
