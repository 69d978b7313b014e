#!/usr/bin/env bash
# Faults that need a file system of their own (root, tmpfs mounts), so they are not in the test
# suite: on 2 ranks,
#  - a disk that fills in the middle of a run (a 2 MB tmpfs): the run stops within seconds with
#    "cannot write", and `slideline post` reads every increment completed before;
#  - a read-only mount: `run -o` and `penalty-study -o` onto it are refused with exit 2 at once
#    (penalty-study's rank 1 used to wait forever).
# Prints one line per check and exits 1 on the first failure.
#
# usage: scripts/check-faults.sh   (as root)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
(cd "$here" && cargo build --release --quiet)
slideline="$here/target/release/slideline"
work="$(mktemp -d)"
mnt="$work/mnt"
mkdir -p "$mnt"
cleanup() { umount "$mnt" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAILED: $*"; exit 1; }

# a disk that fills up
mount -t tmpfs -o size=2m tmpfs "$mnt"
start=$(date +%s.%N)
set +e
timeout 120 mpirun -n 2 "$slideline" bellows --quick --quiet -o "$mnt/q.h5" > "$work/full.out" 2>&1
code=$?
set -e
seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
[ "$code" -ne 124 ] || fail "disk full: the run hung (killed after 120 s)"
[ "$code" -ne 0 ] || fail "disk full: the run reported success"
grep -q "cannot write $mnt/q.h5" "$work/full.out" || fail "disk full: no 'cannot write' message: $(cat "$work/full.out")"
kept=$("$slideline" post "$mnt/q.h5" 2>/dev/null | grep -c '^step .* inc ') || fail "disk full: post cannot read the file"
[ "$kept" -ge 1 ] || fail "disk full: no increment kept"
echo "disk full: stopped in ${seconds} s (exit $code) with 'cannot write'; post reads the $kept increment(s) completed before -> ok"
umount "$mnt"

# a read-only mount
mount -t tmpfs -o size=2m,ro tmpfs "$mnt"
cp "$here/examples/shrink_fit.toml" "$work/fit.toml"
for what in run penalty-study; do
    if [ "$what" = run ]; then
        args=(run "$work/fit.toml" -o "$mnt/fit.h5")
    else
        args=(penalty-study --deck "$work/fit.toml" --reaction ring_top --penalties 1e4,1e5 -o "$mnt/study.h5")
    fi
    set +e
    timeout 60 mpirun -n 2 "$slideline" "${args[@]}" > "$work/ro.out" 2>&1
    code=$?
    set -e
    [ "$code" -ne 124 ] || fail "read-only mount, $what: hung"
    [ "$code" -eq 2 ] && grep -q "cannot write" "$work/ro.out" || fail "read-only mount, $what: exit $code: $(cat "$work/ro.out")"
    echo "read-only mount, $what: exit 2, '$(grep -m1 '^error:' "$work/ro.out")' -> ok"
done
