#!/usr/bin/env bash
# Two slideline binaries on the same cases, 1 rank, for a change that must not change behaviour
# (a refactoring): the default bellows, the quick joint with every analysis
# (--assess --lateral 5 --angular 1 --squirm --frequencies), the shrink-fit walk-through and
# three CalculiX decks (push_out, adjusted_fit, spun_disc) and a deck of every procedure (a heat,
# a general and a frequency step: warm_wall). Every dataset and attribute of each
# results file must be bit-identical (save the wall times), and the printed output identical
# once its seconds are masked. Prints one line per case and exits 1 on the first difference
# in any.
#   scripts/compare-builds.sh OLD_BINARY NEW_BINARY
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
[ $# -eq 2 ] || { echo "usage: $0 OLD_BINARY NEW_BINARY" >&2; exit 2; }
old=$(realpath "$1") new=$(realpath "$2")
python=${SLIDELINE_PYTHON:-/usr/bin/python3}
out=$(realpath -m out/compare-builds)
rm -rf "$out" && mkdir -p "$out"
cases=(
    "bellows|bellows -o CASE.h5"
    "quick_all|bellows --quick --assess --lateral 5 --angular 1 --squirm --frequencies -o CASE.h5"
    "shrink_fit|run $PWD/examples/shrink_fit.toml -o CASE.h5"
    "push_out|run $PWD/tests/data/inp/push_out.inp -o CASE.h5"
    "adjusted_fit|run $PWD/tests/data/inp/adjusted_fit.inp -o CASE.h5"
    "spun_disc|run $PWD/tests/data/inp/spun_disc.inp -o CASE.h5"
    "warm_wall|run $PWD/tests/data/warm_wall.toml -o CASE.h5"
)
status=0
for c in "${cases[@]}"; do
    name=${c%%|*} args=${c#*|}
    for which in old new; do
        bin=${!which}
        mkdir -p "$out/$which" && cd "$out/$which"
        # shellcheck disable=SC2086
        mpirun -n 1 "$bin" ${args//CASE/$name} >"$name.log" 2>&1 || echo "exit $?" >>"$name.log"
        cd - >/dev/null
    done
    "$python" - "$out/old/$name" "$out/new/$name" <<'PY' || status=1
import sys, re, glob, os
import h5py, numpy as np
old, new = sys.argv[1], sys.argv[2]
name = os.path.basename(old)
mask = lambda t: re.sub(r" *\d+\.\d+ s\b|wall time[^\n]*", " <time>", t)
logs = [mask(open(p + ".log").read()) for p in (old, new)]
problems = []
if logs[0] != logs[1]:
    a, b = logs[0].splitlines(), logs[1].splitlines()
    k = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
    problems.append(f"printed output differs at line {k + 1}: {a[k] if k < len(a) else '<end>'!r} against {b[k] if k < len(b) else '<end>'!r}")
count = 0
# the results file and the rest runs' files beside it
for path in sorted(glob.glob(old + "*.h5")):
    other = path.replace(os.path.dirname(old), os.path.dirname(new))
    if not os.path.exists(other):
        problems.append(f"{os.path.basename(other)} missing from the new build's files")
        continue
    fa, fb = h5py.File(path, "r"), h5py.File(other, "r")
    def attrs(oa, ob, where):
        if sorted(oa.attrs) != sorted(ob.attrs):
            problems.append(f"{where}: attributes {sorted(oa.attrs)} against {sorted(ob.attrs)}")
            return
        for k in oa.attrs:
            if k in ("created", "wall_time"):
                continue
            va, vb = oa.attrs[k], ob.attrs[k]
            if isinstance(va, np.ndarray) or isinstance(vb, np.ndarray):
                same = np.array_equal(np.asarray(va), np.asarray(vb), equal_nan=np.asarray(va).dtype.kind == "f")
            else:
                same = va == vb
            if not same:
                problems.append(f"{where} @{k}: {str(va)[:80]!r} against {str(vb)[:80]!r}")
    def visit(ga, gb, where):
        global count
        attrs(ga, gb, where or "/")
        if sorted(ga) != sorted(gb):
            problems.append(f"{where or '/'}: members {sorted(set(ga) ^ set(gb))} in one only")
        for k in sorted(set(ga) & set(gb)):
            a, b = ga[k], gb[k]
            w = f"{where}/{k}"
            if isinstance(a, h5py.Group):
                visit(a, b, w)
                continue
            attrs(a, b, w)
            count += 1
            if k == "wall_time" or w.endswith("/wall_time"):
                continue
            x, y = a[()], b[()]
            if isinstance(x, np.ndarray) and x.dtype.kind == "f":
                same = x.shape == y.shape and np.array_equal(x.view(np.uint8), y.view(np.uint8))
            else:
                same = np.array_equal(np.asarray(x), np.asarray(y))
            if not same:
                problems.append(f"{w} differs")
    visit(fa, fb, "")
print(f"{name:<14} {'identical' if not problems else 'DIFFERENT'}: {count} datasets, printed output {'the same' if logs[0] == logs[1] else 'different'}")
for p in problems[:12]:
    print("   ", p)
sys.exit(1 if problems else 0)
PY
done
exit $status
