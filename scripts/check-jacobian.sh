#!/usr/bin/env bash
# PETSc's finite-difference check of slideline's assembled Jacobian on a deck: runs the deck
# with -snes_test_jacobian (on RANKS ranks, default 2) and prints the worst
# ||J - J_fd||_F / ||J||_F over all Newton iterates; exit 1 if it exceeds TOL (default 1e-6).
#   scripts/check-jacobian.sh examples/lame.toml
#   RANKS=1 TOL=1e-5 scripts/check-jacobian.sh my_contact_deck.toml
set -euo pipefail
deck=${1:?usage: scripts/check-jacobian.sh DECK.toml}
ranks=${RANKS:-2}
tol=${TOL:-1e-6}
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
cargo build --release -q
out=$(mktemp -d)
mpirun -n "$ranks" --oversubscribe target/release/slideline run "$deck" -q -o "$out/check.h5" -- -snes_test_jacobian \
    | awk -v tol="$tol" '
        /\|\|J - Jfd\|\|_F\/\|\|J\|\|_F = / { split($0, a, "= "); split(a[2], b, ","); r = b[1] + 0; n++; if (r > worst) worst = r }
        END {
            if (n == 0) { print "no Jacobian test was printed"; exit 1 }
            printf "%d Jacobian tests, worst ||J - Jfd||/||J|| = %.3e (tolerance %s)\n", n, worst, tol
            exit (worst > tol)
        }'
