//! What a run carries from one step to the next, and where a restart puts it: the state read
//! back from a results file's restart point, exactly what a commit wrote.

use crate::decomposition::Partition;
use crate::error::{Error, Result};
use crate::io::restart::{RestartFrom, RestartPoint};
use crate::io::{HistoryRow, ResultsFile};
use crate::model::Model;
use crate::records::last_increment::LastIncrement;
use crate::solve::contact::{CarriedMultipliers, CarriedSlip, ContactCarry};
use crate::solve::jacobian::pattern::ContactPattern;
use crate::solve::problem::schedule::StepLoads;
use crate::solve::problem::{initial_history, History};
use crate::solve::procedures::general::energy::EnergyAudit;

/// What the run carries from one step to the next: the displacement of every node, this rank's
/// elements' history, contact's committed state and pattern, the history rows, the last step's
/// loads, the energy audit, and the wall time of the run it continues.
pub(in crate::solve) struct Carried {
    pub displacement: Vec<[f64; 2]>,
    pub history: History,
    pub carry: Option<ContactCarry>,
    pub rows: Vec<HistoryRow>,
    pub previous: Option<StepLoads>,
    pub audit: EnergyAudit,
    pub wall_before: f64,
}

/// Where a restart puts the stepping: the step (0-based), the displacement at its start (its
/// newly prescribed values ramp from there), the load factor reached, the next increment's size
/// and the increments the step has taken.
pub(in crate::solve) struct ResumeAt {
    pub step: usize,
    pub step_start: Vec<[f64; 2]>,
    pub load_factor: f64,
    pub size: f64,
    pub increment: usize,
    /// The extrapolation predictor's last increment (None at a step's end, or from an older file).
    pub last_increment: Option<LastIncrement>,
}

impl Carried {
    pub fn fresh(model: &Model, partition: &Partition) -> Self {
        let nodes = model.mesh.coords.len();
        Carried {
            displacement: vec![[0.0; 2]; nodes],
            history: initial_history(model, partition),
            carry: None,
            rows: Vec::new(),
            previous: None,
            audit: EnergyAudit::new(model.reference_temperature.nodal(nodes)),
            wall_before: 0.0,
        }
    }

    /// The state at a restart point, its history rows copied into `results`.
    pub fn restored(model: &Model, partition: &Partition, point: RestartPoint, results: &mut ResultsFile) -> Result<(Self, ResumeAt)> {
        let nodes = model.mesh.coords.len();
        results.continue_history(&point.file, &point.rows)?;
        let zeros = vec![[0.0; 2]; nodes];
        let mut previous = None;
        for k in 0..point.step {
            previous = Some(StepLoads::new(model, k, previous.as_ref(), if k == 0 { &zeros } else { &point.step_ends[k - 1] }));
        }
        let mut audit = EnergyAudit::new(model.reference_temperature.nodal(nodes));
        if let Some(energy) = point.rows.last().and_then(|(_, r)| r.energy) {
            audit = EnergyAudit { totals: energy, last: point.audit.clone(), starts_overlapping: false };
        }
        let carry = (!model.contacts.is_empty()).then(|| {
            // each rank its own couplings on as many ranks as wrote them, shared out otherwise
            let mine = |r: usize| if point.ranks == partition.size { r == partition.rank } else { r % partition.size == partition.rank };
            ContactCarry {
                multipliers: CarriedMultipliers::ByNode(point.multipliers.clone()),
                pattern: ContactPattern::restored(point.pattern.iter().filter(|p| mine(p.0)).map(|p| (p.1, p.2)), point.refits),
                slip: CarriedSlip::ByNode(point.slip.clone()),
            }
        });
        let at = ResumeAt {
            step: point.step,
            step_start: if point.step == 0 { zeros } else { point.step_ends[point.step - 1].clone() },
            load_factor: point.load_factor,
            size: point.next_size,
            increment: point.increment,
            last_increment: point.last_increment.clone(),
        };
        let carried = Carried {
            history: restored_history(model, partition, &point),
            carry,
            rows: point.rows.iter().map(|(_, r)| r.clone()).collect(),
            previous,
            audit,
            wall_before: point.rows.last().map_or(0.0, |(_, r)| r.wall_time),
            displacement: point.displacement,
        };
        Ok((carried, at))
    }
}

/// Reads the restart point (every rank, serially), refusing to overwrite the file it reads.
pub(in crate::solve) fn restart_point(from: &RestartFrom, output: &std::path::Path, model: &Model) -> Result<RestartPoint> {
    let same = match (std::fs::canonicalize(&from.file), std::fs::canonicalize(output)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same {
        return Err(Error::input(format!(
            "cannot restart from {} into itself: write the continued run to another file (--output NAME.h5); it holds the history from the start and the fields from the restart on",
            from.file.display()
        )));
    }
    RestartPoint::read(from, model)
}

/// This rank's elements' history at a restart point.
pub(in crate::solve) fn restored_history(model: &Model, partition: &Partition, point: &RestartPoint) -> History {
    let mut history = initial_history(model, partition);
    let mut local = vec![usize::MAX; model.mesh.elements.len()];
    for (k, &e) in partition.local_elements().iter().enumerate() {
        local[e] = k;
    }
    for &(e, q, state) in &point.plastic {
        if let Some(point) = history.get_mut(local[e]).and_then(|h| h.get_mut(q)) {
            *point = state;
        }
    }
    history
}
