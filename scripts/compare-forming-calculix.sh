#!/usr/bin/env bash
# The forming (`slideline bellows --form`) checked by CalculiX: the forming's deck exported with
# `--form --export-inp`, run by CalculiX (ccx, Debian package calculix-ccx) and by `slideline
# run` on 2 ranks, the same deck both ways; prints, at every time both reached, the ply's
# largest displacement and the largest difference between the two at a node, each crest's
# outside radius and the ply's thickness there, and the largest nodal plastic strain
# (scripts/forming_calculix.py). The deck's two fold pairs (each ply face on itself, for the
# service) are taken out: no fold touches while forming (slideline's history shows none active),
# and CalculiX need not search a surface against itself.
#
# usage: scripts/compare-forming-calculix.sh [PARAMS.toml] [BELLOWS FLAGS...] [--keep DIR]
#   default: one ply of 2 mm, two of the seed's convolutions, friction 0.05 on the dies, the
#   quick mesh (CalculiX 4 to 7 minutes here; without friction it stalls in the closing:
#   docs/bellows.md); give mesh flags for the mesh study (the default mesh: --ply-elements 2;
#   any flag replaces --quick).
#   --keep DIR  run in DIR and keep the files (deck, .dat, .frd, results)
set -euo pipefail
params="" flags=() keep=""
while [ $# -gt 0 ]; do
    case "$1" in
        --keep) keep="$2"; shift 2 ;;
        -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
        *.toml) params="$(realpath "$1")"; shift ;;
        *) flags+=("$1"); shift ;;
    esac
done
[ ${#flags[@]} -gt 0 ] || flags=(--quick)
source "$(dirname "$0")/calculix-setup.sh"
work_in "$keep"
if [ -z "$params" ]; then
    params="$work/forming.toml"
    printf '[bellows]\nconvolutions = 2\nplies = 1\nply_thickness = 2.0\n[design]\naxial_compression = 10.0\n[forming]\nfriction = 0.05\n' > "$params"
fi

"$slideline" bellows --form --params "$params" "${flags[@]}" --export-inp exported.inp > /dev/null
python3 - <<'PY'
import re
deck = open("exported.inp").read()
for name in ("outside_folds", "inside_folds"):
    pattern = r"\*SURFACE INTERACTION, NAME=%s\n\*SURFACE BEHAVIOR[^\n]*\n[^\n]*\n(\*FRICTION\n[^\n]*\n)?\*CONTACT PAIR[^\n]*\n[^\n]*\n" % name
    deck, found = re.subn(pattern, "", deck)
    assert found == 1, f"the fold pair {name} not found in the exported deck"
open("forming.inp", "w").write(deck)
PY
seconds() { local t0=$EPOCHREALTIME; "$@"; python3 -c "print(f'{$EPOCHREALTIME - $t0:.0f}')"; }
echo "CalculiX: ccx -i forming" >&2
ccx_s=$(seconds sh -c "ccx -i forming > ccx.log 2>&1") || { tail -20 ccx.log >&2; echo "CalculiX stopped; the times it reached are compared" >&2; }
echo "slideline run forming.inp on 2 ranks" >&2
sl_s=$(seconds sh -c "mpirun -n 2 '$slideline' run forming.inp -o forming.h5 --quiet > slideline.log 2>&1") || { tail -20 slideline.log >&2; exit 1; }
"$python" "$here/scripts/forming_calculix.py" forming.frd forming.inp forming.h5
echo "wall time: CalculiX ${ccx_s:-?} s, slideline ${sl_s} s (2 ranks)"
