//! The built-in bellows expansion joint: its geometry and mesh ([`joint`]), the analyses the
//! codes ask of it beside their formulas (the chart coefficients of its convolution
//! [`convolution`], the stresses by finite elements [`finite_element`] from the plies' membrane
//! forces [`membrane`], its flexibility, stability and natural frequencies by perturbation steps
//! [`flexibility`], [`stability`], [`vibration`]), and its closing report and pictures
//! ([`report`]).

pub mod convolution;
pub mod finite_element;
pub mod flexibility;
pub mod forming;
pub mod joint;
pub mod membrane;
pub mod report;
pub mod spec;
pub mod stability;
mod stations;
pub mod twin;
pub mod vibration;
pub mod workflow;

use crate::error::{Error, Result};
use crate::petsc::PetscSession;
use crate::solve::RunOptions;
use mpi::traits::*;
use spec::DesignSpec;
use std::path::{Path, PathBuf};

/// The joint `p`'s own model, elastic and without thermal expansion (the codes' linear
/// analyses).
fn elastic_model(p: &DesignSpec) -> Result<crate::model::Model> {
    let mut m = crate::bellows::joint::model(p)?;
    for material in &mut m.materials {
        material.plasticity = None;
        material.thermal_expansion = 0.0;
    }
    Ok(m)
}

/// The joint `p` at rest (its own two steps with no pressure or stroke, elastic, no expansion:
/// the codes' assumption) with the perturbation steps `steps` of that state, run in a scratch
/// directory; `read` takes the rest parameters, the run's answers and its file (collective).
fn at_rest<T>(
    session: &PetscSession,
    p: &DesignSpec,
    name: &str,
    steps: impl FnOnce(&DesignSpec) -> Vec<crate::model::perturbation::Perturbation>,
    read: impl FnOnce(&DesignSpec, &crate::solve::RunSummary, &Path) -> Result<T>,
) -> Result<T> {
    let mut rest = p.clone();
    (rest.design.pressure, rest.design.axial_compression, rest.design.axial_extension) = (0.0, Some(0.0), None);
    (rest.joint.heat_increments, rest.joint.increments, rest.joint.cycle) = (1, 1, false);
    let mut model = elastic_model(&rest)?;
    model.set_perturbations(steps(&rest));
    model.validate()?;
    in_scratch(session, name, |dir| {
        let file = dir.join("rest.h5");
        let summary = crate::solve::run(session, &model, &quiet_run(&file))?;
        read(&rest, &summary, &file)
    })
}

/// A run of one of the assessment's own analyses: no progress, no monitor.
fn quiet_run(output: &Path) -> RunOptions {
    RunOptions { output: output.to_path_buf(), progress: false, verbose: false, monitor: false, restart: None }
}

/// `work` in a fresh temporary directory, the same on every rank (rank 0 names and creates it,
/// and removes it when every rank is done, unless `work` failed: its error may name the file,
/// which is then kept to be read; collective).
fn in_scratch<T>(session: &PetscSession, name: &str, work: impl FnOnce(&Path) -> Result<T>) -> Result<T> {
    let world = session.world();
    let mut id = [std::process::id() as u64, std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos() as u64)];
    world.process_at_rank(0).broadcast_into(&mut id[..]);
    let dir: PathBuf = std::env::temp_dir().join(format!("slideline-{name}-{}-{}", id[0], id[1]));
    if world.rank() == 0 {
        std::fs::create_dir_all(&dir).map_err(|e| Error::Output { path: dir.clone(), message: e.to_string() })?;
    }
    world.barrier();
    let result = work(&dir);
    world.barrier();
    if world.rank() == 0 && result.is_ok() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    result
}
