//! `slideline bellows --form`'s work, in order: the forming (its tool tryouts), the code check
//! with the formed thickness, the perturbations `--squirm` and `--frequencies` ask for at rest
//! (the idealised joint's, the formed bellows'), the service ([`form`]); then the tables and
//! pictures ([`report`]).

use super::code::Column;
use super::measure::Formed;
use crate::bellows::spec::DesignSpec;
use crate::bellows::stability::Stability;
use crate::bellows::vibration::Frequencies;
use crate::bellows::workflow::{code_check, code_verdict, perturbation_steps, picture_path, BellowsJob};
use crate::error::Result;
use crate::io::reader::ResultsReader;
use crate::io::restart::RestartFrom;
use crate::petsc::PetscSession;
use crate::solve::{RunOptions, RunSummary};
use mpi::traits::Communicator;
use std::path::{Path, PathBuf};

/// What `--form` ran: the formed bellows' service (its perturbation steps, if any, about the
/// stroke's end) and, for `--squirm` and `--frequencies`, the same analyses at rest.
pub struct FormedRuns {
    pub service: RunSummary,
    pub rest: Option<FormedAtRest>,
    /// The code check with EJMA's tp and with the formed thicknesses.
    pub code: Vec<Column>,
}

/// The perturbations at rest beside the formed bellows' service: the idealised joint's (nominal
/// thickness, annealed, at rest as `bellows --squirm` analyses it) and the formed bellows' after
/// its springback (no pressure).
pub struct FormedAtRest {
    pub ideal_stability: Option<Stability>,
    pub ideal_frequencies: Option<Frequencies>,
    /// The formed bellows' answers after the springback (their file `STEM_rest.h5`).
    pub formed: RunSummary,
}

/// `--form`: the bellows hydroformed from a straight tube (its five steps, into the output),
/// then the formed bellows in service (the design pressure and the stroke, continuing the
/// forming's file into [`service_path`]), with `--squirm`'s and `--frequencies`' perturbation
/// steps about the stroke's end and about the formed bellows at rest (collective).
pub fn form(session: &PetscSession, job: &BellowsJob) -> Result<FormedRuns> {
    use super::{formed_perturbations, TRYOUTS};
    let options =
        |output: PathBuf, restart: Option<RestartFrom>| RunOptions { output, progress: !job.quiet, verbose: job.verbose, monitor: job.monitor, restart };
    let root = session.world().rank() == 0;
    let mut p = job.params.clone();
    // the tool tryout: formed again with the tube and the dies corrected where the formed w or q
    // misses the target by more than the tolerance (a restart continues its one forming)
    let tryouts = if job.restart.is_some() { 1 } else { TRYOUTS };
    let mut tryout = 1;
    let (forming, formed, figures) = loop {
        let forming = super::model(&p)?;
        let formed = crate::solve::run(session, &forming, &options(job.output.clone(), job.restart.clone()))?;
        let figures = Formed::read(&p, &ResultsReader::open(&job.output)?)?;
        match figures.corrected(&p).filter(|_| tryout < tryouts) {
            None => break (forming, formed, figures),
            Some(next) => {
                if root && !job.quiet {
                    println!("{}", figures.tryout_line(&p, &next));
                }
                p = next;
                tryout += 1;
            }
        }
    };
    // the joint's perturbation steps on the formed bellows
    let steps = formed_perturbations(&p, perturbation_steps(job, &p));
    // as the joint's run: a joint the code's formulas cannot take has a note, not an error
    let code = formed_code_check(session, &job.params, &figures).unwrap_or_else(|e| {
        if root {
            println!("note: no code check of the formed bellows: {e}");
        }
        Vec::new()
    });
    let rest = (!steps.is_empty())
        .then(|| -> Result<FormedAtRest> {
            let announce = |what: &str| {
                if root && !job.quiet {
                    println!("{what} ...");
                }
            };
            announce("the idealised joint at rest (nominal thickness, annealed) and its perturbations");
            let ideal_stability = job.squirm.then(|| crate::bellows::stability::at_rest(session, &job.params, |_, _| {})).transpose()?;
            let ideal_frequencies = job.frequencies.then(|| crate::bellows::vibration::at_rest(session, &job.params)).transpose()?;
            announce("the formed bellows at rest (after its springback) and its perturbations");
            let mut at_rest = forming.clone();
            at_rest.set_perturbations(steps.clone());
            at_rest.validate()?;
            let path = sibling_path(&job.output, "rest");
            crate::output_path::check_output_path(&path, None)?;
            let restart = Some(RestartFrom { file: job.output.clone(), increment: None });
            let formed = crate::solve::run(session, &at_rest, &RunOptions { progress: false, ..options(path, restart) })?;
            Ok(FormedAtRest { ideal_stability, ideal_frequencies, formed })
        })
        .transpose()?;
    // where the springback left the far tangent: the service holds it there
    let tangent_b = &forming.node_sets["tangent_b"];
    let sprung = tangent_b.iter().map(|&n| formed.displacement[n][1]).sum::<f64>() / tangent_b.len() as f64;
    let service = super::service_model(&p, sprung, steps)?;
    let path = service_path(&job.output);
    crate::output_path::check_output_path(&path, None)?;
    let service = crate::solve::run(session, &service, &options(path, Some(RestartFrom { file: job.output.clone(), increment: None })))?;
    Ok(FormedRuns { service, rest, code })
}

/// The code check of joint `p` with EJMA's tp, and with the ply thickness its forming left at
/// the crests and at the roots (`formed`'s, the mean over the plies), each with its chart
/// coefficients and, for a design specification, its verdict (collective).
fn formed_code_check(session: &PetscSession, p: &DesignSpec, formed: &Formed) -> Result<Vec<Column>> {
    let n = p.bellows.plies as f64;
    let thicknesses = [("EJMA's tp", None), ("FE crest", Some(formed.crest() / n)), ("FE root", Some(formed.root() / n))];
    thicknesses
        .into_iter()
        .map(|(label, tp)| {
            let mut q = p.clone();
            q.bellows.formed_ply_thickness = tp;
            let (check, verdict) = match q.has_design_data() {
                true => code_verdict(session, &q).map(|(c, v, _)| (c, Some(v)))?,
                false => (code_check(session, &q)?, None),
            };
            Ok(Column { label, tp: q.geometry().formed_thickness(), check, verdict })
        })
        .collect()
}

/// The service's results file beside the forming's: `STEM_service.h5`.
pub fn service_path(output: &Path) -> PathBuf {
    sibling_path(output, "service")
}

/// `STEM_name.h5` beside the forming's results file (`--form`'s others: the service's, the
/// formed bellows' perturbations at rest).
pub fn sibling_path(output: &Path, name: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}_{name}.h5"))
}

/// The forming's and the service's tables from their results files, and the perturbations'
/// where `--squirm` or `--frequencies` asked for them, printed and kept in the forming's
/// (rank 0, after the runs).
pub fn report(job: &BellowsJob, service: &RunSummary, rest: Option<&FormedAtRest>, code: &[Column]) -> Result<()> {
    use super::{measure, service};
    let (formed, serving) = (ResultsReader::open(&job.output)?, ResultsReader::open(&service_path(&job.output))?);
    // the joint as last formed (a tryout corrects the tube and the dies): the file's own
    let p = &DesignSpec::from_deck(&formed.text_attr("deck")?, &format!("{}: its deck", job.output.display()))?;
    let forming = measure::table(p, &measure::Formed::read(p, &formed)?);
    let in_service = service::table(p, &service::Service::read(p, &formed, &serving)?);
    let pictures = super::pictures::draw(p, &formed, |name| picture_path(&job.output, name))?;
    drop((formed, serving));
    let mut tables = vec![(measure::TABLE, forming), (service::TABLE, in_service)];
    if !code.is_empty() {
        tables.push((super::code::TABLE, super::code::table(code)));
    }
    if let Some(rest) = rest {
        // the formed bellows at rest: no pressure, no stroke (its convolved length the pitch's)
        let mut resting = p.clone();
        (resting.design.axial_compression, resting.design.axial_extension) = (Some(0.0), None);
        let columns = ["idealised", "formed, rest", "formed, end"];
        if let Some(ideal) = &rest.ideal_stability {
            let states = [
                ideal,
                &crate::bellows::stability::from_answers(&rest.formed.perturbations)?,
                &crate::bellows::stability::from_answers(&service.perturbations)?,
            ];
            let states: Vec<(&str, &Stability)> = columns.into_iter().zip(states).collect();
            tables.push(("stability", format!("{}{FORMED_COLUMNS}", crate::bellows::report::stability_columns(p, code.first().map(|c| &c.check), &states))));
        }
        if let Some(ideal) = &rest.ideal_frequencies {
            let states = [
                ideal.clone(),
                crate::bellows::vibration::from_answers(&resting, &rest.formed.perturbations)?,
                crate::bellows::vibration::from_answers(p, &service.perturbations)?,
            ];
            let states: Vec<(&str, &Frequencies)> = columns.into_iter().zip(&states).collect();
            tables.push(("frequencies", format!("{}{FORMED_COLUMNS}", crate::bellows::report::frequencies_columns(p, &states))));
        }
    }
    println!("\n{}", tables.iter().map(|(_, t)| t.as_str()).collect::<Vec<_>>().join("\n"));
    for (path, what) in pictures {
        println!("picture: {} ({what})", path.display());
    }
    crate::io::assessment::write_tables(&job.output, &tables)
}

/// What `--form`'s columns of the perturbation tables are.
const FORMED_COLUMNS: &str = "  columns: the idealised joint (nominal plies, annealed, its tubes) at rest; the formed bellows (its tangents clamped,\n  \
     the forming's thickness, cold work and residual stress, the forming's 20 degC material) after its springback, and at the\n  \
     end of its service (the design pressure and the stroke)\n";
