//! The studies the command line runs, their flags and their dispatch: `slideline
//! penalty-study`, `slideline bellows-sweep` and `slideline coefficients`.

use super::outcome::{fail, is_bad_input, launched_as_rank_zero, warn_unused_options};
use mpi::traits::Communicator;
use slideline::assessment::coefficients::Coefficients;
use slideline::petsc::PetscSession;
use slideline::Error;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct StudyArgs {
    /// A TOML deck to study instead of the bellows (every contact pair gets each penalty).
    #[arg(long)]
    pub deck: Option<PathBuf>,
    /// Penalty values: a range "1e2..1e6" (log-spaced) or a list "1e3,1e4,1e5".
    #[arg(long, default_value = "1e2..1e6")]
    pub penalties: String,
    /// Values per decade of a range.
    #[arg(long, default_value_t = 2)]
    pub per_decade: usize,
    /// The values are the dimensionless kappa (eps = kappa E / h), not N/mm^3.
    #[arg(long)]
    pub dimensionless: bool,
    /// Also run the middle penalty with augmented-Lagrangian updates (the reference).
    #[arg(long)]
    pub augmented: bool,
    /// Reaction tolerance of the recommendation, relative to the reference.
    #[arg(allow_hyphen_values = true, long, default_value_t = 0.01)]
    pub tolerance: f64,
    /// Node set whose axial reaction is compared (bellows: moving_end).
    #[arg(long)]
    pub reaction: Option<String>,
    /// Bellows: the coarse mesh of --quick.
    #[arg(long)]
    pub quick: bool,
    /// Bellows: increments of the compression step.
    #[arg(long)]
    pub increments: Option<usize>,
    /// Bellows: axial compression, mm.
    #[arg(allow_hyphen_values = true, long)]
    pub displacement: Option<f64>,
    /// The study file (HDF5); each run's results go to a directory beside it.
    #[arg(short, long, default_value = "penalty_study.h5")]
    pub output: PathBuf,
    #[command(flatten)]
    pub runs: StudyRuns,
    #[arg(short, long)]
    pub quiet: bool,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    pub petsc: Vec<String>,
}

#[derive(clap::Args)]
pub struct SweepArgs {
    /// The design specification every variant starts from (docs/bellows-spec.md).
    #[arg(long, value_name = "FILE.toml")]
    pub spec: PathBuf,
    /// A key of the specification and its values: KEY=a,b,c (a list), KEY=a..b (the integers
    /// a to b) or KEY=a..b:n (n values from a to b); KEY is section.key, or a key found in one
    /// section. Repeat for more keys: the variants are every combination.
    #[arg(long = "vary", value_name = "KEY=VALUES", required = true)]
    pub vary: Vec<String>,
    #[command(flatten)]
    pub analyses: super::JointAnalyses,
    /// The code check and the analyses of the joint at rest only: no elastic-plastic run of
    /// the design movement.
    #[arg(long)]
    pub elastic_only: bool,
    /// The figure the printed table is sorted by (a column of the study: axial_rate,
    /// allowable_cycles, fe_squirm_pressure, end_force, ..., or a varied key).
    #[arg(long, default_value = "axial_rate", value_name = "FIGURE")]
    pub sort: String,
    /// The study file (HDF5, a CSV beside it); each variant's results go to a directory beside it.
    #[arg(short, long, default_value = "bellows_sweep.h5")]
    pub output: PathBuf,
    #[command(flatten)]
    pub runs: StudyRuns,
    #[arg(short, long)]
    pub quiet: bool,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    pub petsc: Vec<String>,
}

/// How a study shares its runs out over the ranks, and what each keeps.
#[derive(clap::Args)]
pub struct StudyRuns {
    /// Ranks each run uses: the ranks given to mpirun are split into groups of this many, each
    /// taking the next run as it comes free (it must divide the ranks).
    #[arg(long, default_value_t = 1, value_name = "G")]
    pub ranks_per_run: usize,
    /// Keep every increment's fields in each run's file (else its history and each step's end).
    #[arg(long)]
    pub full_output: bool,
}

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
    use slideline::study::{parse_penalties, StudyPlan, Subject};
    let penalties = parse_penalties(&args.penalties, args.per_decade)?;
    let mut bellows = slideline::bellows::spec::DesignSpec::seed();
    if args.quick {
        bellows = bellows.quick();
    }
    bellows.joint.increments = args.increments.unwrap_or(bellows.joint.increments);
    if let Some(d) = args.displacement {
        (bellows.design.axial_compression, bellows.design.axial_extension) = (Some(d), None);
    }
    bellows.validate_joint()?;
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
    let spec = StudyPlan {
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
fn sweep_spec(args: &SweepArgs) -> Result<slideline::study::sweep::SweepPlan, Error> {
    use slideline::study::sweep::{parse_vary, Analyses, SweepPlan};
    // the specification itself must stand before its variants are made
    let base = slideline::bellows::spec::DesignSpec::from_file(&args.spec)?.text;
    let vary = args.vary.iter().map(|v| parse_vary(v, &base, &args.spec)).collect::<Result<Vec<_>, _>>()?;
    if let Some(v) = vary.iter().enumerate().find_map(|(k, v)| vary[..k].iter().any(|w| w.name() == v.name()).then_some(v)) {
        return Err(Error::input(format!("--vary {}: given twice", v.name())));
    }
    let analyses = Analyses {
        assess: args.analyses.assess,
        squirm: args.analyses.squirm,
        frequencies: args.analyses.frequencies,
        lateral: args.analyses.lateral,
        angular: args.analyses.angular,
        elastic_only: args.elastic_only,
    };
    Ok(SweepPlan {
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
        println!(
            "chart coefficients of the idealised U-shaped convolution (computed; the code check takes Cd / {}: its largest excess over the charts' printed points):\n      C1       C2       Cp       Cf       Cd  Cd code",
            slideline::bellows::convolution::CD_EXCESS
        );
    }
    let mut table = Vec::new();
    for &a in c1 {
        for &b in c2 {
            match slideline::bellows::convolution::compute(session, a, b, fineness) {
                Ok(c) => {
                    if root {
                        let code = slideline::bellows::convolution::for_the_code(c);
                        println!("{a:>8.4} {b:>8.4} {:>8.4} {:>8.4} {:>8.4} {:>8.4}", c.cp, c.cf, c.cd, code.cd);
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
