//! The contact part of the Jacobian's sparsity pattern.
//!
//! Contact couples nodes no element couples, and which ones changes as contacts close and the
//! bodies slide. A coupling outside an AIJ matrix's pattern is expensive: PETSc squeezes the
//! storage to the pattern at every assembly, so each row that takes a new entry reallocates the
//! whole matrix (8 % of a quick bellows run went to those copies). So the couplings are kept
//! here, replicated on every rank: each step's matrix is built exactly preallocated for the
//! elements and every coupling found so far, all stored as zeros before the first assembly; and
//! when a Jacobian's contact engagements need couplings the pattern lacks, the matrix is refitted
//! in place before any value is added (`Problem::fit_pattern`: [`ContactPattern::synchronise`],
//! then exact re-preallocation). MUMPS redoes its symbolic analysis after a build or a refit
//! only; every other factorisation reuses it.
//!
//! Two ways of doing better were measured and dropped. Reserving a halo of master nodes around
//! each new coupling (the sliding ahead) stored so many zeros that each numeric factorisation
//! of the quick bellows cost half as much again, fill being fill for MUMPS. Building a new matrix
//! before each attempt whose predecessor grew the pattern doubled the symbolic analyses (155
//! against 84 for 1413 factorisations on the default bellows).

use mpi::datatype::PartitionMut;
use mpi::traits::*;
use std::collections::{BTreeSet, HashMap};
use std::hash::{Hash, Hasher};

#[derive(Clone, Debug, Default)]
pub struct ContactPattern {
    /// Reserved couplings (a < b), the same on every rank after `synchronise`.
    reserved: BTreeSet<(usize, usize)>,
    /// Couplings this rank found missing since the last `synchronise`.
    pending: BTreeSet<(usize, usize)>,
    /// Slave node -> fingerprint of the node list last found covered: an engagement that
    /// couples the same nodes as last time needs no pair-by-pair check.
    covered: HashMap<usize, u64>,
    /// How many times a matrix was refitted in place for new couplings.
    pub refits: usize,
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
            for &b in &nodes[i + 1..] {
                let key = ordered(a, b);
                if a != b && !self.reserved.contains(&key) {
                    self.pending.insert(key);
                }
            }
        }
        self.covered.insert(nodes[0], fingerprint);
    }

    /// Collective: every rank's pending couplings join the reserved ones on all ranks. Returns
    /// the new ones (the same on every rank).
    pub fn synchronise(&mut self, world: &impl Communicator) -> Vec<(usize, usize)> {
        let local = self.take_pending();
        let count = local.len() as i32;
        let mut counts = vec![0i32; world.size() as usize];
        world.all_gather_into(&count, &mut counts[..]);
        let total: i32 = counts.iter().sum();
        if total == 0 {
            return Vec::new();
        }
        let displs: Vec<i32> = counts.iter().scan(0, |s, &c| Some(std::mem::replace(s, *s + c))).collect();
        let mut all = vec![0u64; total as usize];
        world.all_gather_varcount_into(&local[..], &mut PartitionMut::new(&mut all[..], counts, displs));
        self.merge(&all)
    }

    /// This rank's pending couplings, flattened (a, b, a, b, ...), and none left pending.
    fn take_pending(&mut self) -> Vec<u64> {
        std::mem::take(&mut self.pending).into_iter().flat_map(|(a, b)| [a as u64, b as u64]).collect()
    }

    /// Reserves the flattened couplings `all`; returns those that were new.
    fn merge(&mut self, all: &[u64]) -> Vec<(usize, usize)> {
        all.chunks(2).map(|p| (p[0] as usize, p[1] as usize)).filter(|&pair| self.reserved.insert(pair)).collect()
    }

    /// The reserved couplings (a < b).
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

    /// `synchronise` on one rank (the MPI exchange itself runs in the 2-rank contact tests).
    fn synchronise_alone(p: &mut ContactPattern) -> Vec<(usize, usize)> {
        let local = p.take_pending();
        p.merge(&local)
    }

    #[test]
    fn missing_couplings_are_pending_until_synchronised_and_then_reserved() {
        let mut p = ContactPattern::default();
        // slave node 1 on the master edge (110, 112, 111)
        p.require(&[1, 110, 112, 111]);
        assert_eq!(p.pending.len(), 6);
        assert!(p.pending.contains(&(1, 110)) && p.pending.contains(&(111, 112)));
        // the same engagement again: nothing new, and no pair-by-pair check
        p.require(&[1, 110, 112, 111]);
        assert_eq!(p.pending.len(), 6);
        assert_eq!(synchronise_alone(&mut p).len(), 6);
        assert_eq!((p.len(), p.pending.len()), (6, 0));
        // sliding onto the next edge needs only the couplings with its far nodes
        p.require(&[1, 112, 114, 113]);
        assert_eq!(p.pending.len(), 5, "(1, 113), (1, 114), (112, 113), (112, 114), (113, 114)");
        assert_eq!(synchronise_alone(&mut p).len(), 5);
        assert!(synchronise_alone(&mut p).is_empty(), "nothing new");
    }
}
