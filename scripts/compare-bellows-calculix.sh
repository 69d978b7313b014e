#!/usr/bin/env bash
# The built-in bellows joint run both ways: `slideline bellows` on 2 ranks, and CalculiX (ccx,
# Debian package calculix-ccx) on the same model exported with `slideline bellows --export-inp`.
# Prints the two end-reaction curves side by side (N per 2.5-degree sector, the bellows
# table's unit) at the end of step 1 and every 10 mm of compression, and the largest difference.
#
# usage: scripts/compare-bellows-calculix.sh [--quick | BELLOWS FLAGS...] [--keep DIR]
#   default: the quick joint (--quick, about a minute of CalculiX); give no --quick and any
#   other flags for other cases (the full default case takes CalculiX about an hour here).
#   --keep DIR  run in DIR and keep the files (deck, .dat, .frd, results)
set -euo pipefail
flags=() keep=""
while [ $# -gt 0 ]; do
    case "$1" in
        --keep) keep="$2"; shift 2 ;;
        -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
        *) flags+=("$1"); shift ;;
    esac
done
[ ${#flags[@]} -gt 0 ] || flags=(--quick)
source "$(dirname "$0")/calculix-setup.sh"
work_in "$keep"

"$slideline" bellows "${flags[@]}" --export-inp joint.inp > /dev/null
seconds() { local t0=$EPOCHREALTIME; "$@"; python3 -c "print(f'{$EPOCHREALTIME - $t0:.1f}')"; }
echo "CalculiX: ccx -i joint (CAX8, fixed increments)" >&2
ccx_s=$(seconds sh -c "ccx -i joint > ccx.log 2>&1") || { tail -20 ccx.log >&2; exit 1; }
echo "slideline bellows on 2 ranks" >&2
sl_s=$(seconds sh -c "mpirun -n 2 '$slideline' bellows ${flags[*]} -o bellows.h5 --quiet > slideline.log 2>&1") || { tail -20 slideline.log >&2; exit 1; }
"$slideline" post bellows.h5 --csv bellows.csv > /dev/null
stroke=$(sed -n 2p joint.inp | sed -E 's/.* ([0-9.eE+-]+) mm compression.*/\1/')

python3 - "$stroke" "$ccx_s" "$sl_s" <<'PY'
import csv, math, sys
stroke, ccx_s, sl_s = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
sector = 2.5 / 2.0  # CalculiX prints per 2-degree segment
theirs, t = [], None
lines = open("joint.dat").read().splitlines()
for k, line in enumerate(lines):
    if "total force (fx,fy,fz) for set MOVING_END" in line:
        time = float(line.split()[-1])
        theirs.append((time, -float(lines[k + 2].split()[1]) * sector))
# the CSV's header cells carry their units ("time [s]"): key the columns by name alone
rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(open("bellows.csv"))]
ours = [(float(r["time"]), -float(r["reaction_moving_end_z"]) * 2.5 * math.pi / 180.0) for r in rows]

def at(curve, time):
    """Linear interpolation in time (both run fixed increments, the stations may differ)."""
    for (t0, f0), (t1, f1) in zip(curve, curve[1:]):
        if t0 <= time <= t1 + 1e-12:
            return f0 + (f1 - f0) * (time - t0) / (t1 - t0)
    return float("nan")

stations = [(1.0, "end of step 1 (heat, pressure)")]
mm = 10.0
while mm < stroke - 1e-9:
    stations.append((1.0 + mm / stroke, f"{mm:.0f} mm"))
    mm += 10.0
stations.append((2.0, f"{stroke:g} mm (end)"))
print("end reaction of the moving end, N per 2.5-degree sector")
print(f"{'':32} {'CalculiX':>10} {'slideline':>10} {'diff %':>8}")
worst = 0.0
for time, label in stations:
    c, s = at(theirs, time), at(ours, time)
    d = 100.0 * (s - c) / c
    worst = max(worst, abs(d))
    print(f"{label:32} {c:10.2f} {s:10.2f} {d:8.2f}")
print(f"largest difference: {worst:.2f} %")
print(f"wall time: CalculiX {ccx_s:.0f} s (1 thread), slideline {sl_s:.0f} s (2 ranks)")
PY
