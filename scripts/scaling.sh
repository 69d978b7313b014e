#!/usr/bin/env bash
# Speed of the bellows on 1 and 2 ranks: wall time (median of REPEATS runs, 1- and 2-rank runs
# alternating so that the machine's drift hits both alike), the 2-rank speed-up, and the time
# per Newton iteration against the number of unknowns with its fitted exponent.
#   scripts/scaling.sh                 the three target cases and the mesh series (REPEATS=3)
#   REPEATS=1 scripts/scaling.sh       one run each
# Cases: the default joint; the CalculiX deck of it (`bellows --export-inp`, run through the
# .inp reader); the fine ply mesh (4 elements through a ply, 0.5 mm along it); for the growth
# of the cost also the coarse (1 x 2.0) and the mesh-convergence fine (3 x 0.5) meshes.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
REPEATS=${REPEATS:-3}
cargo build --release --quiet
out=out/scaling
mkdir -p "$out"
bin=target/release/slideline

# the CalculiX deck of the default joint
[ -f "$out/joint.inp" ] || $bin bellows --export-inp "$out/joint.inp" >/dev/null

# one run: prints "wall_s newton_iterations unknowns"
one() {
    local ranks=$1 name=$2; shift 2
    local h5="$out/$name-$ranks.h5" log="$out/$name-$ranks.log"
    rm -f "$h5"
    local start end
    start=$(date +%s.%N)
    if [ "$name" = inp ]; then
        mpirun -n "$ranks" $bin run "$out/joint.inp" -q -o "$h5" >"$log" 2>&1
    else
        mpirun -n "$ranks" $bin bellows -q -o "$h5" "$@" >"$log" 2>&1
    fi
    end=$(date +%s.%N)
    python3 - "$h5" "$start" "$end" <<'EOF'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
its = int(f["history/newton_iterations"][:].sum())
nodes = f["mesh/coordinates"].shape[0] // 2 if f["mesh/coordinates"].ndim == 1 else f["mesh/coordinates"].shape[0]
print(f"{float(sys.argv[3]) - float(sys.argv[2]):.2f} {its} {2 * nodes}")
EOF
}

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

printf '%-9s %9s %7s %10s %10s %8s %12s %12s\n' case unknowns newton "1 rank s" "2 ranks s" speed-up "ms/it 1 r" "ms/it 2 r"
: >"$out/series.txt"
for spec in "default" "inp" "fine --ply-elements 4 --ply-element-length 0.5" "coarse --ply-elements 1 --ply-element-length 2.0" "fine3 --ply-elements 3 --ply-element-length 0.5"; do
    read -r name flags <<<"$spec"
    repeats=$REPEATS
    case $name in coarse | fine3) repeats=1 ;; esac
    : >"$out/$name.runs"
    for _ in $(seq "$repeats"); do
        for ranks in 1 2; do
            # shellcheck disable=SC2086
            echo "$ranks $(one "$ranks" "$name" $flags)" >>"$out/$name.runs"
        done
    done
    t1=$(awk '$1 == 1 {print $2}' "$out/$name.runs" | median)
    t2=$(awk '$1 == 2 {print $2}' "$out/$name.runs" | median)
    its1=$(awk '$1 == 1 {print $3}' "$out/$name.runs" | median)
    its2=$(awk '$1 == 2 {print $3}' "$out/$name.runs" | median)
    n=$(awk 'NR == 1 {print $4}' "$out/$name.runs")
    awk -v n="$n" -v t1="$t1" -v t2="$t2" -v i1="$its1" -v i2="$its2" -v name="$name" 'BEGIN {
        printf "%-9s %9d %7s %10.1f %10.1f %8.2f %12.1f %12.1f\n", name, n, (i1 == i2 ? i1 : i1 "/" i2), t1, t2, t1 / t2, 1000 * t1 / i1, 1000 * t2 / i2 }'
    case $name in default | coarse | fine3 | fine) echo "$n $(awk -v t="$t1" -v i="$its1" 'BEGIN {print t / i}') $(awk -v t="$t2" -v i="$its2" 'BEGIN {print t / i}')" >>"$out/series.txt" ;; esac
done

# least-squares exponent of time per Newton iteration against unknowns (bellows meshes)
awk '{x = log($1); for (k = 1; k <= 2; k++) {y = log($(k + 1)); sx[k] += x; sy[k] += y; sxx[k] += x * x; sxy[k] += x * y}; m++}
     END {for (k = 1; k <= 2; k++) printf "time per Newton iteration ~ unknowns^%.2f on %d rank(s) (%d meshes)\n", (m * sxy[k] - sx[k] * sy[k]) / (m * sxx[k] - sx[k] * sx[k]), k, m}' "$out/series.txt"
