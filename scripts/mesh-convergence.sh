#!/usr/bin/env bash
# Mesh convergence of the seed bellows case: runs three ply meshes (elements through each ply x
# element length along the meridian) on 2 ranks, 240 increments each, and prints the end
# reaction, max von Mises, max plastic strain and wall time of each. Extra arguments go to
# `slideline bellows` (e.g. --displacement 20 for a shorter study).
#   scripts/mesh-convergence.sh [bellows flags]
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
cargo build --release --quiet
out=out/mesh-convergence
mkdir -p "$out"
printf '%-8s %-16s %16s %14s %12s %10s\n' mesh "ply elements" "reaction N/sec" "von Mises MPa" "max ep" "wall s"
for spec in "coarse 1 2.0" "default 2 1.0" "fine 3 0.5"; do
    read -r name through length <<<"$spec"
    log="$out/$name.log"
    mpirun -n 2 target/release/slideline bellows --ply-elements "$through" --ply-element-length "$length" \
        -q -o "$out/$name.h5" "$@" >"$log" 2>&1 || { echo "$name: run failed, see $log"; continue; }
    reaction=$(awk '/end reaction at .* per 2.5-deg sector/ {print $(NF-1)}' "$log")
    vm=$(awk '/max von Mises \(Gauss point\) at [0-9.]+ mm/ {print $(NF-1)}' "$log")
    ep=$(awk '/max equivalent plastic strain at/ {print $(NF-1)}' "$log")
    wall=$(awk '/wall time on/ {print $(NF-1)}' "$log")
    printf '%-8s %-16s %16s %14s %12s %10s\n' "$name" "$through x $length mm" "$reaction" "$vm" "$ep" "$wall"
done
