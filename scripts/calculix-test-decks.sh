#!/usr/bin/env bash
# Runs every deck of a directory of CalculiX test decks (such as CalculiX's own axisymmetric
# ones) unchanged through slideline (2 ranks) and, where slideline runs it, through CalculiX
# 2.20 (ccx, Debian package calculix-ccx), and prints a table: slideline's verdict (runs, or
# its error naming the card) and, for the decks that run, the largest difference of the final
# nodal displacements from ccx's printed ones, as a fraction of ccx's largest (a heat deck: of
# the nodal temperatures, as a fraction of ccx's range).
#
# usage: scripts/calculix-test-decks.sh DIR [DECK ...]
#   DIR   the decks (e.g. ../shared/calculix-tests/axisymmetric); work files go to
#         out/calculix-test-decks/
#   DECK  only these (names without .inp)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:?usage: scripts/calculix-test-decks.sh DIR [DECK ...]}"
shift
source "$(dirname "$0")/calculix-setup.sh"
work="$here/out/calculix-test-decks"
mkdir -p "$work"
if [ $# -gt 0 ]; then decks=("$@"); else decks=(); for f in "$dir"/*.inp; do decks+=("$(basename "$f" .inp)"); done; fi
printf '| deck | slideline | against ccx 2.20 (final displacements) |\n| --- | --- | --- |\n'
runs=0
for name in "${decks[@]}"; do
    rm -rf "${work:?}/$name"; mkdir -p "$work/$name"
    cp "$dir/$name.inp" "$work/$name/"
    cd "$work/$name"
    if timeout 600 mpirun -n 2 --oversubscribe "$slideline" run "$name.inp" -o "$name.h5" --quiet > slideline.log 2>&1; then
        runs=$((runs + 1))
        # a deck that prints neither displacements nor stresses (thread prints contact only)
        # gets *NODE PRINT of its set NALL in ccx's copy: an output request, no change to
        # what ccx solves
        # a heat deck's temperatures likewise (ax6ht prints only the heat flux)
        if grep -qiE '^\*HEAT TRANSFER' "$name.inp" && ! grep -qiE '^NT *$' "$name.inp" && grep -qiE 'NSET *= *NALL' "$name.inp"; then
            "$python" -c 'import sys; s = open(sys.argv[1]).read(); i = s.lower().rfind("*end step"); open(sys.argv[1], "w").write(s[:i] + "*NODE PRINT, NSET=NALL\nNT\n" + s[i:])' "$name.inp"
        elif ! grep -qiE '^\*(NODE|EL) PRINT' "$name.inp" && grep -qiE 'NSET *= *NALL' "$name.inp"; then
            "$python" -c 'import sys; s = open(sys.argv[1]).read(); i = s.lower().rfind("*end step"); open(sys.argv[1], "w").write(s[:i] + "*NODE PRINT, NSET=NALL\nU\n" + s[i:])' "$name.inp"
        fi
        if timeout 600 ccx "$name" > ccx.log 2>&1 && [ -f "$name.dat" ]; then
            compared="$("$python" "$here/scripts/calculix_decks.py" "$name.dat" "$name.h5")"
        else
            compared="ccx failed (see $work/$name/ccx.log)"
        fi
        printf "| %s | runs | %s |\n" "$name" "$(echo "$compared" | tr "\n" " ")"
    else
        code=$?
        reason="$(grep -m1 '^error:' slideline.log | sed 's/^error: //; s/|/\\|/g' || true)"
        printf '| %s | exit %s: %s | |\n' "$name" "$code" "${reason:-see $work/$name/slideline.log}"
    fi
    cd "$here"
done
echo
echo "$runs of ${#decks[@]} decks run"
