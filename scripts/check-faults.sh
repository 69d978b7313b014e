#!/usr/bin/env bash
# Faults that need a file system of their own (root, tmpfs mounts), so they are not in the test
# suite: on 2 ranks,
#  - a disk that fills in the middle of a run (a 2 MB tmpfs), on 1 and 2 ranks: the run stops
#    within seconds with exit 1 and "cannot write", its lock released, and `slideline post`
#    reads every increment completed before; `post --plot` onto a full disk says so plainly;
#  - SIGKILL to rank 0 of a 2-rank run at 20 random times, and 20 times timed into the file's
#    writes (scripts/kill_during_writes.py): post reads and a restart continues every file;
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

# a disk that fills up, on 1 and on 2 ranks, three times each (a 1-rank run once crashed
# after the write error, a 2-rank one hung or left its lock)
for ranks in 1 2; do
    for trial in 1 2 3; do
        mount -t tmpfs -o size=2m tmpfs "$mnt"
        start=$(date +%s.%N)
        set +e
        timeout 120 mpirun -n "$ranks" "$slideline" bellows --quick --quiet -o "$mnt/q.h5" > "$work/full.out" 2>&1
        code=$?
        set -e
        seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
        what="disk full, $ranks rank(s), trial $trial"
        [ "$code" -ne 124 ] || fail "$what: the run hung (killed after 120 s)"
        [ "$code" -eq 1 ] || fail "$what: exit $code (a crash, or success): $(cat "$work/full.out")"
        grep -q "^error: cannot write $mnt/q.h5" "$work/full.out" || fail "$what: no 'cannot write' line: $(cat "$work/full.out")"
        [ ! -e "$mnt/q.lock" ] || fail "$what: the lock was left"
        kept=$("$slideline" post "$mnt/q.h5" 2>/dev/null | grep -c '^step .* inc ') || fail "$what: post cannot read the file"
        [ "$kept" -ge 1 ] || fail "$what: no increment kept"
        echo "$what: stopped in ${seconds} s (exit 1) with 'cannot write', the lock released; post reads the $kept increment(s) completed before -> ok"
        umount "$mnt"
    done
done

# a full disk under post --plot: the file system's words, not a Debug struct
mount -t tmpfs -o size=2m tmpfs "$mnt"
mpirun -n 1 "$slideline" bellows --quick --quiet --displacement 5 --increments 2 -o "$work/small.h5" > /dev/null
dd if=/dev/zero of="$mnt/fill" bs=1k count=2000 2> /dev/null || true
set +e
"$slideline" post "$work/small.h5" --plot "$mnt/p.png" > "$work/plot.out" 2>&1
code=$?
set -e
[ "$code" -eq 1 ] && grep -q "cannot write $mnt/p.png: No space left on device" "$work/plot.out" || fail "post --plot onto a full disk: exit $code: $(cat "$work/plot.out")"
! grep -q "Custom {\|IoError(" "$work/plot.out" || fail "post --plot onto a full disk printed a Debug struct"
echo "post --plot onto a full disk: exit 1, '$(head -1 "$work/plot.out")' -> ok"
umount "$mnt"

# SIGKILL to rank 0 of a 2-rank run at random times (20 trials; one in three files was once
# left unreadable, "bad heap free list"): every file is read by post and continued by a restart
for trial in $(seq 1 20); do
    rm -f "$work"/k.*
    delay=$(awk -v s="$RANDOM" 'BEGIN { srand(s); printf "%.2f", 0.8 + 2.2 * rand() }')
    mpirun -n 2 "$slideline" bellows --quick --quiet -o "$work/k.h5" > /dev/null 2>&1 &
    launcher=$!
    sleep "$delay"
    # this mpirun's own ranks only (any other slideline on the machine, a test suite's, is left)
    rank0=$(pgrep -P "$launcher" -x slideline | sort -n | head -1 || true)
    [ -z "$rank0" ] || kill -9 "$rank0" 2> /dev/null || true
    wait || true
    what="SIGKILL to rank 0 at $delay s, trial $trial"
    [ -e "$work/k.h5" ] || { echo "$what: killed before the file was made -> ok"; continue; }
    if [ "$(head -c 8 "$work/k.h5" | od -An -tx1 | tr -d ' \n')" != 894844460d0a1a0a ]; then
        # killed between creating the file and its first flush (the superblock): nothing to
        # read, and post says so
        "$slideline" post "$work/k.h5" > "$work/k.post" 2>&1 && fail "$what: post read a file without a superblock"
        grep -q "incomplete: the run writing it stopped while creating it" "$work/k.post" || fail "$what: no superblock, and post says: $(cat "$work/k.post")"
        echo "$what: killed while creating the file; post says it is incomplete -> ok"
        continue
    fi
    "$slideline" post "$work/k.h5" > "$work/k.post" 2>&1 || fail "$what: post cannot read the file: $(cat "$work/k.post")"
    kept=$(grep -c '^step .* inc ' "$work/k.post" || true)
    if [ "$kept" -eq 0 ]; then
        echo "$what: killed before the first increment; post reads the file -> ok"
        continue
    fi
    if [ "$kept" -lt 42 ]; then
        mpirun -n 2 "$slideline" bellows --quiet --restart "$work/k.h5" -o "$work/k2.h5" > "$work/k2.out" 2>&1 || fail "$what: the restart failed: $(cat "$work/k2.out")"
    fi
    echo "$what: post reads $kept increment(s), a restart continues it -> ok"
done

# SIGKILL to rank 0 timed into the file's writes (20 trials; such kills once left the
# superblock's end of allocation short of the metadata written, "addr overflow", and the
# increments' old-style link table torn, "bad heap free list" or five increments lost)
python3 "$here/scripts/kill_during_writes.py" "$slideline" "$work" 20 || fail "a file killed during its writes did not read"

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
