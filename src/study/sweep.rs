//! bellows-sweep
