//! Throughput of the pure kernels (no PETSc, no MPI): material update, element residual and
//! tangent, pressure edge.
use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use slideline::ad::Dual;
use slideline::element::pressure::{compute_pressure_load, pressure_load_stiffness};
use slideline::element::solid::{compute_solid, ElementGeometry, SolidInput};
use slideline::material::{Kinematics, PointState, J2};

fn kernels(c: &mut Criterion) {
    let x = [[10.0, 0.0], [12.5, 0.3], [12.0, 2.2], [9.7, 2.0], [11.2, 0.1], [12.3, 1.3], [10.9, 2.15], [9.9, 1.0]];
    // a plastic state at every Gauss point
    let u: [[f64; 2]; 8] = std::array::from_fn(|a| [0.02 * x[a][0], -0.01 * x[a][1]]);
    let m = J2::plastic(200e3, 0.3, 1.2e-5, 300.0, 1000.0);
    let geometry = ElementGeometry::new(&x).unwrap();
    let committed = [PointState::initial(Kinematics::Finite); 9];
    let input = SolidInput { geometry: &geometry, material: &m, kinematics: Kinematics::Finite, temperature_change: 10.0, committed: &committed };

    let mut g = c.benchmark_group("material");
    g.throughput(Throughput::Elements(1));
    let f = [1.02, 0.01, -0.005, 0.97, 1.02];
    let state = PointState::initial(Kinematics::Finite);
    g.bench_function("j2 finite update", |b| b.iter(|| m.update(Kinematics::Finite, black_box(&f), 1.0, 0.0, &state).unwrap()));
    let fd: [Dual<6>; 5] = std::array::from_fn(|i| Dual::variable(f[i], i));
    g.bench_function("j2 finite update + tangent (dual)", |b| {
        b.iter(|| m.update(Kinematics::Finite, black_box(&fd), Dual::variable(1.0, 5), 0.0, &state).unwrap())
    });
    g.finish();

    let mut g = c.benchmark_group("element");
    g.throughput(Throughput::Elements(1));
    g.bench_function("q8 finite J2 residual", |b| b.iter(|| compute_solid(&input, black_box(&u), false).unwrap()));
    g.bench_function("q8 finite J2 residual + tangent", |b| b.iter(|| compute_solid(&input, black_box(&u), true).unwrap()));
    let edge = [[100.0, 10.0], [100.5, 0.0], [100.1, 5.0]];
    g.bench_function("pressure edge load", |b| b.iter(|| compute_pressure_load(black_box(&edge), 50.0)));
    g.bench_function("pressure edge stiffness", |b| b.iter(|| pressure_load_stiffness(black_box(&edge), 50.0)));
    g.finish();
}

criterion_group!(benches, kernels);
criterion_main!(benches);
