//! Throughput of the pure kernels (no PETSc, no MPI): element residual + tangent.
use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use slideline::element::pressure::compute_pressure_load;
use slideline::element::solid::compute_solid;
use slideline::material::elastic::Elastic;

fn element_kernels(c: &mut Criterion) {
    let x = [
        [10.0, 0.0],
        [12.5, 0.3],
        [12.0, 2.2],
        [9.7, 2.0],
        [11.2, 0.1],
        [12.3, 1.3],
        [10.9, 2.15],
        [9.9, 1.0],
    ];
    let u: [[f64; 2]; 8] = std::array::from_fn(|a| [1e-3 * a as f64, -2e-3]);
    let m = Elastic::new(200e3, 0.3, 1.2e-5);
    let mut g = c.benchmark_group("element");
    g.throughput(Throughput::Elements(1));
    g.bench_function("q8 residual", |b| {
        b.iter(|| compute_solid(black_box(&x), black_box(&u), 10.0, &m, false).unwrap())
    });
    g.bench_function("q8 residual + tangent", |b| {
        b.iter(|| compute_solid(black_box(&x), black_box(&u), 10.0, &m, true).unwrap())
    });
    g.bench_function("pressure edge", |b| {
        b.iter(|| {
            compute_pressure_load(
                black_box(&[[100.0, 10.0], [100.0, 0.0], [100.0, 5.0]]),
                50.0,
            )
        })
    });
    g.finish();
}

criterion_group!(benches, element_kernels);
criterion_main!(benches);
