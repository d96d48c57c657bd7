#!/bin/bash
# Many processes, one database file: 4 `earc-plan serve` processes (3 on
# stdin/stdout, 1 over its Unix socket) planning with E-ARC and learning,
# `earc-db build` runs inserting, and `earc-db export` / `earc-db inspect`
# reading, all at once for EARC_STRESS_SECONDS (default 40). Afterwards:
# no request failed (busy database or otherwise), every process exited 0,
# `earc-db verify` (integrity_check and every row) passes, and every row
# any writer reported inserted is there exactly once: its id reported by
# one writer only, present, and no two rows of a class share a key.
# Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan earc-db earc-scenario
for k in 1 2 3 4 5 6 7 8; do
  "$BUILD/earc-scenario" generate --family mobile -n 4 --obstacles --seed "$k" -o "$WORK/s$k.json" > /dev/null ||
    { echo "FAIL: generate scenario $k"; exit 1; }
done

"$PY" - "$BUILD" "$WORK" "${EARC_STRESS_SECONDS:-40}" <<'PY'
import json, os, signal, socket, subprocess, sys, threading, time

build, work, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
db = os.path.join(work, "shared.db")
plan_bin, db_bin = os.path.join(build, "earc-plan"), os.path.join(build, "earc-db")
scenarios = [os.path.join(work, "s%d.json" % k) for k in range(1, 9)]
failures = []
lock = threading.Lock()

def fail(msg):
    with lock:
        failures.append(msg)

learned = {}  # writer name -> list of ids it reported committed

def request(n, who):
    return json.dumps({"id": n, "scenario_file": scenarios[(n + who) % len(scenarios)],
                       "method": "earc", "seed": n, "time_limit": 20, "learn": True}) + "\n"

def check(name, n, line):
    if not line:
        fail("%s: no answer to request %d" % (name, n))
        return False
    r = json.loads(line)
    if r.get("id") != n or not r.get("ok"):
        fail("%s: request %d failed: %s" % (name, n, line.strip()[:300]))
        return False
    learned.setdefault(name, []).extend(r["stats"].get("db_learned_ids", []))
    plans[name] = plans.get(name, 0) + 1
    return True

plans = {}
services = []
sock_path = os.path.join(work, "svc.sock")
for i in range(4):
    args = [plan_bin, "serve", "--db", db, "--seed", str(i)]
    if i == 3:
        args += ["--socket", sock_path]
    services.append(subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                                     stderr=open(os.path.join(work, "svc%d.err" % i), "w")))

def drive_stdio(i):
    p, name, n = services[i], "service%d" % i, 0
    while time.monotonic() < end:
        p.stdin.write(request(n, i)); p.stdin.flush()
        if not check(name, n, p.stdout.readline()):
            return
        n += 1

def drive_socket(i):
    name, n, f = "service%d" % i, 0, sock_file
    while time.monotonic() < end:
        f.write(request(n, i)); f.flush()
        if not check(name, n, f.readline()):
            return
        n += 1
    sock.close()

def build_loop():
    k = 0
    while time.monotonic() < end:
        report = os.path.join(work, "build%d.report" % k)
        r = subprocess.run([db_bin, "build", "--db", db, "--count", "24", "--seed", str(100 + k), "--threads", "1",
                            "--time-per-problem", "0.2", "--report", report], capture_output=True, text=True)
        if r.returncode != 0:
            fail("build %d exited %d: %s" % (k, r.returncode, r.stderr.strip()[:300]))
            return
        ids = [int(x) for line in open(report) for x in line.split()] if os.path.exists(report) else []
        learned.setdefault("build%d" % k, []).extend(ids)
        k += 1

reads = {"export": 0, "inspect": 0}
def read_loop():
    while time.monotonic() < end:
        for what in ("export", "inspect"):
            args = [db_bin, what, "--db", db] + (["-o", os.path.join(work, "read.jsonl")] if what == "export" else [])
            r = subprocess.run(args, capture_output=True, text=True)
            if r.returncode != 0:
                fail("%s exited %d: %s" % (what, r.returncode, r.stderr.strip()[:300]))
                return
            reads[what] += 1
        time.sleep(0.2)

# Everything starts once a service has the file open: the socket service
# answers a ping only then (clients wait in its backlog until it does).
# The socket file appears at bind(), a moment before listen(): a connect
# in between is refused, so it is tried again.
sock = None
for _ in range(600):
    if os.path.exists(sock_path):
        try:
            sock = socket.socket(socket.AF_UNIX); sock.connect(sock_path)
            break
        except ConnectionRefusedError:
            sock.close(); sock = None
    time.sleep(0.05)
if sock is None:
    sys.exit("FAIL: service3's socket never accepted a connection")
sock_file = sock.makefile("rw")
sock_file.write('{"id": "hello", "op": "ping"}\n'); sock_file.flush()
if '"ok":true' not in sock_file.readline():
    fail("service3 did not answer a ping on its socket")
end = time.monotonic() + seconds
threads = [threading.Thread(target=drive_stdio, args=(i,)) for i in range(3)]
threads += [threading.Thread(target=drive_socket, args=(3,)), threading.Thread(target=build_loop),
            threading.Thread(target=read_loop)]
for t in threads: t.start()
for t in threads: t.join()

# Two services end at the end of their input, two on SIGTERM / SIGINT.
services[0].stdin.close(); services[1].stdin.close()
services[2].send_signal(signal.SIGTERM); services[3].send_signal(signal.SIGINT)
for i, p in enumerate(services):
    try:
        code = p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill(); code = "hung"
    if code != 0:
        fail("service%d exited %s: %s" % (i, code, open(os.path.join(work, "svc%d.err" % i)).read()[-300:]))
if os.path.exists(sock_path):
    fail("service3 left its socket file behind")

r = subprocess.run([db_bin, "verify", "--db", db], capture_output=True, text=True)
if r.returncode != 0:
    fail("verify: " + r.stdout.strip()[-500:])
r = subprocess.run([db_bin, "export", "--db", db, "-o", os.path.join(work, "final.jsonl")], capture_output=True, text=True)
if r.returncode != 0:
    fail("final export: " + r.stderr.strip())
    rows = []
else:
    rows = [json.loads(l) for l in open(os.path.join(work, "final.jsonl")).read().splitlines()[1:]]
ids = [row["id"] for row in rows]
present = set(ids)
if len(present) != len(ids):
    fail("an id appears twice in the export")
keys = {}
for row in rows:
    k = (row["kind"], row["robot_count"], row["signature"], row["base_class"], tuple(row["key"]))
    keys[k] = keys.get(k, 0) + 1
if any(c > 1 for c in keys.values()):
    fail("%d keys are stored more than once" % sum(1 for c in keys.values() if c > 1))
owner = {}
for name, got in learned.items():
    for i in got:
        if i in owner:
            fail("id %d reported by both %s and %s" % (i, owner[i], name))
        owner[i] = name
        if i not in present:
            fail("id %d reported committed by %s is missing" % (i, name))
by_service = sum(len(v) for n, v in learned.items() if n.startswith("service"))
by_build = sum(len(v) for n, v in learned.items() if n.startswith("build"))
if by_service == 0:
    fail("the services learned nothing: the test proved nothing about their inserts")
if by_build == 0:
    fail("the builder inserted nothing")
if min(plans.get("service%d" % i, 0) for i in range(4)) == 0:
    fail("a service answered no request: %s" % plans)
if reads["export"] == 0 or reads["inspect"] == 0:
    fail("no read ran: %s" % reads)
print("%.0f s: %s requests, %d rows (%d learned by services, %d built), %s reads"
      % (seconds, plans, len(rows), by_service, by_build, reads))
for f in failures[:20]:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
PY
