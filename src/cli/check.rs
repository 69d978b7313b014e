//! `slideline check DECK`: the design-by-analysis checks (ASME VIII-2 Part 5) the deck's
//! `[design_by_analysis]` table names, each by an analysis of its own, and their verdict.

use super::outcome::{fail, is_bad_input, launched_as_rank_zero, warn_unused_options};
use clap::Args;
use mpi::traits::Communicator;
use slideline::petsc::PetscSession;
use slideline::Error;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The input deck (TOML) with a `[design_by_analysis]` table (docs/design-by-analysis.md).
    pub deck: PathBuf,
    /// The verdict file (HDF5, `/dba`); each check's analysis is written beside it,
    /// NAME_limit_load.h5, NAME_buckling.h5, NAME_ratcheting.h5, NAME_fatigue.h5. Default: the deck's name with
    /// `_check.h5`.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// No progress lines.
    #[arg(short, long)]
    pub quiet: bool,
    /// PETSc options (after `--`).
    #[arg(last = true, allow_hyphen_values = true)]
    pub petsc: Vec<String>,
}

pub fn check_command(args: &CheckArgs) -> ExitCode {
    let output = args.output.clone().unwrap_or_else(|| PathBuf::from(format!("{}_check.h5", args.deck.file_stem().unwrap_or_default().to_string_lossy())));
    for path in slideline::dba::output_files(&output) {
        if let Err(e) = slideline::output_path::check_output_path(&path, Some((&args.deck, "the input deck"))) {
            return fail(&e, launched_as_rank_zero());
        }
    }
    let session = match PetscSession::initialize(&args.petsc) {
        Ok(s) => s,
        Err(e) => return fail(&e, launched_as_rank_zero()),
    };
    let root = session.world().rank() == 0;
    let result = (|| {
        let _locks = slideline::dba::lock_outputs(&session, &output)?;
        let (model, notes) = slideline::preprocess::prepared_deck(&args.deck)?;
        let spec = slideline::dba::table::DbaTable::of_model(&model)?.ok_or_else(|| {
            Error::input(format!("{}: no [design_by_analysis] table: it names the checks to run (docs/design-by-analysis.md)", args.deck.display()))
        })?;
        if root && !args.quiet {
            notes.iter().for_each(|note| println!("note: {note}"));
        }
        let verdict = slideline::dba::run(&session, &model, &spec, &output, !args.quiet)?;
        if root {
            slideline::dba::report(&verdict, &args.deck.display().to_string(), &output, &model.source_text)?;
        }
        Ok::<(), Error>(())
    })();
    warn_unused_options(&session, root && !is_bad_input(&result));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(&e, root),
    }
}
