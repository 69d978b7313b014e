//! slideline command line: parse, call the library, map errors to exit codes
//! (2 bad input, 3 not converged, 1 other).

use clap::{Parser, Subcommand};
use mpi::traits::Communicator;
use slideline::petsc::PetscSession;
use slideline::solve::{run, RunOptions};
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
    /// Run the analysis described by a TOML deck and write results to HDF5 (+ XDMF for ParaView).
    ///
    /// PETSc options go after `--`, e.g.
    /// `slideline run cylinder.toml -- -snes_monitor -ksp_type gmres -pc_type gamg -log_view`.
    /// The PETSC_OPTIONS environment variable is honoured too.
    Run {
        /// The input deck (TOML; see README for the format).
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Run { deck, output, quiet, petsc } => {
            let session = match PetscSession::initialize(&petsc) {
                Ok(s) => s,
                Err(e) => return fail(&e, true),
            };
            let root = session.world().rank() == 0;
            let output = output.unwrap_or_else(|| PathBuf::from(deck.file_stem().unwrap_or_default()).with_extension("h5"));
            let result = model::deck::read(&deck).and_then(|m| run(&session, &m, &RunOptions { output, progress: !quiet }));
            match result {
                Ok(summary) => {
                    if root {
                        print_summary(&summary);
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => fail(&e, root),
            }
        }
    }
}

fn fail(e: &Error, print: bool) -> ExitCode {
    if print {
        eprintln!("error: {e}");
    }
    ExitCode::from(e.exit_code() as u8)
}

fn print_summary(summary: &slideline::solve::RunSummary) {
    let Some(last) = summary.history.last() else {
        return;
    };
    println!("done: {} increments in {:.2} s on {} rank(s)", summary.history.len(), summary.wall_time, summary.ranks);
    if !last.reactions.is_empty() {
        println!("final reactions (N):            per radian                      full 360-degree ring");
        println!("  {:<20} {:>14} {:>14}   {:>14} {:>14}", "set", "F_r", "F_z", "F_r", "F_z");
        let ring = 2.0 * std::f64::consts::PI;
        for (set, f) in &last.reactions {
            println!("  {:<20} {:>14.6e} {:>14.6e}   {:>14.6e} {:>14.6e}", set, f[0], f[1], f[0] * ring, f[1] * ring);
        }
    }
}
