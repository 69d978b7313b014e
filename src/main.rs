//! slideline command line: parse, call the library, map errors to exit codes
//! (2 bad input, 3 not converged, 1 other).

mod cli;

use clap::{CommandFactory, FromArgMatches};
use cli::outcome::{fail, finish, is_bad_input, launched_as_rank_zero, warn_unused_options};
use cli::{Cli, Command};
use mpi::traits::Communicator;
use slideline::bellows::workflow;
use slideline::model;
use slideline::petsc::PetscSession;
use slideline::solve::{run, RunOptions};
use std::path::PathBuf;
use std::process::ExitCode;

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
        Command::Bellows(args) => bellows_command(&args, matches.subcommand_matches("bellows")),
        Command::Check(args) => cli::check::check_command(&args),
        Command::PenaltyStudy(args) => cli::study::penalty_study_command(&args),
        Command::BellowsSweep(args) => cli::study::sweep_command(&args),
        Command::Coefficients { c1, c2, through, per_thickness, plot, petsc } => {
            let session = match PetscSession::initialize(&petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, launched_as_rank_zero()),
            };
            cli::study::coefficients(&session, &c1, &c2, slideline::bellows::convolution::Fineness { through, per_thickness }, plot)
        }
        Command::Post(args) => match cli::post::post(&args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e, true),
        },
        Command::Run(args) => run_command(args),
    }
}

/// The restart a run's flags ask for.
fn restart_from(file: &Option<PathBuf>, increment: Option<usize>) -> Option<slideline::io::restart::RestartFrom> {
    file.clone().map(|file| slideline::io::restart::RestartFrom { file, increment })
}

/// `slideline bellows`: the specification or parameters checked before MPI starts, then the
/// joint's run (or its mesh, deck or design-by-analysis checks).
fn bellows_command(args: &cli::BellowsArgs, sub: Option<&clap::ArgMatches>) -> ExitCode {
    // bad flags, specifications and parameter files are reported before MPI and PETSc start
    let params = match args.joint(sub) {
        Ok(p) => p,
        Err(e) => return fail(&e, launched_as_rank_zero()),
    };
    if args.check_only {
        return cli::check_only(&params, &args.petsc);
    }
    if let (true, Err(e)) = (args.form, params.validate_forming()) {
        return fail(&e, launched_as_rank_zero());
    }
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
        let built = if args.form { slideline::bellows::forming::model(&params) } else { slideline::bellows::joint::model(&params) };
        return match built.and_then(|m| model::inp::write(&m, &params.fe_title(), path)) {
            Ok(()) => {
                println!("deck written to {}", path.display());
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e, launched_as_rank_zero()),
        };
    }
    // the results file and the report, checked before any work; never an input file
    let inputs = args.params.as_deref().map(|p| (p, "the --params file")).or(args.spec.as_deref().map(|p| (p, "the --spec file")));
    for path in std::iter::once(&args.output).chain(&args.report) {
        if let Err(e) = slideline::output_path::check_output_path(path, inputs) {
            return fail(&e, launched_as_rank_zero());
        }
    }
    let session = match PetscSession::initialize(&args.petsc) {
        Ok(s) => s,
        Err(e) => return fail(&e, launched_as_rank_zero()),
    };
    if args.mesh_only {
        return match workflow::write_mesh(&session, &params, &args.output) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e, session.world().rank() == 0),
        };
    }
    let root = session.world().rank() == 0;
    if args.dba {
        let result = workflow::design_by_analysis(&session, &params, &args.output, args.report.as_deref(), args.quiet);
        warn_unused_options(&session, root && !is_bad_input(&result));
        return match result {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e, root),
        };
    }
    let job = args.job(params, movements);
    if args.form {
        let result = slideline::bellows::forming::workflow::form(&session, &job);
        warn_unused_options(&session, root && !is_bad_input(&result));
        let (result, rest, code) = match result {
            Ok(runs) => (Ok(runs.service), runs.rest, runs.code),
            Err(e) => (Err(e), None, Vec::new()),
        };
        return finish(result, root, |summary| slideline::bellows::forming::workflow::report(&job, summary, rest.as_ref(), &code));
    }
    let before = match workflow::before_the_run(&session, &job) {
        Ok(before) => before,
        Err(e) => return fail(&e, root),
    };
    let result = workflow::run(&session, &job);
    warn_unused_options(&session, root && !is_bad_input(&result));
    finish(result, root, |summary| workflow::report(&job, &before, summary))
}

/// `slideline run`: a deck's analysis, its notes printed, the flags over its controls.
fn run_command(args: cli::RunArgs) -> ExitCode {
    let cli::RunArgs { deck, output, quiet, verbose, monitor, restart, increment, convergence, output_precision, petsc } = args;
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
    let result = model.and_then(|m| run(&session, &m, &RunOptions { output, progress: !quiet, verbose, monitor, restart: restart_from(&restart, increment) }));
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
