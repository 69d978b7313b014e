//! Plain records the solver produces and `io` writes and reads back (the history's energies,
//! contact states, perturbation and heat answers, the restart's pieces): below both, so that
//! `io` never imports the solver, and `assessment` reads answers without it.

pub mod contact;
pub mod energy;
pub mod heat;
pub mod increment_fields;
pub mod last_increment;
pub mod perturbation;
