//! How a command ends: rank 0 prints the run's summary or the error, every rank exits with the
//! error's code (2 bad input, 3 not converged, 1 other), and PETSc options nothing read are named.

use slideline::petsc::PetscSession;
use slideline::solve::RunSummary;
use slideline::Error;
use std::process::ExitCode;

/// Rank 0 prints the summary (then runs `then`, the subcommand's own report) or the error;
/// every rank returns the exit code.
pub fn finish(result: Result<RunSummary, Error>, root: bool, then: impl FnOnce(&RunSummary) -> Result<(), Error>) -> ExitCode {
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
pub fn is_bad_input<T>(result: &Result<T, Error>) -> bool {
    result.as_ref().is_err_and(|e| e.exit_code() == 2)
}

/// Rank 0 names the PETSc options nothing read (a misspelt option is otherwise silently
/// ignored).
pub fn warn_unused_options(session: &PetscSession, root: bool) {
    if root {
        for option in session.unused_options() {
            eprintln!("warning: PETSc option {option} was not used (misspelt? `-- -help` lists the options PETSc reads)");
        }
    }
}

pub use slideline::launch::launched_as_rank_zero;

/// Prints `e` (when `print`: rank 0, or before MPI the launch's rank 0) and gives its exit code.
pub fn fail(e: &Error, print: bool) -> ExitCode {
    if print {
        // one write: under mpirun, pieces of a line written apart can be split by mpirun's own
        // messages about the exit
        use std::io::Write as _;
        let _ = std::io::stderr().write_all(format!("error: {e}\n").as_bytes());
    } else {
        // mpirun ends the whole job when the first rank exits with an error: the ranks that
        // say nothing leave rank 0 the time to say why (seen: a loaded machine's rank 1 exited
        // before rank 0 had written its line, and the refusal came without one)
        std::thread::sleep(std::time::Duration::from_millis(500));
    }
    ExitCode::from(e.exit_code() as u8)
}

pub fn print_summary(summary: &RunSummary) {
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
