//! The contact part of the Jacobian's sparsity pattern.
//!
//! Contact couples nodes no element couples, and which ones changes as contacts close and the
//! bodies slide. A coupling outside an AIJ matrix's pattern is expensive: PETSc squeezes the
//! storage to the pattern at every assembly, so each row that takes a new entry reallocates the
//! whole matrix (8 % of a quick bellows run went to those copies). So each rank keeps here the
//! couplings its engagements have needed so far: each step's matrix is built for the elements
//! and all of them (the COO layout of `solve::jacobian::layout`; PETSc gathers the ranks' entries into
//! rows), and when a Jacobian's engagements need couplings the pattern lacks, the matrix is
//! refitted in place before any value is added (`Problem::fit_pattern`:
//! [`ContactPattern::synchronise`], then a new COO preallocation on every rank). MUMPS redoes its
//! symbolic analysis after a build or a refit only; every other factorisation reuses it.
//!
//! Two ways of doing better were measured and dropped. Reserving a halo of master nodes around
//! each new coupling (the sliding ahead) stored so many zeros that each numeric factorisation
//! of the quick bellows cost half as much again, fill being fill for MUMPS. Building a new matrix
//! before each attempt whose predecessor grew the pattern doubled the symbolic analyses (155
//! against 84 for 1413 factorisations on the default bellows).

use mpi::collective::SystemOperation;
use mpi::traits::*;
use std::collections::{BTreeSet, HashMap};
use std::hash::{Hash, Hasher};

#[derive(Clone, Debug, Default)]
pub struct ContactPattern {
    /// Couplings reserved for this rank's engagements (a <= b: a node with itself too, since an
    /// engagement's diagonal blocks need places of their own in the layout).
    reserved: BTreeSet<(usize, usize)>,
    /// Couplings this rank found missing since the last `synchronise`.
    pending: BTreeSet<(usize, usize)>,
    /// Slave node -> fingerprint of the node list last found covered: an engagement that
    /// couples the same nodes as last time needs no pair-by-pair check.
    covered: HashMap<usize, u64>,
    /// How many times a matrix was refitted in place for new couplings.
    pub refits: usize,
    /// Couplings reserved since the results file last took them (`take_fresh`): the file keeps
    /// the pattern as it grows, so a restart rebuilds the very matrix structure.
    fresh: Vec<(usize, usize)>,
}

impl ContactPattern {
    /// Records the couplings among `nodes` (an engagement's, its slave node first) that the
    /// pattern lacks.
    pub fn require(&mut self, nodes: &[usize]) {
        let mut hasher = std::collections::hash_map::DefaultHasher::new();
        nodes.hash(&mut hasher);
        let fingerprint = hasher.finish();
        if self.covered.get(&nodes[0]) == Some(&fingerprint) {
            return;
        }
        for (i, &a) in nodes.iter().enumerate() {
            for &b in &nodes[i..] {
                let key = ordered(a, b);
                if !self.reserved.contains(&key) {
                    self.pending.insert(key);
                }
            }
        }
        self.covered.insert(nodes[0], fingerprint);
    }

    /// Collective: reserves this rank's pending couplings. True on every rank when a new one on
    /// any rank `needs_room` (couples two free DOFs: then every rank refits its matrix).
    pub fn synchronise(&mut self, world: &impl Communicator, needs_room: impl Fn(usize, usize) -> bool) -> bool {
        let grown = self.reserve_pending(needs_room);
        let mut any = 0i32;
        world.all_reduce_into(&i32::from(grown), &mut any, SystemOperation::max());
        any > 0
    }

    /// Reserves the pending couplings; whether one of them `needs_room`.
    fn reserve_pending(&mut self, needs_room: impl Fn(usize, usize) -> bool) -> bool {
        let pending = std::mem::take(&mut self.pending);
        let grown = pending.iter().any(|&(a, b)| needs_room(a, b));
        self.fresh.extend(pending.iter().copied());
        self.reserved.extend(pending);
        grown
    }

    /// A pattern holding `reserved` (a restart's), with `refits` refits so far.
    pub fn restored(reserved: impl IntoIterator<Item = (usize, usize)>, refits: usize) -> Self {
        ContactPattern { reserved: reserved.into_iter().map(|(a, b)| ordered(a, b)).collect(), refits, ..Default::default() }
    }

    /// The couplings reserved since the last call.
    pub fn take_fresh(&mut self) -> Vec<(usize, usize)> {
        std::mem::take(&mut self.fresh)
    }

    /// The reserved couplings (a <= b).
    pub fn pairs(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.reserved.iter().copied()
    }

    /// Number of reserved couplings.
    pub fn len(&self) -> usize {
        self.reserved.len()
    }

    pub fn is_empty(&self) -> bool {
        self.reserved.is_empty()
    }
}

fn ordered(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_couplings_are_pending_until_synchronised_and_then_reserved() {
        let mut p = ContactPattern::default();
        // slave node 1 on the master edge (110, 112, 111): 6 pairs and 4 diagonal blocks
        p.require(&[1, 110, 112, 111]);
        assert_eq!(p.pending.len(), 10);
        assert!(p.pending.contains(&(1, 110)) && p.pending.contains(&(111, 112)) && p.pending.contains(&(1, 1)));
        // the same engagement again: nothing new, and no pair-by-pair check
        p.require(&[1, 110, 112, 111]);
        assert_eq!(p.pending.len(), 10);
        assert!(p.reserve_pending(|_, _| true));
        assert_eq!((p.len(), p.pending.len()), (10, 0));
        // sliding onto the next edge needs only the couplings with its far nodes
        p.require(&[1, 112, 114, 113]);
        assert_eq!(p.pending.len(), 7, "(1, 113), (1, 114), (112, 113), (112, 114), (113, 114), (113, 113), (114, 114)");
        // new couplings that need no room (a fixed node, say) reserve without a refit
        assert!(!p.reserve_pending(|a, b| a != 114 && b != 114 && a != 113 && b != 113));
        assert_eq!(p.len(), 17);
        assert!(!p.reserve_pending(|_, _| true), "nothing new");
    }
}
