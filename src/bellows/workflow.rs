//! The `slideline bellows` command's work, in order: the code check and the analyses of the
//! joint at rest the flags ask for ([`before_the_run`]), the elastic-plastic run with the
//! perturbation steps about its end ([`run`]), then the closing table, the sections after it
//! and the pictures ([`report`]); and `--mesh-only`'s mesh ([`write_mesh`]).

use super::flexibility::{Flexibility, Movements};
use super::report::BellowsReport;
use super::spec::DesignSpec;
use super::stability::{Stability, SQUIRM};
use super::vibration::{Frequencies, LATERAL_MODES};
use crate::assessment::code::{CodeCheck, Duty, Source};
use crate::assessment::coefficients::Coefficients;
use crate::assessment::fe_check::FeCheck;
use crate::assessment::verdict::Verdict;
use crate::decomposition::Partition;
use crate::error::Result;
use crate::io::plots::{outline_picture, Panel, SegmentLayer};
use crate::io::reader::ResultsReader;
use crate::io::restart::RestartFrom;
use crate::io::ResultsFile;
use crate::model::perturbation::Perturbation;
use crate::petsc::PetscSession;
use crate::solve::contact::affinity::partition_affinity;
use crate::solve::{RunOptions, RunSummary};
use mpi::traits::Communicator;
use std::path::{Path, PathBuf};

/// What a `slideline bellows` command asks for, its flags checked.
pub struct BellowsJob {
    /// The joint (its code verdict is printed before the analyses where it has a design
    /// specification's data: see [`BellowsJob::spec`]).
    pub params: DesignSpec,
    /// Write the design report here (`--report`), after the run.
    pub report: Option<PathBuf>,
    /// The flexibility's movements (`--lateral`, `--angular`), if any.
    pub movements: Option<Movements>,
    pub output: PathBuf,
    pub quiet: bool,
    pub verbose: bool,
    pub monitor: bool,
    pub restart: Option<RestartFrom>,
    pub squirm: bool,
    pub assess: bool,
    pub frequencies: bool,
}

impl BellowsJob {
    /// The joint as a design specification, where it has one's data (the allowable stress and
    /// the cycles): the code's verdict is then made and printed.
    pub fn spec(&self) -> Option<&DesignSpec> {
        self.params.has_design_data().then_some(&self.params)
    }
}

/// What the analyses before the main run found, for its report: the code check, the
/// finite-element assessment, and the flexibility, stability and natural frequencies of the
/// joint at rest.
pub struct BeforeTheRun {
    pub code: Option<CodeCheck>,
    /// A design specification's verdict and its table (`--spec`).
    pub verdict: Option<(Verdict, String)>,
    pub fe: Option<FeCheck>,
    pub rest: Option<(Movements, Flexibility)>,
    pub stable: Option<Stability>,
    pub vibrating: Option<Frequencies>,
}

/// `OUTPUT_name.png` beside the output.
pub fn picture_path(output: &Path, name: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}_{name}.png"))
}

/// The bellows' code check (EJMA): the design pressure and the whole stroke, with the chart
/// coefficients given (`--coefficients`) or computed for its convolution (collective).
pub fn code_check(session: &PetscSession, params: &DesignSpec) -> Result<CodeCheck> {
    let geometry = params.geometry();
    let (coefficients, source) = match params.bellows.coefficients {
        Some([cp, cf, cd]) => (Coefficients { cp, cf, cd }, Source::Given),
        None => (super::convolution::compute_for_the_code(session, geometry.c1(), geometry.c2())?, Source::Computed),
    };
    let duty = Duty {
        pressure: params.design.pressure,
        stroke: params.displacement().abs(),
        modulus: params.youngs_modulus(),
        yield_stress: params.yield_stress(),
        tangent_length: params.bellows.tangent_length,
        forming: params.bellows.forming,
    };
    Ok(CodeCheck::new(&geometry, coefficients, source, duty))
}

/// The code check of design specification `spec` and its verdict, with the table that prints
/// them; the chart coefficients given or computed for its convolution (collective).
pub fn code_verdict(session: &PetscSession, spec: &DesignSpec) -> Result<(CodeCheck, Verdict, String)> {
    let check = spec.code_check(|b| super::convolution::compute_for_the_code(session, b.c1(), b.c2()))?;
    let verdict = spec.verdict(&check)?;
    let table = super::report::verdict_table(spec, &check, &verdict)?;
    Ok((check, verdict, table))
}

/// The code check (a note where it cannot be made) and the analyses of the joint at rest the
/// job asks for, each announced (collective).
pub fn before_the_run(session: &PetscSession, job: &BellowsJob) -> Result<BeforeTheRun> {
    let params = &job.params;
    let root = session.world().rank() == 0;
    // the code check, with the chart coefficients given or computed for the joint's own
    // convolution: a specification's, for its equivalent movement, with its verdict; else the
    // stroke's
    let (code, verdict) = match job.spec() {
        Some(spec) => {
            let (check, verdict, table) = code_verdict(session, spec)?;
            if root && !job.quiet {
                print!("{table}");
            }
            (Some(check), Some((verdict, table)))
        }
        None => {
            let code = code_check(session, params);
            if let (true, Err(e)) = (root, &code) {
                println!("note: no code check: {e}");
            }
            (code.ok(), None)
        }
    };
    let announce = |what: &str| {
        if root && !job.quiet {
            println!("{what} ...");
        }
    };
    // the instability pressures of the joint at rest (for --squirm and --assess, once)
    let stable = (job.squirm || job.assess)
        .then(|| {
            announce("stability: the joint at rest and its buckling analyses");
            // the squirm's mode at rest, pictured from the rest run's file (rank 0; a picture
            // that fails is a note: the other ranks go on)
            let picture = picture_path(&job.output, "squirm_mode");
            super::stability::at_rest(session, params, |file, s| {
                if let (true, true, Some(p)) = (root, job.squirm, s.squirm) {
                    let title = format!("the joint's squirm at rest, {p:.1} MPa: its column buckling mode (n = 1)");
                    let drawn = ResultsReader::open(file).and_then(|r| super::report::mode_picture(&r, &picture, SQUIRM, 1, 1, &title));
                    if let Err(e) = drawn {
                        println!("note: no picture of the squirm's mode: {e}");
                    }
                }
            })
        })
        .transpose()?;
    let vibrating = job
        .frequencies
        .then(|| {
            announce("natural frequencies: the joint at rest and its frequency analyses");
            super::vibration::at_rest(session, params)
        })
        .transpose()?;
    // the finite-element side of the assessment, and the flexibility of the joint at rest
    let fe = stable.as_ref().filter(|_| job.assess).map(|s| {
        announce("assessment: linear elastic analyses of the design pressure and of the stroke");
        super::finite_element::analyse(session, params, s)
    });
    let rest = job.movements.map(|m| {
        announce("flexibility: the joint at rest and its harmonic perturbations");
        super::flexibility::at_rest(session, params, m).map(|f| (m, f))
    });
    let (fe, rest) = (fe.transpose()?, rest.transpose()?);
    // the stability section is --squirm's
    let stable = stable.filter(|_| job.squirm);
    if let (true, false, Some(c)) = (root, job.quiet, &code) {
        let k = c.coefficients;
        println!(
            "bellows: {} plies x {} mm, {} convolutions, pitch {}, height {}; EJMA axial rate {:.1} N/mm full ring, {:.2} N/mm per 2.5-degree sector (C1 = {:.3}, C2 = {:.3}: Cp {:.3}, Cf {:.3}, Cd {:.3} {})",
            params.bellows.plies, params.bellows.ply_thickness, params.bellows.convolutions, params.bellows.pitch, params.bellows.convolution_height, c.axial_rate, c.axial_rate * 2.5 / 360.0, c.c1, c.c2, k.cp, k.cf, k.cd, c.source.label()
        );
    }
    Ok(BeforeTheRun { code, verdict, fe, rest, stable, vibrating })
}

/// The perturbation steps the job's flags ask for on joint `p`: the flexibility's movements,
/// the stability's, the frequencies', each once (the axial rate's step is all three's).
pub fn perturbation_steps(job: &BellowsJob, p: &DesignSpec) -> Vec<Perturbation> {
    let lists = [
        job.movements.map(|m| super::flexibility::steps(p, m)),
        job.squirm.then(|| super::stability::steps(p)),
        job.frequencies.then(|| super::vibration::steps(p)),
    ];
    let mut steps: Vec<Perturbation> = Vec::new();
    for step in lists.into_iter().flatten().flatten() {
        if !steps.iter().any(|s| s.name == step.name) {
            steps.push(step);
        }
    }
    steps
}

/// The elastic-plastic run of the joint, with the perturbation steps the flags ask for about
/// its end (collective).
pub fn run(session: &PetscSession, job: &BellowsJob) -> Result<RunSummary> {
    let params = &job.params;
    let mut m = super::joint::model(params)?;
    // the same perturbations about the run's end state
    m.set_perturbations(perturbation_steps(job, params));
    m.validate()?;
    crate::solve::run(
        session,
        &m,
        &RunOptions { output: job.output.clone(), progress: !job.quiet, verbose: job.verbose, monitor: job.monitor, restart: job.restart.clone() },
    )
}

/// How far `--dba`'s limit load raises the design pressure looking for the collapse: the
/// convolutions of a joint that passes the code's in-plane check (at about 2.3 Sy) hold several
/// times their design pressure.
const BELLOWS_SEARCH_TO: f64 = 20.0;

/// The time budget of the bellows' collapse search, s: its verdict is known before it starts,
/// and near collapse a ply pack in contact takes tens of seconds an increment.
const BELLOWS_SEARCH_SECONDS: f64 = 300.0;

/// `--dba`: the design-by-analysis checks (ASME VIII-2 Part 5) on the joint `params`
/// describes, with the allowable stress of its specification: the limit load under the design
/// pressure alone (the ends held; the stroke is a secondary load), ratcheting over three
/// cycles of the stroke (compress, return) under the pressure, and where the specification's
/// material gives its cyclic curve (`backstresses`) fatigue over three such cycles against
/// its required cycles. The verdict is printed with the
/// specification's code verdict before it and written to `output` (`/dba`, and the code's
/// verdict as a run's file holds it); each analysis in a file beside it; with `report`, the
/// design report of `output` (collective).
pub fn design_by_analysis(session: &PetscSession, params: &DesignSpec, output: &Path, report: Option<&Path>, quiet: bool) -> Result<()> {
    use crate::dba::table::{Allowable, DbaTable, FatigueTable, LimitLoadTable, RatchetingTable};
    use crate::error::Error;
    use crate::model::KinematicHardening;
    let spec = params
        .has_design_data()
        .then_some(params)
        .ok_or_else(|| crate::error::Error::input("bellows --dba: the checks need the allowable stress of a design specification (--spec FILE)"))?;
    let (_, _, allowable) = spec.at_temperature()?;
    let mut cycling = params.clone();
    cycling.joint.cycle = true;
    let mut model = super::joint::model(&cycling)?;
    // the specification's cyclic curve, where it gives one, for the fatigue check (the other
    // checks are elastic-perfectly plastic)
    let kinematic = KinematicHardening::new(&spec.material.backstresses).map_err(|e| Error::input(format!("[material] backstresses: {e}")))?;
    for m in &mut model.materials {
        m.kinematic = kinematic;
    }
    let stroke = vec!["compress".to_string(), "return".to_string()];
    let fatigue = (!kinematic.is_empty()).then(|| FatigueTable {
        cycle: stroke.clone(),
        cycles: crate::dba::table::LEAST_CYCLES,
        design_cycles: spec.design.cycles.unwrap_or(f64::NAN),
        curve: None,
        curve_modulus: None,
    });
    let checks = DbaTable {
        fatigue,
        allowable_stress: Some(Allowable::Every(allowable)),
        limit_load: Some(LimitLoadTable {
            factor: 1.5,
            search_to: BELLOWS_SEARCH_TO,
            search_increments: 40,
            search_seconds: Some(BELLOWS_SEARCH_SECONDS),
            steps: Some(vec!["heat".into()]),
        }),
        ratcheting: Some(RatchetingTable { cycle: stroke, cycles: crate::dba::table::LEAST_CYCLES, section: None }),
        buckling: None,
    };
    checks.validate(&model)?;
    let _locks = crate::dba::lock_outputs(session, output)?;
    // the code's verdict first, as the run prints it (collective: its chart coefficients)
    let (_, code, code_table) = code_verdict(session, spec)?;
    let root = session.world().rank() == 0;
    if root {
        print!("{code_table}");
    }
    let verdict = crate::dba::run(session, &model, &checks, output, !quiet)?;
    if !root {
        return Ok(());
    }
    crate::dba::report(&verdict, &params.fe_title(), output, &model.source_text)?;
    crate::io::assessment::write_verdict(output, &code, &spec.text, &spec.sha256())?;
    if let Some(path) = report {
        super::report::html::write_design_report(&ResultsReader::open(output)?, None, path)?;
        println!("report: {}", path.display());
    }
    Ok(())
}

/// The bellows closing table (slideline beside the paper) and the pictures, from the results
/// file (rank 0, after the run).
pub fn report(job: &BellowsJob, before: &BeforeTheRun, summary: &RunSummary) -> Result<()> {
    let (params, output) = (&job.params, job.output.as_path());
    let BeforeTheRun { code, verdict, fe, rest, stable, vibrating } = before;
    let (code, fe, rest, stable, vibrating) = (code.as_ref(), fe.as_ref(), rest.as_ref(), stable.as_ref(), vibrating.as_ref());
    let reader = ResultsReader::open(output)?;
    let life = match fe {
        Some(_) => super::finite_element::strain_life(&reader, params.youngs_modulus())?,
        None => None,
    };
    // a restart from a finished run's end writes no increment of its own: its fields are in
    // the file it continued
    let fields = !reader.increments()?.is_empty();
    let mut report = fields.then(|| BellowsReport::new(params, code.cloned(), summary, &reader)).transpose()?;
    if let Some(r) = report.as_mut() {
        r.code_section = verdict.is_none();
    }
    match &report {
        Some(report) => println!("\n{}", report.table()),
        None => println!("\nno increment in this run: the closing table is the continued file's (`slideline post` it)"),
    }
    if let (Some(c), Some(f)) = (code, fe) {
        println!("{}", super::report::assessment_section(c, f, life.as_ref()));
    }
    // the tables after the closing one, kept in the file for `slideline post FILE`
    let mut tables: Vec<(&str, String)> = Vec::new();
    if let Some((_, table)) = verdict {
        tables.push((super::report::CODE_VERDICT, table.clone()));
    }
    if let Some((movements, at_rest)) = rest {
        let operating = super::flexibility::from_run(params, *movements, &summary.perturbations, &reader)?;
        tables.push(("flexibility", super::report::flexibility_section(params, code, *movements, at_rest, Some(&operating))));
    }
    // the pictures of modes: the squirm's at rest (drawn from the rest run's file), the first
    // lateral mode's about the run's end
    let mut pictures: Vec<PathBuf> = Vec::new();
    if let Some(at_rest) = stable {
        let operating = super::stability::from_answers(&summary.perturbations)?;
        tables.push(("stability", super::report::stability_section(params, code, at_rest, &operating)));
        pictures.extend(at_rest.squirm.map(|_| picture_path(output, "squirm_mode")));
    }
    if let Some(at_rest) = vibrating {
        let operating = super::vibration::from_answers(params, &summary.perturbations)?;
        tables.push(("frequencies", super::report::frequencies_section(params, at_rest, &operating)));
        if let Some(m) = operating.lateral {
            let path = picture_path(output, &format!("{LATERAL_MODES}_mode"));
            let title = format!("the joint's first lateral mode (n = 1) about the end of the run, {:.1} Hz", m.frequency);
            super::report::mode_picture(&reader, &path, LATERAL_MODES, 1, 1, &title)?;
            pictures.push(path);
        }
    }
    for (_, table) in &tables {
        println!("{table}");
    }
    for path in pictures {
        println!("picture: {}", path.display());
    }
    for (path, what) in report.map(|r| r.pictures(output, &reader)).transpose()?.into_iter().flatten() {
        println!("picture: {} ({what})", path.display());
    }
    drop(reader);
    // the code check and the tables beside the run's results (the file is closed: rank 0 alone
    // opens it)
    crate::io::assessment::write_tables(output, &tables)?;
    if let Some(c) = code {
        crate::io::assessment::write(output, c)?;
    }
    if let (Some(spec), Some((v, _))) = (job.spec(), verdict) {
        crate::io::assessment::write_verdict(output, v, &spec.text, &spec.sha256())?;
    }
    if let Some(f) = fe {
        crate::io::assessment::write_finite_element(output, f, life.as_ref())?;
    }
    // the design report, from the file alone (as `post FILE --report` writes it again), with
    // the picture of the joint beside the run's
    if let Some(path) = &job.report {
        println!("picture: {}", joint_picture(params, output)?.display());
        let reader = ResultsReader::open(output)?;
        let closing = super::report::closing_table_from_file(&reader)?;
        super::report::html::write_design_report(&reader, closing.as_deref(), path)?;
        println!("report: {}", path.display());
    }
    Ok(())
}

/// Writes the joint's mesh (Gmsh .msh next to `output`, and the results file's /mesh) and a
/// picture of where the pressure acts (collective).
pub fn write_mesh(session: &PetscSession, params: &DesignSpec, output: &Path) -> Result<()> {
    let msh = output.with_extension("msh");
    let (mesh, sets) = super::joint::mesh(params)?;
    let root = session.world().rank() == 0;
    if root {
        crate::model::gmsh::write(&mesh, &sets, &msh)?;
    }
    let m = super::joint::model(params)?;
    let partition = Partition::new(session, &m.mesh, &partition_affinity(&m))?;
    drop(ResultsFile::create(output, session, &m, &partition)?);
    if root {
        println!("mesh written to {} and {}", msh.display(), output.display());
        println!("picture: {}", joint_picture(params, output)?.display());
    }
    Ok(())
}

/// The joint's meridian section with the faces the pressure acts on, next to `output`
/// (`STEM_wetted.png`): to check the load before a run, and the report's picture of the joint.
fn joint_picture(params: &DesignSpec, output: &Path) -> Result<PathBuf> {
    let (mesh, sets) = super::joint::mesh(params)?;
    let picture = picture_path(output, "wetted");
    let layers = vec![
        SegmentLayer { label: "boundary".into(), segments: mesh.edge_segments(&mesh.free_edges()), width: 1 },
        SegmentLayer { label: format!("wetted: {} MPa", params.design.pressure), segments: mesh.edge_segments(&sets.surfaces["wetted"]), width: 4 },
    ];
    outline_picture(&picture, "bellows joint: the faces the pressure acts on (meridian section)", &[Panel { caption: None, layers }])?;
    Ok(picture)
}
