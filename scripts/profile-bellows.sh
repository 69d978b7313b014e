#!/usr/bin/env bash
# Where the time of a bellows run goes, on 1 and 2 ranks, from PETSc's -log_view (slideline
# registers the stages Residual, Jacobian, Contact and Output; the linear solve, PCSetUp (MUMPS's
# factorisation) and KSPSolve, stays in the main stage with SNES and the line search). Prints the stage times, the ratio of
# everything outside the linear solve to the linear solve, the MUMPS factorisations (symbolic
# analyses reused while the Jacobian's pattern holds) and the 2-rank speed-up.
#   scripts/profile-bellows.sh [bellows flags]     (default: the default case, ~6 min; --quick ~30 s)
#   SLIDELINE=/path/to/other/slideline scripts/profile-bellows.sh    another build (before/after)
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
cargo build --release --quiet
bin=${SLIDELINE:-target/release/slideline}
flags=("$@")
out=out/profile
mkdir -p "$out"
printf '%-6s %9s %9s %9s %9s %9s %9s %9s %14s %17s\n' ranks "wall s" "lin.solve" residual jacobian contact output "other" "outside/solve" "symbolic/numeric"
declare -A wall
for n in 1 2; do
    log="$out/ranks$n.log"
    mpirun -n "$n" "$bin" bellows ${flags[@]+"${flags[@]}"} -q -o "$out/ranks$n.h5" -- -log_view >"$log" 2>&1
    stage() { awk -v s="$1:" '/Summary of Stages/ {on=1} on && $2 == s {print $3; exit}' "$log"; }
    # the linear solve: MUMPS's factorisation (PCSetUp) and the triangular solves (KSPSolve)
    ksp=$(awk '/^(KSPSolve|PCSetUp) / {t += $4; n++} n == 2 {print t; exit}' "$log")
    main=$(awk '/Summary of Stages/ {on=1} on && /Main Stage:/ {print $4; exit}' "$log")
    res=$(stage Residual); jac=$(stage Jacobian); con=$(stage Contact); outp=$(stage Output)
    count() { awk -v e="$1" '$1 == e {print $2; exit}' "$log"; }
    factorisations="$(count MatLUFactorSym)/$(count MatLUFactorNum)"
    wall[$n]=$(awk '/^done:/ {print $(NF-4)}' "$log")
    python3 - "$n" "$factorisations" "${wall[$n]}" "$ksp" "$main" "$res" "$jac" "$con" "$outp" <<'PY'
import sys
n, factorisations = sys.argv[1:3]
wall, ksp, main, res, jac, con, out = map(float, sys.argv[3:])
other = main - ksp  # SNES, line search, predictor set-up, stepping, outside any stage
outside = res + jac + con + out + other
print(f"{n:<6} {wall:9.2f} {ksp:9.2f} {res:9.2f} {jac:9.2f} {con:9.2f} {out:9.2f} {other:9.2f} {outside / ksp:14.2f} {factorisations:>17}")
PY
done
python3 -c "import sys; print(f'speed-up 1 -> 2 ranks: {float(sys.argv[1]) / float(sys.argv[2]):.2f}')" "${wall[1]}" "${wall[2]}"
