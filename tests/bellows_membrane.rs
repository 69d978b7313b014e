//! The plies' meridional membrane stress from the elements' nodal forces
//! (`assessment::membrane`), the assessment's S3 and S5, against statics: in the linear stroke
//! analysis of the quick joint (tube B's end pushed 0.7 mm towards tube A, no pressure, the
//! sleeve sliding without friction), the pack carries the whole end reaction through every
//! crest and root. At an apex the meridian is axial, so the plies' membrane forces,
//! sum_k sigma_k t r_k per radian (r_k each ply's mid radius), must equal the reaction at the
//! moving end: within 1e-4 of it at every crest and root apex (measured 6e-6). The ply element length 1.9 mm
//! puts an element line on every apex (10 elements per half torus of radius 6). One rank, one
//! test function: MPI can be initialised once per process.

use slideline::bellows::finite_element::stroke_analysis;
use slideline::bellows::joint::convolution_pieces;
use slideline::bellows::membrane::PlyMembrane;
use slideline::bellows::spec::DesignSpec;
use slideline::io::reader::ResultsReader;
use slideline::petsc::PetscSession;
use slideline::solve::{run, RunOptions};

#[test]
fn the_plies_membrane_forces_at_every_apex_carry_the_end_reaction() {
    let session = PetscSession::initialize(&[]).expect("PETSc");
    let mut p = DesignSpec::seed().quick();
    p.joint.ply_element_length = 1.9;
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("stroke.h5");
    let model = stroke_analysis(&p, 0.7).expect("model");
    let options = RunOptions { output: file.clone(), progress: false, verbose: false, monitor: false, restart: None };
    run(&session, &model, &options).expect("the stroke analysis runs");

    let r = ResultsReader::open(&file).unwrap();
    let last = r.increments().unwrap().pop().unwrap();
    let reaction = *r.history("reaction_moving_end_z").unwrap().last().unwrap();
    let pieces = convolution_pieces(&p);
    let membrane = PlyMembrane::from_file(&r, &last, &model, &p, &pieces, 1.0).expect("membrane");
    let (t, pack) = (p.bellows.ply_thickness, p.pack_thickness());
    let mut apexes = 0;
    for (i, piece) in pieces.iter().enumerate().filter(|(_, c)| !c.end && !c.label.starts_with("sidewall")) {
        let (x, tangent) = piece.piece.at(0.5);
        assert!(tangent[0].abs() < 1e-12 && tangent[1] > 0.0, "{}: the meridian at the apex runs along +z", piece.label);
        // ply k's mid-surface lies (k + 1/2) t outward from the pack's inside
        let force: f64 = (0..p.bellows.plies).map(|k| membrane.at(k, i, 0.5) * t * (x[0] - pack / 2.0 + (k as f64 + 0.5) * t)).sum();
        eprintln!("{}: plies' force {force:.4} N per radian, reaction {reaction:.4}", piece.label);
        assert!((force / reaction - 1.0).abs() < 1e-4, "{}: the plies carry {force} N per radian, the end reaction is {reaction}", piece.label);
        apexes += 1;
    }
    assert_eq!(apexes, 2 * p.bellows.convolutions - 1, "every crest and every root between two convolutions");
    assert!(reaction < 0.0, "the stroke pushes");
}
