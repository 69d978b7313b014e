#!/usr/bin/env bash
# Two slideline binaries on the same cases in one sitting, runs of the two alternating so that
# the machine's drift hits both alike (this machine's speed moves by a quarter between hours):
# the default bellows on 2 ranks (wall time, median of REPEATS; Newton iterations; results
# file size; and its answers, which must agree: end reaction, largest von Mises stress and
# plastic strain, energy balance), then the results file sizes of the quick joint and of the
# CalculiX push-out deck (tests/data/inp/push_out.inp), each as the ratio new / old.
#   scripts/compare-binaries.sh OLD NEW [slideline flags for every run, e.g. --output-precision single]
#   REPEATS=1 scripts/compare-binaries.sh ...
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
[ $# -ge 2 ] || { echo "usage: $0 OLD_BINARY NEW_BINARY [flags]" >&2; exit 2; }
old=$1 new=$2
shift 2
flags=("$@")
REPEATS=${REPEATS:-3}
out=out/compare
mkdir -p "$out"
python=${SLIDELINE_PYTHON:-/usr/bin/python3}

for i in $(seq "$REPEATS"); do
    for which in old new; do
        bin=${!which}
        # the new flags may not exist in the old binary: only the new one gets them
        extra=()
        [ "$which" = new ] && extra=(${flags[@]+"${flags[@]}"})
        start=$(date +%s.%N)
        mpirun -n 2 "$bin" bellows -q -o "$out/$which-$i.h5" ${extra[@]+"${extra[@]}"} >"$out/$which-$i.log" 2>&1
        end=$(date +%s.%N)
        echo "$which $i $(echo "$end - $start" | bc)" >>"$out/walls.txt.$$"
    done
done
for which in old new; do
    bin=${!which}
    extra=()
    [ "$which" = new ] && extra=(${flags[@]+"${flags[@]}"})
    mpirun -n 2 "$bin" bellows --quick -q -o "$out/$which-quick.h5" ${extra[@]+"${extra[@]}"} >/dev/null 2>&1
    mpirun -n 2 "$bin" run tests/data/inp/push_out.inp -q -o "$out/$which-push.h5" ${extra[@]+"${extra[@]}"} >/dev/null 2>&1
done
"$python" - "$out" "$REPEATS" "$out/walls.txt.$$" <<'PY'
import sys, os, statistics, h5py
import numpy as np
out, repeats, walls = sys.argv[1], int(sys.argv[2]), sys.argv[3]
wall = {"old": [], "new": []}
for line in open(walls):
    which, _, seconds = line.split()
    wall[which].append(float(seconds))
os.remove(walls)
def answers(path):
    h = h5py.File(path, "r")["history"]
    return {
        "end reaction moving_end z, N/rad": h["reaction_moving_end_z"][-1],
        "largest plastic strain": h["max_equivalent_plastic_strain"][-1],
        "energy balance error, N mm/rad": h["energy_balance_error"][-1],
        "Newton iterations": h["newton_iterations"][:].sum(),
        "increments": len(h["step"]),
    }
def max_von_mises(path):
    f = h5py.File(path, "r")
    last = sorted(f["increments"])[-1]
    return float(np.nanmax(f["increments"][last]["von_mises"][:]))
mb = lambda p: os.path.getsize(p) / 1e6
o, n = f"{out}/old-1.h5", f"{out}/new-1.h5"
print(f"default bellows, 2 ranks, wall s (median of {repeats}, alternating): old {statistics.median(wall['old']):.1f} {sorted(round(w, 1) for w in wall['old'])}, new {statistics.median(wall['new']):.1f} {sorted(round(w, 1) for w in wall['new'])}, new / old {statistics.median(wall['new']) / statistics.median(wall['old']):.2f}")
a, b = answers(o), answers(n)
for k in a:
    print(f"  {k:<36} old {a[k]:>14.6g}   new {b[k]:>14.6g}")
va, vb = max_von_mises(o), max_von_mises(n)
print(f"  {'largest von Mises at the end, MPa':<36} old {va:>14.6g}   new {vb:>14.6g}")
for case in ("", "quick", "push"):
    po, pn = (f"{out}/old-1.h5", f"{out}/new-1.h5") if not case else (f"{out}/old-{case}.h5", f"{out}/new-{case}.h5")
    name = {"": "default bellows", "quick": "quick bellows", "push": "push-out deck (.inp)"}[case]
    print(f"results file, {name:<22} old {mb(po):8.1f} MB   new {mb(pn):8.1f} MB   new / old {mb(pn) / mb(po):.2f}")
PY
