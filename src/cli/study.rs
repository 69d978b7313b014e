//! `slideline penalty-study` and `slideline coefficients`: the studies the command line runs.

use super::outcome::{fail, is_bad_input, launched_as_rank_zero, warn_unused_options};
use super::{StudyArgs, SweepArgs};
use mpi::traits::Communicator;
use slideline::assessment::coefficients::Coefficients;
use slideline::petsc::PetscSession;
use slideline::Error;
use std::path::PathBuf;
use std::process::ExitCode;

/// `slideline penalty-study` from start to exit code: the groups of ranks, the study.
pub fn penalty_study_command(args: &StudyArgs) -> ExitCode {
    let session = match PetscSession::initialize_groups(&args.petsc, args.runs.ranks_per_run) {
        Ok(s) => s,
        Err(e) => return fail(&e, launched_as_rank_zero()),
    };
    let root = session.everyone().rank() == 0;
    let result = penalty_study(&session, args);
    warn_unused_options(&session, root && !is_bad_input(&result));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(&e, root),
    }
}

/// `slideline bellows-sweep` from start to exit code: the sweep checked (before MPI and PETSc
/// start: a bad sweep is refused once), the groups of ranks, the sweep.
pub fn sweep_command(args: &SweepArgs) -> ExitCode {
    let spec = match sweep_spec(args) {
        Ok(s) => s,
        Err(e) => return fail(&e, launched_as_rank_zero()),
    };
    let session = match PetscSession::initialize_groups(&args.petsc, args.runs.ranks_per_run) {
        Ok(s) => s,
        Err(e) => return fail(&e, launched_as_rank_zero()),
    };
    let root = session.everyone().rank() == 0;
    let result = slideline::study::sweep::bellows_sweep(&session, &spec);
    warn_unused_options(&session, root && !is_bad_input(&result));
    match result {
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => fail(&e, root),
    }
}

/// `slideline penalty-study`: the study spec for the bellows or a deck, then the runs.
fn penalty_study(session: &PetscSession, args: &StudyArgs) -> Result<(), Error> {
    use slideline::study::{parse_penalties, StudySpec, Subject};
    let penalties = parse_penalties(&args.penalties, args.per_decade)?;
    let mut bellows = slideline::bellows::joint::BellowsParams::default();
    if args.quick {
        bellows = bellows.quick();
    }
    bellows.increments = args.increments.unwrap_or(bellows.increments);
    bellows.displacement = args.displacement.unwrap_or(bellows.displacement);
    bellows.validate()?;
    let subject = match &args.deck {
        // a TOML or an .inp deck, as `slideline run` reads it
        Some(d) => {
            let (model, notes) = slideline::preprocess::prepared_deck(d)?;
            if session.everyone().rank() == 0 && !args.quiet {
                notes.iter().for_each(|note| println!("note: {note}"));
            }
            Subject::Deck(model)
        }
        None => Subject::Bellows(bellows),
    };
    let measures = subject.measures(args.reaction.clone())?;
    let spec = StudySpec {
        subject,
        penalties,
        dimensionless: args.dimensionless,
        augmented: args.augmented,
        measures,
        tolerance: args.tolerance,
        output: args.output.clone(),
        progress: !args.quiet,
        full_output: args.runs.full_output,
    };
    slideline::study::penalty_study(session, &spec).map(|_| ())
}

/// `slideline bellows-sweep`'s keys and their values checked against the specification.
fn sweep_spec(args: &SweepArgs) -> Result<slideline::study::sweep::SweepSpec, Error> {
    use slideline::study::sweep::{parse_vary, Analyses, SweepSpec};
    // the specification itself must stand before its variants are made
    let base = slideline::bellows::spec::DesignSpec::from_file(&args.spec)?.text;
    let vary = args.vary.iter().map(|v| parse_vary(v, &base, &args.spec)).collect::<Result<Vec<_>, _>>()?;
    if let Some(v) = vary.iter().enumerate().find_map(|(k, v)| vary[..k].iter().any(|w| w.name() == v.name()).then_some(v)) {
        return Err(Error::input(format!("--vary {}: given twice", v.name())));
    }
    let analyses = Analyses {
        assess: args.assess,
        squirm: args.squirm,
        frequencies: args.frequencies,
        lateral: args.lateral,
        angular: args.angular,
        elastic_only: args.elastic_only,
    };
    Ok(SweepSpec {
        base,
        path: args.spec.clone(),
        vary,
        analyses,
        sort: args.sort.clone(),
        output: args.output.clone(),
        progress: !args.quiet,
        full_output: args.runs.full_output,
    })
}

/// Each coefficient against C2, a curve per C1 (the codes' charts): PREFIX_cp.png, ...
pub fn coefficient_charts(prefix: &std::path::Path, table: &[(f64, f64, Coefficients)]) -> Result<(), Error> {
    use slideline::io::plots::{line_plot, Axes, Curve};
    let mut c1s: Vec<f64> = table.iter().map(|t| t.0).collect();
    c1s.dedup();
    for (name, pick) in [("cp", (|c: &Coefficients| c.cp) as fn(&Coefficients) -> f64), ("cf", |c| c.cf), ("cd", |c| c.cd)] {
        let curves: Vec<Curve> =
            c1s.iter().map(|&a| Curve { label: format!("C1 = {a}"), points: table.iter().filter(|t| t.0 == a).map(|t| (t.1, pick(&t.2))).collect() }).collect();
        let path = PathBuf::from(format!("{}_{name}.png", prefix.display()));
        let title = format!("C{} of the idealised U-shaped convolution (computed)", &name[1..]);
        line_plot(&path, &title, "C2 = 1.82 rm / sqrt(Dm tp)", &format!("C{}", &name[1..]), &curves, &[], Axes::FromOrigin)?;
        println!("picture: {}", path.display());
    }
    Ok(())
}

/// `slideline coefficients`: every chart point (C1 x C2) checked, then each computed and printed
/// (collective), and the charts drawn at `plot` (rank 0).
pub fn coefficients(session: &PetscSession, c1: &[f64], c2: &[f64], fineness: slideline::bellows::convolution::Fineness, plot: Option<PathBuf>) -> ExitCode {
    let root = session.world().rank() == 0;
    // every point and the mesh checked before any analysis
    let checked = fineness.checked().and_then(|_| {
        c1.iter().flat_map(|&a| c2.iter().map(move |&b| (a, b))).try_for_each(|(a, b)| slideline::bellows::convolution::check_chart_point(a, b, fineness))
    });
    if let Err(e) = checked {
        return fail(&e, root);
    }
    if root {
        println!("chart coefficients of the idealised U-shaped convolution (computed):\n      C1       C2       Cp       Cf       Cd");
    }
    let mut table = Vec::new();
    for &a in c1 {
        for &b in c2 {
            match slideline::bellows::convolution::compute(session, a, b, fineness) {
                Ok(c) => {
                    if root {
                        println!("{a:>8.4} {b:>8.4} {:>8.4} {:>8.4} {:>8.4}", c.cp, c.cf, c.cd);
                    }
                    table.push((a, b, c));
                }
                Err(e) => return fail(&e, root),
            }
        }
    }
    match plot.filter(|_| root).map(|prefix| coefficient_charts(&prefix, &table)) {
        Some(Err(e)) => fail(&e, true),
        _ => ExitCode::SUCCESS,
    }
}
