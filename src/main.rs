//! slideline command line: parse, call the library, map errors to exit codes
//! (2 bad input, 3 not converged, 1 other).

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use mpi::traits::Communicator;
use slideline::dist::Partition;
use slideline::io::reader::ResultsReader;
use slideline::io::ResultsFile;
use slideline::petsc::PetscSession;
use slideline::report::{BellowsReport, SECTOR_RADIANS};
use slideline::solve::affinity::partition_affinity;
use slideline::solve::{run, RunOptions, RunSummary};
use slideline::{model, Error};
use std::path::PathBuf;
use std::process::ExitCode;

/// Parallel nonlinear finite-element solver for axisymmetric solids in contact, on PETSc.
///
/// Units throughout: mm, N, MPa, degC. Run in parallel with `mpirun -n 2 slideline run DECK`.
#[derive(Parser)]
#[command(name = "slideline", version, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Analyse an axial bellows expansion joint (the seed paper's DN300 case by default).
    ///
    /// Geometry, material and loads default to the paper's values; every one can be changed
    /// by a flag. Step 1 heats to --temperature with --pressure inside, step 2 compresses the
    /// joint by --displacement in --increments increments.
    Bellows(BellowsArgs),
    /// Run the analysis described by a TOML deck and write results to HDF5 (+ XDMF for ParaView).
    ///
    /// PETSc options go after `--`, e.g.
    /// `slideline run cylinder.toml -- -snes_monitor -ksp_type gmres -pc_type gamg -log_view`.
    /// The PETSC_OPTIONS environment variable is honoured too.
    Run {
        /// The input deck: TOML (see README), or an Abaqus/CalculiX deck (.inp; the subset in the
        /// README's "Abaqus/CalculiX input" section).
        deck: PathBuf,
        /// Results file (HDF5). Default: the deck's name with extension .h5, in the current directory.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// No progress lines.
        #[arg(short, long)]
        quiet: bool,
        /// PETSc options (after `--`).
        #[arg(last = true, allow_hyphen_values = true)]
        petsc: Vec<String>,
    },
    /// Read a results file: the run's summary and history, a field at an increment, a node's
    /// or set's time series, two runs side by side, the force-displacement picture. No MPI.
    Post(PostArgs),
    /// Run one model for a range of penalty values (and with the augmented Lagrangian) and
    /// compare iterations, penetration and reaction: the bellows (default) or a deck.
    PenaltyStudy(StudyArgs),
}

#[derive(clap::Args)]
struct StudyArgs {
    /// A TOML deck to study instead of the bellows (every contact pair gets each penalty).
    #[arg(long)]
    deck: Option<PathBuf>,
    /// Penalty values: a range "1e2..1e6" (log-spaced) or a list "1e3,1e4,1e5".
    #[arg(long, default_value = "1e2..1e6")]
    penalties: String,
    /// Values per decade of a range.
    #[arg(long, default_value_t = 2)]
    per_decade: usize,
    /// The values are the dimensionless kappa (eps = kappa E / h), not N/mm^3.
    #[arg(long)]
    dimensionless: bool,
    /// Also run the middle penalty with augmented-Lagrangian updates (the reference).
    #[arg(long)]
    augmented: bool,
    /// Reaction tolerance of the recommendation, relative to the reference.
    #[arg(long, default_value_t = 0.01)]
    tolerance: f64,
    /// Node set whose axial reaction is compared (bellows: moving_end).
    #[arg(long)]
    reaction: Option<String>,
    /// Bellows: the coarse mesh of --quick.
    #[arg(long)]
    quick: bool,
    /// Bellows: increments of the compression step.
    #[arg(long)]
    increments: Option<usize>,
    /// Bellows: axial compression, mm.
    #[arg(long)]
    displacement: Option<f64>,
    /// The study file (HDF5); each run's results go to a directory beside it.
    #[arg(short, long, default_value = "penalty_study.h5")]
    output: PathBuf,
    #[arg(short, long)]
    quiet: bool,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    petsc: Vec<String>,
}

/// `slideline penalty-study`: the study spec for the bellows or a deck, then the runs.
fn penalty_study(session: &PetscSession, args: &StudyArgs) -> Result<(), Error> {
    use slideline::study::{parse_penalties, StudySpec, Subject};
    let penalties = parse_penalties(&args.penalties, args.per_decade)?;
    let mut bellows = model::bellows::BellowsParams::default();
    if args.quick {
        bellows = bellows.quick();
    }
    bellows.increments = args.increments.unwrap_or(bellows.increments);
    bellows.displacement = args.displacement.unwrap_or(bellows.displacement);
    bellows.validate()?;
    let subject = match &args.deck {
        Some(d) => Subject::Deck(model::deck::read(d)?),
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
    };
    slideline::study::penalty_study(session, &spec).map(|_| ())
}

#[derive(clap::Args)]
struct PostArgs {
    /// The results file (HDF5) of a run.
    file: PathBuf,
    /// Write the history table as CSV to this file (all columns, full precision).
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Field to report (displacement, stress, von_mises, von_mises_mean,
    /// equivalent_plastic_strain, equivalent_plastic_strain_max): min/max and where.
    #[arg(long, requires = "increment")]
    field: Option<String>,
    /// Increment (1-based, as in the history) for --field.
    #[arg(long)]
    increment: Option<usize>,
    /// Time series of the node with this external number.
    #[arg(long)]
    node: Option<u64>,
    /// Time series of this node set (its reaction if constrained, else its mean displacement).
    #[arg(long)]
    set: Option<String>,
    /// Another results file: the two histories side by side.
    #[arg(long)]
    compare: Option<PathBuf>,
    /// Write FILE_force.png (axial reactions against time).
    #[arg(long)]
    plot: bool,
    /// Print the deck text stored in the file.
    #[arg(long)]
    deck: bool,
}

/// `slideline post`: without options the summary and the history; each option adds its report.
fn post(args: &PostArgs) -> Result<(), Error> {
    use slideline::post;
    let r = ResultsReader::open(&args.file)?;
    let detail = args.field.is_some() || args.node.is_some() || args.set.is_some() || args.compare.is_some() || args.csv.is_some() || args.plot || args.deck;
    if !detail {
        print!("{}\n{}", post::summary(&r)?, post::history_table(&r)?);
    }
    if args.deck {
        println!("{}", r.text_attr("deck")?);
    }
    if let Some(path) = &args.csv {
        std::fs::write(path, post::history_csv(&r)?).map_err(|e| Error::Output { path: path.clone(), message: e.to_string() })?;
        println!("history written to {}", path.display());
    }
    if let Some(name) = &args.field {
        print!("{}", post::field(&r, name, args.increment.unwrap_or(0))?);
    }
    if let Some(id) = args.node {
        print!("{}", post::node_series(&r, id)?);
    }
    if let Some(set) = &args.set {
        print!("{}", post::set_series(&r, set)?);
    }
    if let Some(other) = &args.compare {
        print!("{}", post::compare(&r, &ResultsReader::open(other)?)?);
    }
    if args.plot {
        println!("picture: {}", post::plot(&r)?.display());
    }
    Ok(())
}

/// Flags of `slideline bellows` (mm, MPa, degC).
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
struct BellowsArgs {
    /// A TOML file of joint parameters (any field of BellowsParams, e.g. examples/bellows.toml);
    /// flags given on the command line override it.
    #[arg(long)]
    params: Option<PathBuf>,
    /// Number of plies in the pack.
    #[arg(long, default_value_t = 2)]
    plies: usize,
    /// Thickness of each ply, mm.
    #[arg(long, default_value_t = 1.0)]
    ply_thickness: f64,
    /// Number of convolutions.
    #[arg(long, default_value_t = 6)]
    convolutions: usize,
    /// Convolution pitch, mm (4 x torus radius for U shapes).
    #[arg(long, default_value_t = 24.0)]
    pitch: f64,
    /// Convolution height w (mid-surface, root to crest), mm.
    #[arg(long, default_value_t = 20.0)]
    height: f64,
    /// Mean radius of the root and crest tori, mm.
    #[arg(long, default_value_t = 6.0)]
    torus_radius: f64,
    /// Axial compression of the joint, mm.
    #[arg(long, default_value_t = 70.0)]
    displacement: f64,
    /// Increments of the compression step.
    #[arg(long, default_value_t = 240)]
    increments: usize,
    /// Contact penalty, N/mm^3 (MPa per mm of penetration).
    #[arg(long, default_value_t = 1.0e4)]
    penalty: f64,
    /// Operating temperature, degC (from 20).
    #[arg(long, default_value_t = 200.0)]
    temperature: f64,
    /// Internal pressure, MPa (0.6 = 6 bar).
    #[arg(long, default_value_t = 0.6)]
    pressure: f64,
    /// Initial yield stress, MPa.
    #[arg(long, default_value_t = 300.0)]
    yield_stress: f64,
    /// Linear isotropic hardening modulus, MPa.
    #[arg(long, default_value_t = 1000.0)]
    hardening: f64,
    /// Element length along the plies, mm.
    #[arg(long, default_value_t = 1.0)]
    ply_element_length: f64,
    /// Elements through each ply.
    #[arg(long, default_value_t = 2)]
    ply_elements: usize,
    /// A coarse, quick version of the same case (about a minute).
    #[arg(long)]
    quick: bool,
    /// Write the mesh (Gmsh .msh next to --output) and stop.
    #[arg(long)]
    mesh_only: bool,
    /// Results file (HDF5).
    #[arg(short, long, default_value = "bellows.h5")]
    output: PathBuf,
    /// No progress lines.
    #[arg(short, long)]
    quiet: bool,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    petsc: Vec<String>,
}

impl BellowsArgs {
    /// The joint's parameters: the defaults (the seed case) or the `--params` file, then every
    /// flag given on the command line (`given(id)`), then `--quick`.
    fn params(&self, given: impl Fn(&str) -> bool) -> Result<model::bellows::BellowsParams, Error> {
        let mut p = match &self.params {
            Some(path) => model::bellows::BellowsParams::from_toml_file(path)?,
            None => model::bellows::BellowsParams::default(),
        };
        let from_file = self.params.is_some();
        let mut take = |id: &str, set: &mut dyn FnMut(&mut model::bellows::BellowsParams)| {
            if !from_file || given(id) {
                set(&mut p);
            }
        };
        take("plies", &mut |p| p.plies = self.plies);
        take("ply_thickness", &mut |p| p.ply_thickness = self.ply_thickness);
        take("convolutions", &mut |p| p.convolutions = self.convolutions);
        take("pitch", &mut |p| p.pitch = self.pitch);
        take("height", &mut |p| p.height = self.height);
        take("torus_radius", &mut |p| p.torus_radius = self.torus_radius);
        take("displacement", &mut |p| p.displacement = self.displacement);
        take("increments", &mut |p| p.increments = self.increments);
        take("penalty", &mut |p| p.penalty = self.penalty);
        take("temperature", &mut |p| p.temperature = self.temperature);
        take("pressure", &mut |p| p.pressure = self.pressure);
        take("yield_stress", &mut |p| p.yield_stress = self.yield_stress);
        take("hardening", &mut |p| p.hardening_modulus = self.hardening);
        take("ply_element_length", &mut |p| p.ply_element_length = self.ply_element_length);
        take("ply_elements", &mut |p| p.ply_elements = self.ply_elements);
        Ok(if self.quick { p.quick() } else { p })
    }
}

fn main() -> ExitCode {
    let matches = Cli::command().get_matches();
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    match cli.command {
        Command::Bellows(args) => {
            let sub = matches.subcommand_matches("bellows");
            let given = |id: &str| sub.and_then(|m| m.value_source(id)) == Some(clap::parser::ValueSource::CommandLine);
            // bad flags and parameter files are reported before MPI and PETSc start
            let params = match args.params(given).and_then(|p| p.validate().map(|()| p)) {
                Ok(p) => p,
                Err(e) => return fail(&e, true),
            };
            let session = match PetscSession::initialize(&args.petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, true),
            };
            if args.mesh_only {
                return match write_mesh(&session, &params, &args.output) {
                    Ok(()) => ExitCode::SUCCESS,
                    Err(e) => fail(&e, session.world().rank() == 0),
                };
            }
            let root = session.world().rank() == 0;
            if root && !args.quiet {
                let ejma = model::bellows::ejma_axial_rate(&params, EJMA_CF);
                println!("bellows: {} plies x {} mm, {} convolutions, pitch {}, height {}; EJMA axial rate {:.1} N/mm full ring, {:.2} N/mm per 2.5-degree sector (Cf = {EJMA_CF})", params.plies, params.ply_thickness, params.convolutions, params.pitch, params.height, ejma, ejma * 2.5 / 360.0);
            }
            let result = model::bellows::model(&params).and_then(|m| run(&session, &m, &RunOptions { output: args.output.clone(), progress: !args.quiet }));
            finish(result, root, |summary| report(&params, summary, &args.output))
        }
        Command::PenaltyStudy(args) => {
            let session = match PetscSession::initialize(&args.petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, true),
            };
            let root = session.world().rank() == 0;
            match penalty_study(&session, &args) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&e, root),
            }
        }
        Command::Post(args) => match post(&args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e, true),
        },
        Command::Run { deck, output, quiet, petsc } => {
            let session = match PetscSession::initialize(&petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, true),
            };
            let root = session.world().rank() == 0;
            let output = output.unwrap_or_else(|| PathBuf::from(deck.file_stem().unwrap_or_default()).with_extension("h5"));
            let model = model::read_deck(&deck).map(|(m, notes)| {
                if root && !quiet {
                    notes.iter().for_each(|note| println!("note: {note}"));
                }
                m
            });
            let segment = model.as_ref().ok().and_then(|m| m.reaction_segment_degrees);
            let result = model.and_then(|m| run(&session, &m, &RunOptions { output, progress: !quiet }));
            finish(result, root, |summary| {
                if let (Some(degrees), Some(last)) = (segment, summary.history.last()) {
                    // CalculiX's convention, for reading beside its .dat file
                    println!("final reactions per {degrees}-degree segment (N, as CalculiX prints them):");
                    for (set, f) in &last.reactions {
                        println!("  {:<20} {:>14.6e} {:>14.6e}", set, f[0] * degrees.to_radians(), f[1] * degrees.to_radians());
                    }
                }
                Ok(())
            })
        }
    }
}

/// `--mesh-only`: the joint's mesh and sets as Gmsh 4.1 (OUTPUT with .msh) and as a results
/// file without increments (OUTPUT: /mesh with its sets, the layout of every results file).
fn write_mesh(session: &PetscSession, params: &model::bellows::BellowsParams, output: &std::path::Path) -> Result<(), Error> {
    let msh = output.with_extension("msh");
    let (mesh, sets) = model::bellows::mesh(params)?;
    let root = session.world().rank() == 0;
    if root {
        model::gmsh::write(&mesh, &sets, &msh)?;
    }
    let m = model::bellows::model(params)?;
    let partition = Partition::new(session, &m.mesh, &partition_affinity(&m))?;
    drop(ResultsFile::create(output, session, &m, &partition)?);
    if root {
        println!("mesh written to {} and {}", msh.display(), output.display());
    }
    Ok(())
}

/// The bellows closing table (slideline beside the paper) and the pictures, from the results
/// file (rank 0, after the run).
fn report(params: &model::bellows::BellowsParams, summary: &RunSummary, output: &std::path::Path) -> Result<(), Error> {
    let reader = ResultsReader::open(output)?;
    let ejma = model::bellows::ejma_axial_rate(params, EJMA_CF) * SECTOR_RADIANS / (2.0 * std::f64::consts::PI);
    let report = BellowsReport::new(params, ejma, EJMA_CF, &summary.history, summary.wall_time, summary.ranks, &reader)?;
    println!("\n{}", report.table());
    for path in report.pictures(output, &reader)? {
        println!("picture: {}", path.display());
    }
    Ok(())
}

/// EJMA's C_f for the default convolution proportions (from the EJMA chart; approximate).
const EJMA_CF: f64 = 1.9;

/// Rank 0 prints the summary (then runs `then`, the subcommand's own report) or the error;
/// every rank returns the exit code.
fn finish(result: Result<RunSummary, Error>, root: bool, then: impl FnOnce(&RunSummary) -> Result<(), Error>) -> ExitCode {
    match result {
        Ok(summary) => {
            if root {
                print_summary(&summary);
                if let Err(e) = then(&summary) {
                    return fail(&e, true);
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e, root),
    }
}

fn fail(e: &Error, print: bool) -> ExitCode {
    if print {
        eprintln!("error: {e}");
    }
    ExitCode::from(e.exit_code() as u8)
}

fn print_summary(summary: &RunSummary) {
    let Some(last) = summary.history.last() else {
        return;
    };
    println!("done: {} increments in {:.2} s on {} rank(s)", summary.history.len(), summary.wall_time, summary.ranks);
    if summary.reserved_couplings > 0 {
        println!(
            "Jacobian pattern: {} contact couplings (node pairs, counted on each rank that needs them) reserved by the end; matrix refitted in place {} time(s)",
            summary.reserved_couplings, summary.pattern_refits
        );
    }
    if !last.reactions.is_empty() {
        println!("final reactions (N):            per radian                      full 360-degree ring");
        println!("  {:<20} {:>14} {:>14}   {:>14} {:>14}", "set", "F_r", "F_z", "F_r", "F_z");
        let ring = 2.0 * std::f64::consts::PI;
        for (set, f) in &last.reactions {
            println!("  {:<20} {:>14.6e} {:>14.6e}   {:>14.6e} {:>14.6e}", set, f[0], f[1], f[0] * ring, f[1] * ring);
        }
    }
}
