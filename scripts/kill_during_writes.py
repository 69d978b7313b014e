#!/usr/bin/env python3
"""SIGKILL to rank 0 of a 2-rank quick joint timed into its file's writes (where a kill at a
random time rarely lands): the results file's modification time is watched in a tight loop, and
after its k-th change (k random in KMIN..KMAX, about a dozen per increment) rank 0 is killed
after a random 0 to 4 ms. Then `post` must read the file (or call it incomplete, killed while
being created) and a restart continue it. Prints a line per trial; exit 1 if any file failed,
kept as WORK/trialN.h5.

usage: scripts/kill_during_writes.py SLIDELINE WORK TRIALS   (check-faults.sh runs it)
"""
import os
import random
import signal
import subprocess
import sys
import time

slideline, work, trials = sys.argv[1], sys.argv[2], int(sys.argv[3])
kmin, kmax = int(os.environ.get("KMIN", "20")), int(os.environ.get("KMAX", "400"))
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
h5 = os.path.join(work, "w.h5")
failed = 0
for t in range(1, trials + 1):
    for name in ("w.h5", "w.lock", "w.sta", "w.xmf", "w2.h5", "w2.lock"):
        if os.path.exists(os.path.join(work, name)):
            os.remove(os.path.join(work, name))
    run = subprocess.Popen(["mpirun", "-n", "2", slideline, "bellows", "--quick", "--quiet", "-o", h5], env=env,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    k, delay = random.randint(kmin, kmax), random.uniform(0.0, 0.004)
    seen, last = 0, None
    while run.poll() is None and seen < k:
        try:
            stamp = os.stat(h5).st_mtime_ns
        except FileNotFoundError:
            stamp = None
        if stamp is not None and stamp != last:
            last, seen = stamp, seen + 1
    what = f"SIGKILL to rank 0 at the file's change {k} + {delay * 1e3:.1f} ms, trial {t}"
    if run.poll() is not None:
        print(f"{what}: the run ended first -> skipped")
        continue
    time.sleep(delay)
    # this mpirun's own ranks only; the lowest process id is rank 0
    ranks = subprocess.run(["pgrep", "-P", str(run.pid), "-x", os.path.basename(slideline)], capture_output=True, text=True).stdout.split()
    if ranks:
        os.kill(min(map(int, ranks)), signal.SIGKILL)
    run.wait()
    kept = os.path.join(work, f"trial{t}.h5")
    subprocess.run(["cp", h5, kept], check=True)
    post = subprocess.run([slideline, "post", h5], capture_output=True, text=True, env=env)
    notes = " ".join(line for line in post.stderr.splitlines() if line.startswith("note"))
    if post.returncode != 0:
        if "incomplete: the run writing it stopped while creating it" in post.stderr:
            print(f"{what}: killed while creating the file; post says it is incomplete -> ok")
            os.remove(kept)
            continue
        failed += 1
        print(f"FAILED: {what}: post cannot read the file (kept as {kept}): {post.stderr.strip()}")
        continue
    rows = sum(1 for line in post.stdout.splitlines() if line.startswith("step ") and " inc " in line)
    # only the increment being written when the rank was killed may be incomplete
    lost = [line for line in post.stderr.splitlines() if "were not completely written" in line and ("," in line or "(s)  were" in line)]
    if lost:
        failed += 1
        print(f"FAILED: {what}: complete increments lost (kept as {kept}): {lost[0]}")
        continue
    if 0 < rows < 42:
        again = subprocess.run(["mpirun", "-n", "2", slideline, "bellows", "--quiet", "--restart", h5, "-o", os.path.join(work, "w2.h5")],
                               capture_output=True, text=True, env=env)
        if again.returncode != 0:
            failed += 1
            print(f"FAILED: {what}: the restart failed (kept as {kept}): {again.stderr.strip()}")
            continue
    os.remove(kept)
    print(f"{what}: post reads {rows} increment(s){', a restart continues it' if 0 < rows < 42 else ''} -> ok {notes}")
print(f"killed during writes: {trials - failed} of {trials} files read")
sys.exit(1 if failed else 0)
