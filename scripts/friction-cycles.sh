#!/usr/bin/env bash
# How friction costs the bellows' load cycle, two binaries side by side in one sitting: the quick
# and the default joint's cycle (`bellows --cycle`, 2 ranks) frictionless, with ply friction 0.2,
# and with ply friction 0.2 and sleeve friction 0.1, each run by OLD and NEW. Printed per run:
# increments, cutbacks, Newton iterations, wall time, the answers (end reaction at full stroke,
# loop area, friction dissipated, energy balance error) and the answers' difference from a
# reference: NEW at a quarter of the increment (4 x the increments).
#   scripts/friction-cycles.sh OLD NEW              # quick and default
#   SIZES=quick scripts/friction-cycles.sh OLD NEW  # the quick joint only (a few minutes)
# Wall times are one run each: this machine's speed drifts, so read them as rough ratios.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
[ $# -eq 2 ] || { echo "usage: $0 OLD_BINARY NEW_BINARY" >&2; exit 2; }
old=$1 new=$2
out=out/friction-cycles
mkdir -p "$out"
python=${SLIDELINE_PYTHON:-/usr/bin/python3}
frictions=("frictionless:" "plies:--friction-plies 0.2" "plies+sleeve:--friction-plies 0.2 --friction-sleeve 0.1")

for size in ${SIZES:-quick default}; do
    size_flags=()
    increments=240
    if [ "$size" = quick ]; then
        size_flags=(--quick)
        increments=40
    fi
    for f in "${frictions[@]}"; do
        name=${f%%:*}
        read -r -a flags <<<"${f#*:}"
        for which in old new ref; do
            bin=$new
            extra=()
            [ "$which" = old ] && bin=$old
            [ "$which" = ref ] && extra=(--increments $((4 * increments)))
            log="$out/$size-$name-$which.log"
            # a run that stops (exit 3) still prints its table: keep going
            mpirun -n 2 "$bin" bellows "${size_flags[@]}" --cycle ${flags[@]+"${flags[@]}"} ${extra[@]+"${extra[@]}"} \
                -o "$out/$size-$name-$which.h5" >"$log" 2>&1 || echo "($size $name $which: exit $?)" >>"$log"
        done
    done
done

"$python" - "$out" ${SIZES:-quick default} <<'PY'
import re, sys
out, sizes = sys.argv[1], sys.argv[2:]
def number(text, label, k=0):
    # a table line: the label, then the value column (e.g. "255.1", "92 / 8", "332.3 / 949.8")
    for line in text.splitlines():
        if line.strip().startswith(label):
            value = re.split(r"\s{2,}", line.strip())[1]
            try:
                return float(value.split("/")[k].split("(")[0])
            except (IndexError, ValueError):
                return float("nan")
    return float("nan")
def read(path):
    text = open(path).read()
    return {
        "increments": number(text, "increments / cutbacks"),
        "cutbacks": number(text, "increments / cutbacks", 1),
        "newton": number(text, "Newton iterations"),
        "wall": number(text, "wall time on"),
        "reaction": number(text, "end reaction at"),
        "loop": number(text, "cycle: loop area"),
        "dissipated": number(text, "thermal work / friction dissipated", 1),
        "balance": float((re.search(r"balance error.*\((-?[\d.]+) %\)", text) or [None, "nan"])[1]),
        "stopped": "exit" in text.splitlines()[-1] if text else True,
    }
def diff(a, b):
    return "-" if b == 0 or b != b or a != a else f"{100 * (a - b) / abs(b):+.2f} %"
for size in sizes:
    print(f"\n{size} joint, cycle on 2 ranks (reference: NEW at 4 x the increments)")
    print(f"{'friction':<13} {'run':<4} {'incs':>5} {'cutbacks':>8} {'Newton':>7} {'wall s':>7}  "
          f"{'reaction N':>10} {'loop N mm':>10} {'dissipated':>10} {'balance %':>9}  {'d reaction':>10} {'d loop':>8} {'d dissipated':>12}")
    frictionless_newton = {}
    for name in ["frictionless", "plies", "plies+sleeve"]:
        ref = read(f"{out}/{size}-{name}-ref.log")
        for which in ["old", "new", "ref"]:
            r = read(f"{out}/{size}-{name}-{which}.log")
            if name == "frictionless":
                frictionless_newton[which] = r["newton"]
            ratio = r["newton"] / frictionless_newton[which] if frictionless_newton.get(which) else float("nan")
            flag = " (stopped)" if r["stopped"] else ""
            print(f"{name:<13} {which:<4} {r['increments']:>5.0f} {r['cutbacks']:>8.0f} {r['newton']:>7.0f} {r['wall']:>7.1f}  "
                  f"{r['reaction']:>10.2f} {r['loop']:>10.1f} {r['dissipated']:>10.1f} {r['balance']:>9.3f}  "
                  f"{diff(r['reaction'], ref['reaction']):>10} {diff(r['loop'], ref['loop']):>8} {diff(r['dissipated'], ref['dissipated']):>12}"
                  f"   Newton / frictionless {ratio:.2f}{flag}")
PY
