//! One Newton iteration's assembly on the default bellows mesh, 1 rank: the residual (elements,
//! pressure, contact search and kernels), the Jacobian alone (the same with tangents, into the
//! preallocated AIJ matrix), and the pair as a Newton iteration makes it (the Jacobian at the
//! residual's iterate, from the material tangents the residual kept), at the end of the heating step (200 degC, 0.6 MPa, plies and
//! sleeve in contact). Reported per call and as elements per second; compare with the linear
//! solve of the same iteration in scripts/profile-bellows.sh.
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use slideline::bellows::joint::model;
use slideline::bellows::spec::DesignSpec;
use slideline::decomposition::{DofMap, Partition};
use slideline::petsc::{PetscSession, VecOps, Vector};
use slideline::solve::contact::affinity::partition_affinity;
use slideline::solve::contact::contact_nodes;
use slideline::solve::problem::schedule::StepLoads;
use slideline::solve::problem::{initial_history, Problem, StepStart};

fn assembly(c: &mut Criterion) {
    let session = PetscSession::initialize(&[]).expect("PETSc");
    let m = model(&DesignSpec::seed()).expect("bellows model");
    let partition = Partition::new(&session, &m.mesh, &partition_affinity(&m)).expect("partition");
    let nodes = m.mesh.coords.len();
    let loads = StepLoads::new(&m, 0, None, &vec![[0.0; 2]; nodes]);
    let dofs = DofMap::new(&partition, &loads.prescribed_mask(&m)).expect("dofs");
    // two nearby states, alternated, so that no evaluation is served from the contact cache
    let xa = Vector::mpi(&session, session.comm(), dofs.local_len()).expect("vector");
    let mut xb = Vector::mpi(&session, session.comm(), dofs.local_len()).expect("vector");
    xb.set_all(1e-9).expect("set");
    let mut f = Vector::mpi(&session, session.comm(), dofs.local_len()).expect("vector");
    let coupled = contact_nodes(&m);
    let mut problem =
        Problem::new(&session, &m, &partition, &dofs, &xa, StepStart { step: 0, history: initial_history(&m, &partition), contact: None }).expect("problem");
    problem.set_load(loads.at(&m, 1.0));
    // the matrix as the stepping loop makes it, with the contact couplings of this state reserved
    let mut jacobian = problem.jacobian_matrix().expect("matrix");
    problem.assemble_jacobian(&xa, &mut jacobian).expect("jacobian");

    let mut g = c.benchmark_group("bellows assembly (1 rank)");
    g.throughput(Throughput::Elements(m.mesh.elements.len() as u64));
    g.sample_size(20);
    let mut flip = false;
    g.bench_function("residual", |b| {
        b.iter(|| {
            flip = !flip;
            problem.assemble_residual(if flip { &xa } else { &xb }, &mut f).expect("residual")
        })
    });
    g.bench_function("jacobian", |b| {
        b.iter(|| {
            flip = !flip;
            problem.assemble_jacobian(if flip { &xa } else { &xb }, &mut jacobian).expect("jacobian")
        })
    });
    // what a Newton iteration assembles: the residual at an iterate, then the Jacobian there
    // (which finds the material tangents the residual kept)
    g.bench_function("residual + jacobian", |b| {
        b.iter(|| {
            flip = !flip;
            let x = if flip { &xa } else { &xb };
            problem.assemble_residual(x, &mut f).expect("residual");
            problem.assemble_jacobian(x, &mut jacobian).expect("jacobian")
        })
    });
    g.finish();
    println!("bellows mesh: {} elements, {} nodes, {} unknowns, {} contact nodes", m.mesh.elements.len(), nodes, dofs.local_len(), coupled.len());
}

criterion_group!(benches, assembly);
criterion_main!(benches);
