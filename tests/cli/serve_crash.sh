#!/bin/bash
# Crash safety: rounds in which an `earc-db build --report` and an
# `earc-plan serve` (planning with E-ARC, learning) write into one database
# and each is SIGKILLed at a random moment, until EARC_CRASH_KILLS kills
# (default 50) have been made, seeded by EARC_CRASH_SEED (default 1); more
# than EARC_CRASH_SECONDS (default 150) fails the test. Every few rounds
# and at the end: `earc-db verify` passes (the file opens, integrity_check
# ok, every row sound); at the end every id the builder's report or a
# service's answer said was committed before its kill is in the file, and
# a new service opens it, answers and exits 0 on SIGTERM.
# Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan earc-db earc-scenario
for k in 1 2 3 4 5 6; do
  "$BUILD/earc-scenario" generate --family mobile -n 4 --obstacles --seed "$k" -o "$WORK/s$k.json" > /dev/null ||
    { echo "FAIL: generate scenario $k"; exit 1; }
done

"$PY" - "$BUILD" "$WORK" "${EARC_CRASH_KILLS:-50}" "${EARC_CRASH_SEED:-1}" "${EARC_CRASH_SECONDS:-150}" <<'PY'
import json, os, random, signal, subprocess, sys, threading, time

build, work = sys.argv[1], sys.argv[2]
want_kills, seed, budget = int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
rng = random.Random(seed)
db = os.path.join(work, "crash.db")
plan_bin, db_bin = os.path.join(build, "earc-plan"), os.path.join(build, "earc-db")
scenarios = [os.path.join(work, "s%d.json" % k) for k in range(1, 7)]
failures = []
committed = {}  # id -> who reported it
stats = {"build_ids": 0, "service_ids": 0, "answers": 0, "kills": 0, "rounds": 0}

def fail(msg):
    failures.append(msg)

def report(ids, who):
    for i in ids:
        if i in committed:
            fail("id %d reported by %s and %s" % (i, committed[i], who))
        committed[i] = who

def verify(when):
    r = subprocess.run([db_bin, "verify", "--db", db], capture_output=True, text=True)
    if r.returncode != 0:
        fail("%s: verify exited %d: %s" % (when, r.returncode, (r.stdout + r.stderr).strip()[-400:]))

def feed(p, rnd, answers):
    # Requests one at a time; an answer read in full counts as reported.
    n = 0
    try:
        while True:
            p.stdin.write(json.dumps({"id": n, "scenario_file": scenarios[(rnd + n) % len(scenarios)],
                                      "method": "earc", "seed": rnd * 1000 + n, "time_limit": 20}) + "\n")
            p.stdin.flush()
            line = p.stdout.readline()
            if not line.endswith("\n"):
                return
            answers.append(json.loads(line))
            n += 1
    except (BrokenPipeError, OSError, ValueError):
        return

start = time.monotonic()
rnd = 0
while stats["kills"] < want_kills:
    if time.monotonic() - start > budget:
        fail("only %d kills in %.0f s" % (stats["kills"], budget))
        break
    rep = os.path.join(work, "build%d.report" % rnd)
    builder = subprocess.Popen([db_bin, "build", "--db", db, "--count", "100000", "--seed", str(1000 + rnd),
                                "--threads", "1", "--time-per-problem", "0.2", "--report", rep],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    service = subprocess.Popen([plan_bin, "serve", "--db", db, "--seed", str(rnd)], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    answers = []
    feeder = threading.Thread(target=feed, args=(service, rnd, answers))
    feeder.start()
    # Both are killed at random moments, in random order.
    victims = [builder, service]
    rng.shuffle(victims)
    for p in victims:
        time.sleep(rng.uniform(0.05, 1.2))
        p.send_signal(signal.SIGKILL)
        code = p.wait()
        if code != -signal.SIGKILL:
            # Finished before the kill (a short build): only a clean exit is fine.
            if code != 0:
                fail("round %d: %s exited %d" % (rnd, p.args[1], code))
        else:
            stats["kills"] += 1
    feeder.join()
    for f in (service.stdin, service.stdout):
        try:
            f.close()
        except OSError:
            pass
    ids = []
    if os.path.exists(rep):
        text = open(rep).read()
        for line in text.splitlines(keepends=True):
            if line.endswith("\n"):  # a line is written whole after the commit
                ids += [int(x) for x in line.split()]
    report(ids, "build round %d" % rnd)
    stats["build_ids"] += len(ids)
    for a in answers:
        if not a.get("ok"):
            fail("round %d: request failed: %s" % (rnd, json.dumps(a)[:300]))
            continue
        learned = a["stats"].get("db_learned_ids", [])
        report(learned, "service round %d" % rnd)
        stats["service_ids"] += len(learned)
    stats["answers"] += len(answers)
    rnd += 1
    stats["rounds"] = rnd
    if rnd % 8 == 0:
        verify("after round %d" % rnd)

verify("at the end")
r = subprocess.run([db_bin, "export", "--db", db, "-o", os.path.join(work, "final.jsonl")], capture_output=True, text=True)
if r.returncode != 0:
    fail("export: " + r.stderr.strip())
else:
    present = {json.loads(l)["id"] for l in open(os.path.join(work, "final.jsonl")).read().splitlines()[1:]}
    missing = sorted(i for i in committed if i not in present)
    if missing:
        fail("%d reported commits are missing, e.g. %s (%s)" % (len(missing), missing[:5], committed[missing[0]]))
if stats["build_ids"] == 0 or stats["service_ids"] == 0:
    fail("nothing was reported committed by %s: the kills tested nothing"
         % ("the builder" if stats["build_ids"] == 0 else "the services"))

# And the file is usable for planning again.
p = subprocess.Popen([plan_bin, "serve", "--db", db], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                     stderr=subprocess.PIPE, text=True)
p.stdin.write(json.dumps({"id": "after", "scenario_file": scenarios[0], "method": "earc"}) + "\n"); p.stdin.flush()
line = p.stdout.readline()
if not line or not json.loads(line).get("ok"):
    fail("a service on the crashed file did not answer: %r" % line)
p.send_signal(signal.SIGTERM)
try:
    code = p.wait(timeout=60)
except subprocess.TimeoutExpired:
    p.kill(); code = "hung"
if code != 0:
    fail("the last service exited %s on SIGTERM: %s" % (code, p.stderr.read()[-300:]))

print("seed %d: %d rounds, %d kills, %d answers; %d build ids and %d learned ids reported, all present"
      % (seed, stats["rounds"], stats["kills"], stats["answers"], stats["build_ids"], stats["service_ids"]))
for f in failures[:20]:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
PY
