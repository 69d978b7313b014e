//! Throughput of the pure kernels (no PETSc, no MPI): material update, element residual and
//! tangent, pressure edge, contact kernel per slave node, and the contact search and segment
//! integration per surface size (the bellows ply interface at three meshes).
use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use slideline::ad::Dual;
use slideline::element::pressure::{compute_pressure_load, pressure_load_stiffness};
use slideline::element::solid::{compute_solid, solid_tangent, ElementGeometry, SolidInput};
use slideline::fe::quadrature::Integration;
use slideline::fe::section::Section;
use slideline::fe::shape::Shape;
use slideline::material::{Kinematics, PointState, SurfaceBranch, J2};

fn kernels(c: &mut Criterion) {
    let x = [[10.0, 0.0], [12.5, 0.3], [12.0, 2.2], [9.7, 2.0], [11.2, 0.1], [12.3, 1.3], [10.9, 2.15], [9.9, 1.0]];
    // a plastic state at every Gauss point
    let u: [[f64; 2]; 8] = std::array::from_fn(|a| [0.02 * x[a][0], -0.01 * x[a][1]]);
    let m = J2::plastic(200e3, 0.3, 1.2e-5, 300.0, 1000.0);
    let geometry = ElementGeometry::new(Shape::Quad8, Integration::Full, Section::Axisymmetric, &x).unwrap();
    let committed = [PointState::initial(Kinematics::Finite); 9];
    let input = SolidInput {
        geometry: &geometry,
        material: &m,
        kinematics: Kinematics::Finite,
        temperature_change: [10.0; 8],
        committed: &committed,
        surface: SurfaceBranch::Elastic,
    };

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
    g.bench_function("q8 finite J2 residual", |b| b.iter(|| compute_solid(&input, black_box(&u), None).unwrap()));
    let mut material = [Default::default(); 9];
    g.bench_function("q8 finite J2 residual + material tangents (dual)", |b| b.iter(|| compute_solid(&input, black_box(&u), Some(&mut material)).unwrap()));
    g.bench_function("q8 element tangent from the material tangents", |b| b.iter(|| solid_tangent(&geometry, black_box(&material))));
    let edge = [[100.0, 10.0], [100.5, 0.0], [100.1, 5.0]];
    g.bench_function("pressure edge load", |b| b.iter(|| compute_pressure_load(Section::Axisymmetric, black_box(&edge), 50.0)));
    g.bench_function("pressure edge stiffness", |b| b.iter(|| pressure_load_stiffness(Section::Axisymmetric, black_box(&edge), 50.0)));
    g.finish();
}

fn contact(c: &mut Criterion) {
    use slideline::bellows::joint::mesh;
    use slideline::bellows::spec::DesignSpec;
    use slideline::contact::integrated::weighted_gaps_into;
    use slideline::contact::node_to_edge::{edge_residual_and_tangent, project_on_edge, ContactLaw};
    use slideline::contact::search::EdgeGrid;
    use slideline::contact::surface::ContactSurface;

    let mut g = c.benchmark_group("contact kernel");
    g.throughput(Throughput::Elements(1));
    let edge = [
        [167.0 + 6.0 * 3.3f64.cos(), 200.0 + 6.0 * 3.3f64.sin()],
        [167.0 + 6.0 * 3.6f64.cos(), 200.0 + 6.0 * 3.6f64.sin()],
        [167.0 + 6.0 * 3.45f64.cos(), 200.0 + 6.0 * 3.45f64.sin()],
    ];
    let xs = [edge[2][0] + 0.001, edge[2][1]];
    g.bench_function("projection on a quadratic edge", |b| b.iter(|| project_on_edge(black_box(xs), &edge).unwrap()));
    let proj = project_on_edge(xs, &edge).unwrap();
    g.bench_function("slave node residual + tangent (dual)", |b| {
        let law = ContactLaw::linear(2.0, 1e4, 0.0, [false, false]);
        b.iter(|| edge_residual_and_tangent(black_box(xs), &edge, &proj, &law))
    });
    g.finish();

    // per slave node of the bellows' ply interface, at the quick, default and fine ply meshes
    let mut g = c.benchmark_group("contact surface");
    for (name, through, length) in [("quick", 1, 2.0), ("default", 2, 1.0), ("fine", 3, 0.5)] {
        let mut p = DesignSpec::seed();
        (p.joint.ply_elements, p.joint.ply_element_length) = (through, length);
        let (m, sets) = mesh(&p).unwrap();
        let slave = ContactSurface::new(&m, &sets.surfaces["ply2_inner"]);
        let master = ContactSurface::new(&m, &sets.surfaces["ply1_outer"]);
        let x = |n: usize| m.coords[n];
        let nodes = slave.nodes.len();
        g.throughput(Throughput::Elements(nodes as u64));
        g.bench_function(format!("grid + closest edge, {name} ({nodes} slave nodes)"), |b| {
            b.iter(|| {
                let grid = EdgeGrid::new(&master, &x, 2.0);
                slave.nodes.iter().filter(|&&n| grid.closest_edge(&master, &x, x(n), &[], 2.0, None).is_some()).count()
            })
        });
        let all: Vec<usize> = (0..nodes).collect();
        g.bench_function(format!("segment-integrated gaps + gradients, {name} ({nodes} slave nodes)"), |b| {
            // the buffers refilled from one call to the next, as a contact evaluation does
            let mut gaps = Vec::new();
            b.iter(|| {
                weighted_gaps_into(&slave, &master, &x, &x, black_box(&all), &[], 2.0, &mut gaps);
                gaps.iter().flat_map(|w| &w.samples).map(|s| s.gradient()[0]).sum::<f64>()
            })
        });
        let mut gaps = Vec::new();
        weighted_gaps_into(&slave, &master, &x, &x, &all, &[], 2.0, &mut gaps);
        // once per integration point, as the tangent computes them (a point serves two nodes)
        let mut points: Vec<_> = gaps.iter().flat_map(|w| &w.samples).collect();
        points.sort_by_key(|s| s.point);
        points.dedup_by_key(|s| s.point);
        g.bench_function(format!("segment-integrated Hessians, {name} ({nodes} slave nodes)"), |b| {
            b.iter(|| points.iter().map(|s| s.point_hessian(&x)[(0, 0)]).sum::<f64>())
        });
    }
    g.finish();
}

criterion_group!(benches, kernels, contact);
criterion_main!(benches);
