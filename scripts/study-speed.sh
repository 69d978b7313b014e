#!/usr/bin/env bash
# A study's runs shared out to groups against today's sequential way, on this machine's 2
# cores, the two alternating so that the machine's drift hits both alike (REPEATS each,
# medians): the 6-penalty quick bellows study with 2 ranks per run (one after another) and
# with 2 groups of 1 rank, and the same for an 8-variant sweep of examples/dn200_joint.toml
# (convolutions 4..5 x plies 2..3 x ply thickness 0.4, 0.5, each with its elastic-plastic
# run), and the same 8 variants at rest (--elastic-only --squirm --frequencies: the code check
# and the buckling and frequency analyses, no stroke). Prints each median and the ratio
# concurrent / sequential (docs/performance.md quotes them).
#   scripts/study-speed.sh [BINARY]      (default target/release/slideline)
#   REPEATS=1 STUDIES="penalty sweep rest" scripts/study-speed.sh
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
bin=$(realpath "${1:-target/release/slideline}")
REPEATS=${REPEATS:-3}
out=out/study-speed
rm -rf "$out" && mkdir -p "$out"

penalty=(penalty-study --quick --penalties 1e3,3e3,1e4,3e4,1e5,3e5 -q)
sweep=(bellows-sweep --spec examples/dn200_joint.toml --vary convolutions=4..5 --vary plies=2..3 --vary ply_thickness=0.4,0.5 -q)
rest=("${sweep[@]}" --elastic-only --squirm --frequencies)
STUDIES=${STUDIES:-penalty sweep}

# one timed study: NAME G ARGS...
timed() {
    local name=$1 g=$2
    shift 2
    local start end
    start=$(date +%s.%N)
    mpirun -n 2 "$bin" "$@" --ranks-per-run "$g" -o "$out/$name.h5" >"$out/$name.log" 2>&1
    end=$(date +%s.%N)
    echo "$end - $start" | bc
}

declare -A walls
for i in $(seq "$REPEATS"); do
    for study in $STUDIES; do
        declare -n args=$study
        walls[$study-sequential]+="$(timed "$study-seq-$i" 2 "${args[@]}") "
        walls[$study-concurrent]+="$(timed "$study-con-$i" 1 "${args[@]}") "
        unset -n args
    done
done

median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
for study in $STUDIES; do
    seq_median=$(echo "${walls[$study-sequential]}" | median)
    con_median=$(echo "${walls[$study-concurrent]}" | median)
    printf '%-8s sequential (1 group of 2 ranks) %6.1f s [%s]  concurrent (2 groups of 1) %6.1f s [%s]  concurrent / sequential %.2f\n' \
        "$study" "$seq_median" "${walls[$study-sequential]% }" "$con_median" "${walls[$study-concurrent]% }" "$(echo "$con_median / $seq_median" | bc -l)"
done
