//! slideline command line: parse, call the library, map errors to exit codes
//! (2 bad input, 3 not converged, 1 other).

mod cli;

use clap::{CommandFactory, FromArgMatches};
use cli::{Cli, Command, PostArgs, StudyArgs};
use mpi::traits::Communicator;
use slideline::assessment::code::{CodeCheck, Duty, Source};
use slideline::assessment::coefficients::Coefficients;
use slideline::bellows::flexibility::{Flexibility, Movements};
use slideline::bellows::report::BellowsReport;
use slideline::bellows::{stability::SQUIRM, vibration::LATERAL_MODES};
use slideline::dist::Partition;
use slideline::io::plots::{outline_picture, Panel, SegmentLayer};
use slideline::io::reader::ResultsReader;
use slideline::io::ResultsFile;
use slideline::petsc::PetscSession;
use slideline::solve::affinity::partition_affinity;
use slideline::solve::{run, RunOptions, RunSummary};
use slideline::{model, Error};
use std::path::PathBuf;
use std::process::ExitCode;

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
            if session.world().rank() == 0 && !args.quiet {
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
    };
    slideline::study::penalty_study(session, &spec).map(|_| ())
}

/// `slideline post`: without options the summary and the history; each option adds its report.
/// Everything is checked before anything is written, and the text goes out at the end, once:
/// a reader that closes the pipe early (`| head`) ends it quietly, as `cat` does.
fn post(args: &PostArgs) -> Result<(), Error> {
    use slideline::post;
    let r = ResultsReader::open(&args.file)?;
    r.notes()?.iter().for_each(|note| eprintln!("note: {note}"));
    if args.increment.is_some() && args.field.is_none() && args.linearize.is_empty() {
        return Err(Error::input("--increment goes with --field or --linearize (the other reports cover every increment)"));
    }
    if args.force && args.compare.is_none() {
        return Err(Error::input("--force goes with --compare"));
    }
    let plot = args.plot.as_ref().map(|p| p.clone().unwrap_or_else(|| post::default_plot_path(&r)));
    for path in args.csv.iter().chain(&plot) {
        slideline::output_path::check_output_path(path, Some((&args.file, "the results file")))?;
    }
    let increment = args.increment.as_deref().unwrap_or("last");
    let detail = args.field.is_some()
        || args.node.is_some()
        || args.set.is_some()
        || args.compare.is_some()
        || args.csv.is_some()
        || plot.is_some()
        || args.deck
        || !args.linearize.is_empty();
    let heat = r.heat_steps()?;
    if !heat.is_empty()
        && (args.field.is_some() || args.node.is_some() || args.set.is_some() || args.csv.is_some() || plot.is_some() || !args.linearize.is_empty())
    {
        return Err(Error::input(format!(
            "{}: a heat-conduction run has no increments; its fields are /heat/{}/temperature and .../flux (h5py), or the sidecar {}_{}.xmf in ParaView",
            args.file.display(),
            heat[0].0,
            args.file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            heat[0].0
        )));
    }
    let mut out = String::new();
    if !detail {
        out += &format!("{}\n{}", post::summary(&r)?, post::history_table(&r, args.verbose)?);
        // a bellows run's closing table, as the run printed it
        // (what a damaged file cannot give again is said, not fatal: post reads what is left)
        match post::bellows_table(&r) {
            Ok(Some(table)) => out += &format!("\n{table}"),
            Ok(None) => {}
            Err(e) => out += &format!("\nnote: the closing table cannot be printed again: {e}\n"),
        }
        // and the tables after it (flexibility, stability, frequencies), word for word
        match r.printed_tables() {
            Ok(tables) => tables.iter().for_each(|(_, table)| out += &format!("{table}\n")),
            Err(e) => out += &format!("\nnote: the tables after the closing one cannot be printed again: {e}\n"),
        }
    }
    if args.deck {
        out += &format!("{}\n", r.text_attr("deck")?);
    }
    if args.assessment {
        match r.assessment()? {
            Some(check) => {
                out += &slideline::bellows::report::code_section(&check);
                if let Some((fe, life)) = r.finite_element_assessment()? {
                    out += &slideline::bellows::report::assessment_section(&check, &fe, life.as_ref());
                }
            }
            None => return Err(Error::input(format!("{}: no code check in the file (`slideline bellows` writes one)", args.file.display()))),
        }
    }
    if let Some(path) = &args.csv {
        std::fs::write(path, post::history_csv(&r)?).map_err(|e| Error::Output { path: path.clone(), message: e.to_string() })?;
        out += &format!("history written to {}\n", path.display());
    }
    if let Some(name) = &args.field {
        out += &post::field(&r, name, post::increment_number(&r, increment)?)?;
    }
    if let Some(id) = args.node {
        out += &post::node_series(&r, id)?;
    }
    if let Some(set) = &args.set {
        out += &post::set_series(&r, set)?;
    }
    if let Some(other) = &args.compare {
        out += &post::compare(&r, &ResultsReader::open(other)?, args.force)?;
    }
    if let Some(path) = &plot {
        out += &format!("picture: {}\n", post::plot(&r, path)?.display());
    }
    if !args.linearize.is_empty() {
        out += &post::linearize(&r, &args.linearize, post::increment_number(&r, increment)?)?;
    }
    print_quietly_on_closed_pipe(&out)
}

/// Writes `text` to standard output; a closed pipe (the reader has what it wanted) is no error.
fn print_quietly_on_closed_pipe(text: &str) -> Result<(), Error> {
    use std::io::Write as _;
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(text.as_bytes()).and_then(|_| stdout.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Error::Output { path: "standard output".into(), message: e.to_string() }),
        _ => Ok(()),
    }
}

fn main() -> ExitCode {
    let matches = match Cli::command().try_get_matches() {
        Ok(m) => m,
        // under mpirun every rank parses the same line: one of them says what is wrong
        Err(e) if launched_as_rank_zero() => e.exit(),
        Err(e) => return ExitCode::from(e.exit_code() as u8),
    };
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(cli) => cli,
        Err(e) if launched_as_rank_zero() => e.exit(),
        Err(e) => return ExitCode::from(e.exit_code() as u8),
    };
    match cli.command {
        Command::Bellows(args) => {
            let sub = matches.subcommand_matches("bellows");
            let given = |id: &str| sub.and_then(|m| m.value_source(id)) == Some(clap::parser::ValueSource::CommandLine);
            // bad flags and parameter files are reported before MPI and PETSc start
            let params = match args.params(given).and_then(|p| p.validate().map(|()| p)) {
                Ok(p) => p,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            // the movements of the flexibility perturbations, if any
            let movements = match args.movements(&params) {
                Ok(m) => m,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            if let Some(path) = &args.export_inp {
                // checked before any work; never the --params file it may come from
                if let Err(e) = slideline::output_path::check_output_path(path, args.params.as_deref().map(|p| (p, "the --params file"))) {
                    return fail(&e, launched_as_rank_zero());
                }
                // no MPI needed: every rank would write the same file
                return match slideline::bellows::joint::model(&params).and_then(|m| model::inp::write(&m, &params.title(), path)) {
                    Ok(()) => {
                        println!("deck written to {}", path.display());
                        ExitCode::SUCCESS
                    }
                    Err(e) => fail(&e, launched_as_rank_zero()),
                };
            }
            if let Err(e) = slideline::output_path::check_output_path(&args.output, args.params.as_deref().map(|p| (p, "the --params file"))) {
                return fail(&e, launched_as_rank_zero());
            }
            let session = match PetscSession::initialize(&args.petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            if args.mesh_only {
                return match write_mesh(&session, &params, &args.output) {
                    Ok(()) => ExitCode::SUCCESS,
                    Err(e) => fail(&e, session.world().rank() == 0),
                };
            }
            let root = session.world().rank() == 0;
            // the code check, with the chart coefficients given or computed for the joint's own
            // convolution (collective)
            let code = code_check(&session, &params);
            if let (true, Err(e)) = (root, &code) {
                println!("note: no code check: {e}");
            }
            let code = code.ok();
            // the analyses of their own before the main run (collective), each announced
            let announce = |what: &str| {
                if root && !args.quiet {
                    println!("{what} ...");
                }
            };
            // the instability pressures of the joint at rest (for --squirm and --assess, once)
            let stable = (args.squirm || args.assess).then(|| {
                announce("stability: the joint at rest and its buckling analyses");
                // the squirm's mode at rest, pictured from the rest run's file (rank 0; a picture
                // that fails is a note: the other ranks go on)
                let picture = picture_path(&args.output, "squirm_mode");
                slideline::bellows::stability::at_rest(&session, &params, |file, s| {
                    if let (true, true, Some(p)) = (root, args.squirm, s.squirm) {
                        let title = format!("the joint's squirm at rest, {p:.1} MPa: its column buckling mode (n = 1)");
                        let drawn = ResultsReader::open(file).and_then(|r| slideline::bellows::report::mode_picture(&r, &picture, SQUIRM, 1, 1, &title));
                        if let Err(e) = drawn {
                            println!("note: no picture of the squirm's mode: {e}");
                        }
                    }
                })
            });
            let stable = match stable.transpose() {
                Ok(s) => s,
                Err(e) => return fail(&e, root),
            };
            let vibrating = args.frequencies.then(|| {
                announce("natural frequencies: the joint at rest and its frequency analyses");
                slideline::bellows::vibration::at_rest(&session, &params)
            });
            let vibrating = match vibrating.transpose() {
                Ok(v) => v,
                Err(e) => return fail(&e, root),
            };
            // the finite-element side of the assessment, and the flexibility of the joint at rest
            let fe = stable.as_ref().filter(|_| args.assess).map(|s| {
                announce("assessment: linear elastic analyses of the design pressure and of the stroke");
                slideline::bellows::finite_element::analyse(&session, &params, s)
            });
            let rest = movements.map(|m| {
                announce("flexibility: the joint at rest and its harmonic perturbations");
                slideline::bellows::flexibility::at_rest(&session, &params, m).map(|f| (m, f))
            });
            let (fe, rest) = match (fe.transpose(), rest.transpose()) {
                (Ok(fe), Ok(rest)) => (fe, rest),
                (Err(e), _) | (_, Err(e)) => return fail(&e, root),
            };
            // the stability section is --squirm's
            let stable = stable.filter(|_| args.squirm);
            if let (true, false, Some(c)) = (root, args.quiet, &code) {
                let k = c.coefficients;
                println!(
                    "bellows: {} plies x {} mm, {} convolutions, pitch {}, height {}; EJMA axial rate {:.1} N/mm full ring, {:.2} N/mm per 2.5-degree sector (C1 = {:.3}, C2 = {:.3}: Cp {:.3}, Cf {:.3}, Cd {:.3} {})",
                    params.plies, params.ply_thickness, params.convolutions, params.pitch, params.height, c.axial_rate, c.axial_rate * 2.5 / 360.0, c.c1, c.c2, k.cp, k.cf, k.cd, c.source.label()
                );
            }
            let result = slideline::bellows::joint::model(&params).and_then(|mut m| {
                // the same perturbations about the run's end state
                if let Some(movements) = movements {
                    m.perturbations = slideline::bellows::flexibility::steps(&params, movements);
                }
                // the axial rate's step is shared by the flexibility's, the stability's and the
                // frequencies'
                let stability = args.squirm.then(|| slideline::bellows::stability::steps(&params));
                let vibration = args.frequencies.then(|| slideline::bellows::vibration::steps(&params));
                for more in stability.into_iter().chain(vibration) {
                    let have: Vec<String> = m.perturbations.iter().map(|s| s.name.clone()).collect();
                    m.perturbations.extend(more.into_iter().filter(|s| !have.contains(&s.name)));
                }
                m.validate()?;
                run(
                    &session,
                    &m,
                    &RunOptions {
                        output: args.output.clone(),
                        progress: !args.quiet,
                        verbose: args.verbose,
                        monitor: args.monitor,
                        restart: restart_from(&args.restart, args.increment),
                    },
                )
            });
            warn_unused_options(&session, root && !is_bad_input(&result));
            finish(result, root, |summary| {
                report(
                    &params,
                    &BeforeTheRun { code: code.as_ref(), fe: fe.as_ref(), rest: rest.as_ref(), stable: stable.as_ref(), vibrating: vibrating.as_ref() },
                    summary,
                    &args.output,
                )
            })
        }
        Command::PenaltyStudy(args) => {
            let session = match PetscSession::initialize(&args.petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            let root = session.world().rank() == 0;
            let result = penalty_study(&session, &args);
            warn_unused_options(&session, root && !is_bad_input(&result));
            match result {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&e, root),
            }
        }
        Command::Coefficients { c1, c2, through, per_thickness, plot, petsc } => {
            let session = match PetscSession::initialize(&petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            let root = session.world().rank() == 0;
            let fineness = slideline::bellows::convolution::Fineness { through, per_thickness };
            // every point and the mesh checked before any analysis
            let checked = fineness.checked().and_then(|_| {
                c1.iter()
                    .flat_map(|&a| c2.iter().map(move |&b| (a, b)))
                    .try_for_each(|(a, b)| slideline::bellows::convolution::check_chart_point(a, b, fineness))
            });
            if let Err(e) = checked {
                return fail(&e, root);
            }
            if root {
                println!("chart coefficients of the idealised U-shaped convolution (computed):\n      C1       C2       Cp       Cf       Cd");
            }
            let mut table = Vec::new();
            for &a in &c1 {
                for &b in &c2 {
                    match slideline::bellows::convolution::compute(&session, a, b, fineness) {
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
        Command::Post(args) => match post(&args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e, true),
        },
        Command::Run { deck, output, quiet, verbose, monitor, restart, increment, convergence, output_precision, petsc } => {
            let output = output.unwrap_or_else(|| PathBuf::from(deck.file_stem().unwrap_or_default()).with_extension("h5"));
            if let Err(e) = slideline::output_path::check_output_path(&output, Some((&deck, "the input deck"))) {
                return fail(&e, launched_as_rank_zero());
            }
            let session = match PetscSession::initialize(&petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            let root = session.world().rank() == 0;
            let model = slideline::preprocess::prepared_deck(&deck).map(|(m, notes)| {
                if root && !quiet {
                    notes.iter().for_each(|note| println!("note: {note}"));
                }
                let mut m = m;
                if let Some(c) = convergence {
                    m.stepping.convergence = c.into();
                }
                if let Some(p) = output_precision {
                    m.output.precision = p.into();
                }
                m
            });
            let segment = model.as_ref().ok().and_then(|m| m.reaction_segment_degrees);
            let result =
                model.and_then(|m| run(&session, &m, &RunOptions { output, progress: !quiet, verbose, monitor, restart: restart_from(&restart, increment) }));
            warn_unused_options(&session, root && !is_bad_input(&result));
            finish(result, root, |summary| {
                // CalculiX's convention, for reading beside its .dat file
                let Some(degrees) = segment else { return Ok(()) };
                if let Some(last) = summary.history.last() {
                    println!("final reactions per {degrees}-degree segment (N, as CalculiX prints them):");
                    for (set, f) in &last.reactions {
                        println!("  {:<20} {:>14.6e} {:>14.6e}", set, f[0] * degrees.to_radians(), f[1] * degrees.to_radians());
                    }
                }
                for (name, answer) in &summary.heat {
                    println!("heat step '{name}': heat flowing in per {degrees}-degree segment (as CalculiX prints RFL):");
                    for f in &answer.flows {
                        println!("  {:<20} {:>14.6e}", f.set, f.flow * degrees.to_radians());
                    }
                }
                Ok(())
            })
        }
    }
}

/// The restart a run's flags ask for.
fn restart_from(file: &Option<PathBuf>, increment: Option<usize>) -> Option<slideline::io::restart::RestartFrom> {
    file.clone().map(|file| slideline::io::restart::RestartFrom { file, increment })
}

/// `OUTPUT_name.png` beside the output.
fn picture_path(output: &std::path::Path, name: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}_{name}.png"))
}

/// `--mesh-only`: the joint's mesh and sets as Gmsh 4.1 (OUTPUT with .msh) and as a results
/// file without increments (OUTPUT: /mesh with its sets, the layout of every results file).
fn write_mesh(session: &PetscSession, params: &slideline::bellows::joint::BellowsParams, output: &std::path::Path) -> Result<(), Error> {
    let msh = output.with_extension("msh");
    let (mesh, sets) = slideline::bellows::joint::mesh(params)?;
    let root = session.world().rank() == 0;
    if root {
        model::gmsh::write(&mesh, &sets, &msh)?;
    }
    let m = slideline::bellows::joint::model(params)?;
    let partition = Partition::new(session, &m.mesh, &partition_affinity(&m))?;
    drop(ResultsFile::create(output, session, &m, &partition)?);
    if root {
        println!("mesh written to {} and {}", msh.display(), output.display());
        // where the pressure acts, to check the load before a run
        let picture = picture_path(output, "wetted");
        let layers = vec![
            SegmentLayer { label: "boundary".into(), segments: mesh.edge_segments(&mesh.free_edges()), width: 1 },
            SegmentLayer { label: format!("wetted: {} MPa", params.pressure), segments: mesh.edge_segments(&sets.surfaces["wetted"]), width: 4 },
        ];
        outline_picture(&picture, "bellows joint: the faces the pressure acts on (meridian section)", &[Panel { caption: None, layers }])?;
        println!("picture: {}", picture.display());
    }
    Ok(())
}

/// What the bellows' own analyses before the main run found, for its report: the code check,
/// the finite-element assessment, and the flexibility, stability and natural frequencies of the
/// joint at rest.
struct BeforeTheRun<'a> {
    code: Option<&'a CodeCheck>,
    fe: Option<&'a slideline::assessment::fe_check::FeCheck>,
    rest: Option<&'a (Movements, Flexibility)>,
    stable: Option<&'a slideline::bellows::stability::Stability>,
    vibrating: Option<&'a slideline::bellows::vibration::Frequencies>,
}

/// The bellows closing table (slideline beside the paper) and the pictures, from the results
/// file (rank 0, after the run).
fn report(params: &slideline::bellows::joint::BellowsParams, before: &BeforeTheRun<'_>, summary: &RunSummary, output: &std::path::Path) -> Result<(), Error> {
    let BeforeTheRun { code, fe, rest, stable, vibrating } = *before;
    let reader = ResultsReader::open(output)?;
    let life = match fe {
        Some(_) => slideline::bellows::finite_element::strain_life(&reader, params.youngs_modulus)?,
        None => None,
    };
    // a restart from a finished run's end writes no increment of its own: its fields are in
    // the file it continued
    let fields = !reader.increments()?.is_empty();
    let report = fields.then(|| BellowsReport::new(params, code.cloned(), summary, &reader)).transpose()?;
    match &report {
        Some(report) => println!("\n{}", report.table()),
        None => println!("\nno increment in this run: the closing table is the continued file's (`slideline post` it)"),
    }
    if let (Some(c), Some(f)) = (code, fe) {
        println!("{}", slideline::bellows::report::assessment_section(c, f, life.as_ref()));
    }
    // the tables after the closing one, kept in the file for `slideline post FILE`
    let mut tables: Vec<(&str, String)> = Vec::new();
    if let Some((movements, at_rest)) = rest {
        let operating = slideline::bellows::flexibility::from_run(params, *movements, &summary.perturbations, &reader)?;
        tables.push(("flexibility", slideline::bellows::report::flexibility_section(params, code, *movements, at_rest, Some(&operating))));
    }
    // the pictures of modes: the squirm's at rest (drawn from the rest run's file), the first
    // lateral mode's about the run's end
    let mut pictures: Vec<PathBuf> = Vec::new();
    if let Some(at_rest) = stable {
        let operating = slideline::bellows::stability::from_answers(&summary.perturbations)?;
        tables.push(("stability", slideline::bellows::report::stability_section(params, code, at_rest, &operating)));
        pictures.extend(at_rest.squirm.map(|_| picture_path(output, "squirm_mode")));
    }
    if let Some(at_rest) = vibrating {
        let operating = slideline::bellows::vibration::from_answers(params, &summary.perturbations)?;
        tables.push(("frequencies", slideline::bellows::report::frequencies_section(params, at_rest, &operating)));
        if let Some(m) = operating.lateral {
            let path = picture_path(output, &format!("{LATERAL_MODES}_mode"));
            let title = format!("the joint's first lateral mode (n = 1) about the end of the run, {:.1} Hz", m.frequency);
            slideline::bellows::report::mode_picture(&reader, &path, LATERAL_MODES, 1, 1, &title)?;
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
    slideline::io::assessment::write_tables(output, &tables)?;
    if let Some(c) = code {
        slideline::io::assessment::write(output, c)?;
    }
    fe.map_or(Ok(()), |f| slideline::io::assessment::write_finite_element(output, f, life.as_ref()))
}

/// Each coefficient against C2, a curve per C1 (the codes' charts): PREFIX_cp.png, ...
fn coefficient_charts(prefix: &std::path::Path, table: &[(f64, f64, Coefficients)]) -> Result<(), Error> {
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

/// The bellows' code check (EJMA): the design pressure and the whole stroke, with the chart
/// coefficients given (`--coefficients`) or computed for its convolution (collective).
fn code_check(session: &PetscSession, params: &slideline::bellows::joint::BellowsParams) -> Result<CodeCheck, Error> {
    let geometry = slideline::bellows::joint::code_geometry(params);
    let (coefficients, source) = match params.coefficients {
        Some([cp, cf, cd]) => (Coefficients { cp, cf, cd }, Source::Given),
        None => (slideline::bellows::convolution::compute(session, geometry.c1(), geometry.c2(), Default::default())?, Source::Computed),
    };
    let p = params;
    let duty =
        Duty { pressure: p.pressure, stroke: p.displacement.abs(), modulus: p.youngs_modulus, yield_stress: p.yield_stress, tangent_length: p.tangent_length };
    Ok(CodeCheck::new(&geometry, coefficients, source, duty))
}

/// Rank 0 prints the summary (then runs `then`, the subcommand's own report) or the error;
/// every rank returns the exit code.
fn finish(result: Result<RunSummary, Error>, root: bool, then: impl FnOnce(&RunSummary) -> Result<(), Error>) -> ExitCode {
    match result {
        Ok(summary) => {
            if root {
                print_summary(&summary);
                if let Err(e) = then(&summary) {
                    return fail(&e, launched_as_rank_zero());
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e, root),
    }
}

/// Whether a run ended on bad input (then options left unread say nothing more).
fn is_bad_input<T>(result: &Result<T, Error>) -> bool {
    result.as_ref().is_err_and(|e| e.exit_code() == 2)
}

/// Rank 0 names the PETSc options nothing read (a misspelt option is otherwise silently
/// ignored).
fn warn_unused_options(session: &PetscSession, root: bool) {
    if root {
        for option in session.unused_options() {
            eprintln!("warning: PETSc option {option} was not used (misspelt? `-- -help` lists the options PETSc reads)");
        }
    }
}

/// Whether this process is rank 0 of its launch (or launched alone), read from the launcher's
/// environment: for messages printed before MPI starts.
fn launched_as_rank_zero() -> bool {
    ["OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"].iter().all(|v| std::env::var(v).map_or(true, |r| r == "0"))
}

fn fail(e: &Error, print: bool) -> ExitCode {
    if print {
        // one write: under mpirun, pieces of a line written apart can be split by mpirun's own
        // messages about the exit
        use std::io::Write as _;
        let _ = std::io::stderr().write_all(format!("error: {e}\n").as_bytes());
    }
    ExitCode::from(e.exit_code() as u8)
}

fn print_summary(summary: &RunSummary) {
    for (name, answer) in &summary.heat {
        let [low, high] = answer.temperature.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &t| [a.min(t), b.max(t)]);
        println!("heat step '{name}': temperatures {low:.6e} to {high:.6e} degC");
        match summary.plane {
            true => println!("  heat flowing in (mW, over the plane model's thickness):"),
            false => println!("  heat flowing in (mW):          per radian    full 360-degree ring"),
        }
        for f in &answer.flows {
            match summary.plane {
                true => println!("  {:<20} {:>14.6e}", f.set, f.flow),
                false => println!("  {:<20} {:>14.6e}   {:>14.6e}", f.set, f.flow, std::f64::consts::TAU * f.flow),
            }
        }
    }
    let Some(last) = summary.history.last() else {
        return;
    };
    println!("{}", summary.done_line());
    if summary.reserved_couplings > 0 {
        println!(
            "Jacobian pattern: {} contact couplings (node pairs, counted on each rank that needs them) reserved by the end; matrix refitted in place {} time(s)",
            summary.reserved_couplings, summary.pattern_refits
        );
    }
    if !last.reactions.is_empty() && summary.plane {
        println!("final reactions (N, over the plane model's thickness):");
        println!("  {:<20} {:>14} {:>14}", "set", "F_x", "F_y");
        for (set, f) in &last.reactions {
            println!("  {:<20} {:>14.6e} {:>14.6e}", set, f[0], f[1]);
        }
    } else if !last.reactions.is_empty() {
        println!("final reactions (N):            per radian                      full 360-degree ring");
        println!("  {:<20} {:>14} {:>14}   {:>14} {:>14}", "set", "F_r", "F_z", "F_r", "F_z");
        let ring = 2.0 * std::f64::consts::PI;
        for (set, f) in &last.reactions {
            println!("  {:<20} {:>14.6e} {:>14.6e}   {:>14.6e} {:>14.6e}", set, f[0], f[1], f[0] * ring, f[1] * ring);
        }
    }
    for (name, answer) in &summary.perturbations {
        if !answer.modes.is_empty() {
            println!(
                "{}",
                slideline::post::eigen_lines(name, answer.analysis, &answer.modes.iter().map(|m| (m.eigenvalue, m.effective_mass)).collect::<Vec<_>>())
            );
            for (i, m) in answer.modes.iter().enumerate() {
                for (surface, p) in &m.critical_pressures {
                    println!("  mode {:>2}: critical pressure on '{surface}' {p:.6e} MPa", i + 1);
                }
            }
            continue;
        }
        println!("perturbation step '{name}': reactions (full 360-degree ring)");
        for r in &answer.reactions {
            let resultants: Vec<String> = r.resultants.iter().map(|(what, v, units)| format!("{what} {v:.6e} {units}")).collect();
            println!("  {:<20} {}", r.set, if resultants.is_empty() { format!("summed nodal forces per radian {:?}", r.force) } else { resultants.join(", ") });
        }
    }
}
