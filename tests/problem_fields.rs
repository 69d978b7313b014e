//! The output fields after convergence are those the last residual evaluation kept when it was
//! made at the same iterate, and a fresh evaluation otherwise: both must give the same stresses,
//! plastic strains and nodal forces. Likewise the material tangents a commit keeps: the
//! Jacobian after it equals one made from the committed history, and written straight into
//! PETSc's storage it equals the one MatSetValuesCOO makes. A two-block stack in contact, finite-strain J2 yielding
//! under a rough displacement field, heated, on one rank.
//! One test function: MPI can be initialised once per process.

use slideline::decomposition::{DofMap, Partition};
use slideline::model::{deck, Temperature};
use slideline::petsc::{MatOps, PetscSession, VecOps, Vector};
use slideline::solve::contact::affinity::partition_affinity;
use slideline::solve::problem::schedule::StepLoads;
use slideline::solve::problem::{initial_history, ElementFields, Problem, StepStart};
use std::path::Path;

const DECK: &str = r#"
nlgeom = true
[[mesh.block]]
name = "lower"
r = [10.0, 14.0]
z = [0.0, 2.0]
divisions = [3, 2]
[[mesh.block]]
name = "upper"
r = [10.0, 14.0]
z = [1.99, 4.0]
divisions = [4, 2]
[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
thermal_expansion = 1.2e-5
yield_stress = 300.0
hardening_modulus = 1000.0
[[contact]]
name = "stack"
slave = "upper_bottom"
master = "lower_top"
penalty = 1.0e4
[[step]]
temperature = 120.0
boundary = [ { set = "lower_bottom", uz = 0.0 }, { set = "upper_top", uz = -0.05 } ]
"#;

fn assert_same(a: &ElementFields, b: &ElementFields, what: &str) {
    let flat = |f: &ElementFields| -> Vec<f64> {
        f.stress.iter().flatten().flatten().chain(f.plastic_strain.iter().flatten()).chain(f.nodal_force.iter().flatten()).copied().collect()
    };
    let (x, y) = (flat(a), flat(b));
    assert_eq!(x.len(), y.len());
    let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, (u, v)) in x.iter().zip(&y).enumerate() {
        assert!((u - v).abs() <= 1e-12 * scale, "{what}: entry {i}: {u} vs {v}");
    }
}

#[test]
fn kept_output_fields_equal_a_fresh_evaluation() {
    let session = PetscSession::initialize(&[]).expect("PETSc");
    let model = deck::parse(DECK, Path::new("stack.toml")).expect("deck");
    let partition = Partition::new(&session, &model.mesh, &partition_affinity(&model)).expect("partition");
    let nodes = model.mesh.coords.len();
    let loads = StepLoads::new(&model, 0, None, &vec![[0.0; 2]; nodes]);
    let dofs = DofMap::new(&partition, &loads.prescribed_mask(&model)).expect("dofs");
    let mut x = Vector::mpi(&session, session.comm(), dofs.local_len()).expect("vector");
    {
        // a rough field: every element strained past yield somewhere, the blocks pressed together
        let mut v = x.write().expect("write");
        for (i, u) in v.iter_mut().enumerate() {
            *u = 0.02 * ((i as f64) * 0.7).sin() - 0.01;
        }
    }
    let mut other = Vector::mpi(&session, session.comm(), dofs.local_len()).expect("vector");
    other.copy_from(&x).expect("copy");
    other.axpy(1e-3, &x).expect("axpy");
    let mut f = Vector::mpi(&session, session.comm(), dofs.local_len()).expect("vector");
    let mut problem = Problem::new(&session, &model, &partition, &dofs, &x, StepStart { step: 0, history: initial_history(&model, &partition), contact: None })
        .expect("problem");
    problem.set_load(loads.at(&model, 1.0));

    problem.assemble_residual(&x, &mut f).expect("residual");
    let kept = problem.evaluate_fields(&x).expect("fields at the residual's iterate");
    problem.assemble_residual(&other, &mut f).expect("residual elsewhere");
    let fresh = problem.evaluate_fields(&x).expect("fields evaluated afresh");
    assert_same(&kept, &fresh, "kept vs fresh at x");
    assert!(kept.plastic_strain.iter().flatten().any(|&ep| ep > 0.0), "the state is meant to be plastic");
    assert!(kept.nodal_force.iter().flatten().any(|&v| v != 0.0));
    // and the other way round: the fields at `other` differ (the test can tell states apart)
    problem.assemble_residual(&other, &mut f).expect("residual elsewhere");
    let moved = problem.evaluate_fields(&other).expect("kept at other");
    let differs = kept.stress.iter().flatten().flatten().zip(moved.stress.iter().flatten().flatten()).any(|(a, b)| (a - b).abs() > 1e-6);
    assert!(differs, "the two iterates give the same stresses");
    // a changed load (temperature) is not served from the kept fields
    problem.assemble_residual(&x, &mut f).expect("residual");
    let mut hotter = loads.at(&model, 1.0);
    hotter.temperature = Temperature::Uniform(hotter.temperature.at(0) + 10.0);
    problem.set_load(hotter);
    let heated = problem.evaluate_fields(&x).expect("fields under another load");
    let differs = kept.stress.iter().flatten().flatten().zip(heated.stress.iter().flatten().flatten()).any(|(a, b)| (a - b).abs() > 1e-6);
    assert!(differs, "the kept fields served a different load");

    // A commit keeps the material tangents of the elements whose history it leaves unchanged
    // (for the next increment's predictor) and drops the others: the Jacobian at x after the
    // commit equals one from a new problem started from the committed history.
    problem.set_load(loads.at(&model, 1.0));
    problem.assemble_residual(&x, &mut f).expect("residual");
    problem.commit();
    let mut after_commit = problem.jacobian_matrix().expect("matrix");
    problem.assemble_jacobian(&x, &mut after_commit).expect("jacobian after the commit");
    // the same Jacobian again, now written straight into PETSc's storage of the matrix
    let mut rewritten = problem.jacobian_matrix().expect("matrix");
    problem.assemble_jacobian(&other, &mut rewritten).expect("jacobian elsewhere");
    assert!(problem.writes_jacobian_storage(), "bound to the storage after the first assembly");
    problem.assemble_jacobian(&x, &mut rewritten).expect("jacobian written into the storage");
    let (history, carry) = problem.into_history();
    let mut restarted = Problem::new(&session, &model, &partition, &dofs, &x, StepStart { step: 0, history, contact: carry }).expect("problem");
    restarted.set_load(loads.at(&model, 1.0));
    let mut fresh = restarted.jacobian_matrix().expect("matrix");
    restarted.assemble_jacobian(&x, &mut fresh).expect("jacobian from the committed history");
    let (mut y1, mut y2) = (Vector::mpi(&session, session.comm(), dofs.local_len()).unwrap(), Vector::mpi(&session, session.comm(), dofs.local_len()).unwrap());
    after_commit.multiply(&other, &mut y1).expect("product");
    fresh.multiply(&other, &mut y2).expect("product");
    let mut y3 = Vector::mpi(&session, session.comm(), dofs.local_len()).unwrap();
    rewritten.multiply(&other, &mut y3).expect("product");
    let (a, b, c) = (y1.read().unwrap().to_vec(), y2.read().unwrap().to_vec(), y3.read().unwrap().to_vec());
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for (i, (p, q)) in a.iter().zip(&b).enumerate() {
        assert!((p - q).abs() <= 1e-12 * scale, "row {i}: {p} after the commit vs {q} from the committed history");
    }
    assert_eq!(a, c, "the values written into the storage are those MatSetValuesCOO sets");
}
