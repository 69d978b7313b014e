#!/usr/bin/env bash
# Runs CalculiX (ccx, Debian package calculix-ccx) and slideline on 1 and 2 ranks on the same
# Abaqus/CalculiX deck and prints them side by side: the reaction history of a node set, max
# von Mises and max displacement at the end, increments, iterations, wall times and ratios.
#
# usage: scripts/compare-calculix.sh MODEL.inp --set NAME [--store]
#   --set NAME  the node set whose axial reaction is compared (a set with a prescribed uz;
#               the deck needs *NODE PRINT, NSET=NAME, TOTALS=ONLY with RF for CalculiX)
#   --store     also copy CalculiX's MODEL.dat beside the deck as MODEL.ccx.dat (the stored
#               reference of tests/calculix_decks.rs)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
deck="" set_name="" store=0
while [ $# -gt 0 ]; do
    case "$1" in
        --set) set_name="$2"; shift 2 ;;
        --store) store=1; shift ;;
        -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
        *) deck="$1"; shift ;;
    esac
done
if [ -z "$deck" ] || [ -z "$set_name" ] || [ ! -f "$deck" ]; then
    echo "usage: scripts/compare-calculix.sh MODEL.inp --set NAME [--store]" >&2
    exit 2
fi
source "$(dirname "$0")/calculix-setup.sh"

job="$(basename "$deck" .inp)"
deck_dir="$(cd "$(dirname "$deck")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$deck_dir"/*.inp "$work"/
cp "$deck_dir"/*.inc "$work"/ 2>/dev/null || true

# wall seconds of a command (bash's microsecond clock)
seconds() { local t0=$EPOCHREALTIME; "$@"; python3 -c "print(f'{$EPOCHREALTIME - $t0:.3f}')"; }
cd "$work"
echo "CalculiX: ccx -i $job" >&2
ccx_s=$(seconds sh -c "ccx -i $job > ccx.log 2>&1") || { tail -20 ccx.log >&2; exit 1; }
for n in 1 2; do
    echo "slideline on $n rank(s)" >&2
    s=$(seconds sh -c "mpirun -n $n '$slideline' run $job.inp -o run$n.h5 --quiet > run$n.log 2>&1") || { tail -20 run$n.log >&2; exit 1; }
    echo "$s" > run$n.seconds
    "$slideline" post run$n.h5 --csv run$n.csv > /dev/null
    last=$(python3 -c "import csv; print(len(list(csv.DictReader(open('run$n.csv')))))")
    { "$slideline" post run$n.h5 --field von_mises --increment "$last"; "$slideline" post run$n.h5 --field displacement --increment "$last"; } > run$n.post
done
echo "== $job: CalculiX 2.20 against slideline =="
python3 "$here/scripts/calculix_results.py" "$work/$job" "$set_name" "$ccx_s" \
    run1.csv "$(cat run1.seconds)" run1.post run2.csv "$(cat run2.seconds)" run2.post
if [ $store -eq 1 ]; then
    cp "$job.dat" "$deck_dir/$job.ccx.dat"
    echo "stored CalculiX's results as $job.ccx.dat beside the deck"
fi
