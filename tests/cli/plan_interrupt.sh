#!/bin/bash
# earc-plan plan and Ctrl-C: SIGINT a second or so into a plan that would
# run to its 60 s limit (E-ARC on a jam of 128 boxes, learning into a
# database) stops it within seconds with exit 130 and one line saying so;
# the solution file is whole and unsolved, as at the time limit, and the
# database verifies. SIGINT during --refine writes the best plan found so
# far, which validates. SIGTERM exits 143. lightning-db interrupted leaves
# no file. Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan earc-db earc-scenario earc-bench
"$BUILD/earc-scenario" generate --family mobile -n 128 --obstacles --seed 3 -o "$WORK/big.json" > /dev/null ||
  fail "generate"

"$PY" - "$BUILD" "$WORK" "$SRC/datasets/mobile-obst-16-s1.json" <<'PY'
import json, os, signal, subprocess, sys, time

build, work, small = (os.path.abspath(a) for a in sys.argv[1:4])
plan_bin = os.path.join(build, "earc-plan")
failures = []
def fail(msg): failures.append(msg)

def interrupted(args, sig, after=1.5):
    """Runs args, sends sig `after` s in: (exit code, stderr, seconds from the signal to the exit)."""
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=work)
    time.sleep(after)
    if p.poll() is not None:
        fail("%s ended before the signal: exit %d, %s" % (" ".join(args[1:3]), p.returncode, p.stderr.read()))
        return None
    t0 = time.monotonic()
    p.send_signal(sig)
    try:
        out, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill(); p.communicate()
        fail("%s: still running 30 s after the signal" % " ".join(args))
        return None
    return p.returncode, err, time.monotonic() - t0

def solution(name):
    with open(os.path.join(work, name)) as f:
        return json.load(f)  # whole JSON, or the test fails here

# E-ARC learning into a database, stopped unsolved.
r = interrupted([plan_bin, "plan", "big.json", "--method", "earc", "--db", "s.db", "--time-limit", "60",
                 "-o", "earc.json"], signal.SIGINT)
if r:
    rc, err, took = r
    lines = [l for l in err.splitlines() if "interrupted" in l]
    if rc != 130: fail("earc: exit %d, not 130: %s" % (rc, err))
    if took > 10: fail("earc: %.1f s from SIGINT to the exit" % took)
    if len(lines) != 1 or "interrupted (SIGINT)" not in lines[0] or "unsolved" not in lines[0]:
        fail("earc: not one line saying it was interrupted unsolved: %r" % err)
    sol = solution("earc.json")
    if sol["solved"] is not False or sol["stats"].get("failure") != ["time_limit"]:
        fail("earc: the solution is not an unsolved time-limit failure: %r" % sol["stats"].get("failure"))
    if sol["stats"].get("interrupted") != "SIGINT": fail("earc: stats.interrupted is %r" % sol["stats"].get("interrupted"))
    for side in ("s.db-wal", "s.db-shm"):
        if os.path.exists(os.path.join(work, side)): fail("the interrupted plan left %s" % side)
    v = subprocess.run([os.path.join(build, "earc-db"), "verify", "--db", "s.db"], cwd=work, capture_output=True, text=True)
    if v.returncode != 0: fail("earc-db verify after the interrupt: exit %d: %s" % (v.returncode, v.stderr))

# Prioritized refined for up to 60 s, stopped while refining: the best
# plan so far, valid. The signal comes well after the first plan would
# be made (timed without --refine: a sanitizer build is slower).
t0 = time.monotonic()
subprocess.run([plan_bin, "plan", small, "--method", "prioritized", "-q", "-o", "first.json"], cwd=work, check=True)
first_s = time.monotonic() - t0
r = interrupted([plan_bin, "plan", small, "--method", "prioritized", "--refine", "60", "--time-limit", "120",
                 "-o", "refined.json"], signal.SIGINT, after=1.0 + 2 * first_s)
if r:
    rc, err, took = r
    if rc != 130: fail("refine: exit %d, not 130: %s" % (rc, err))
    if took > 10: fail("refine: %.1f s from SIGINT to the exit" % took)
    if "interrupted (SIGINT)" not in err or "best valid plan" not in err:
        fail("refine: the message does not say the best plan is written: %r" % err)
    sol = solution("refined.json")
    ref = sol["stats"].get("refine", {})
    if sol["solved"] is not True or not ref: fail("refine: not solved, or no stats.refine")
    elif ref["seconds_spent"] > 15: fail("refine: refined for %s s of the 60" % ref["seconds_spent"])
    v = subprocess.run([plan_bin, "validate", small, "refined.json"], cwd=work, capture_output=True, text=True)
    if v.returncode != 0: fail("refine: the interrupted plan does not validate: %s" % v.stdout + v.stderr)

# SIGTERM: 143.
r = interrupted([plan_bin, "plan", "big.json", "--method", "arc", "--time-limit", "60", "-q", "-o", "arc.json"],
                signal.SIGTERM, after=1.0)
if r:
    rc, err, took = r
    if rc != 143 or "interrupted (SIGTERM)" not in err: fail("arc: exit %d on SIGTERM: %r" % (rc, err))
    solution("arc.json")

# earc-bench lightning-db: nothing written.
r = interrupted([os.path.join(build, "earc-bench"), "lightning-db", "--robots", "8", "--count", "1000",
                 "-o", "l.db"], signal.SIGINT, after=1.0)
if r:
    rc, err, took = r
    if rc != 130 or "interrupted (SIGINT)" not in err or "nothing written" not in err:
        fail("lightning-db: exit %d: %r" % (rc, err))
    if took > 15: fail("lightning-db: %.1f s from SIGINT to the exit" % took)
    if os.path.exists(os.path.join(work, "l.db")): fail("the interrupted lightning-db wrote its database")

for f in failures: print("FAIL: " + f)
sys.exit(1 if failures else 0)
PY
rc=$?
[ $rc -eq 0 ] || exit $rc
echo "ok: SIGINT and SIGTERM stop plans within seconds, files whole"
