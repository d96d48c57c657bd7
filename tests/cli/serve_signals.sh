#!/bin/bash
# earc-plan serve end to end: a second service on the same socket is
# refused; bad lines on the socket get one-line errors and the service goes
# on; SIGINT during a long planning request cuts it short (answered as
# interrupted, in seconds, not at its 60 s limit), what it learned is in
# the file, the socket file is removed and the exit status is 0. An idle
# service, and one blocked writing to a stdout nobody reads, end cleanly
# on SIGINT (two at once) and SIGTERM.
# Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan earc-db earc-scenario
# A request that is still planning 1.5 s in: 128 boxes among obstacles in
# the 20 x 20 square, seed 3, a jam E-ARC plans to its time limit (96 of
# them, once unsolved too, the crowd solver now plans in half a second).
"$BUILD/earc-scenario" generate --family mobile -n 128 --obstacles --seed 3 -o "$WORK/big.json" > /dev/null ||
  { echo "FAIL: generate"; exit 1; }

"$PY" - "$BUILD" "$WORK" <<'PY'
import json, os, signal, socket, subprocess, sys, time

build, work = sys.argv[1], sys.argv[2]
plan_bin, db_bin = os.path.join(build, "earc-plan"), os.path.join(build, "earc-db")
db, sock_path = os.path.join(work, "s.db"), os.path.join(work, "s.sock")
failures = []
def fail(msg): failures.append(msg)

svc = subprocess.Popen([plan_bin, "serve", "--db", db, "--socket", sock_path], stdin=subprocess.PIPE,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
for _ in range(600):
    if os.path.exists(sock_path):
        break
    time.sleep(0.05)
s = socket.socket(socket.AF_UNIX); s.connect(sock_path)
f = s.makefile("rw")
def ask(line):
    f.write(line + "\n"); f.flush()
    return f.readline()

first = ask('{"id": 1, "op": "ping"}')
if json.loads(first) != {"id": 1, "ok": True, "protocol": "earc.service.v1"}:
    fail("ping: %r" % first)

# A second service on the same socket: refused, exit 2, one line.
r = subprocess.run([plan_bin, "serve", "--db", os.path.join(work, "other.db"), "--socket", sock_path],
                   stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
if r.returncode != 2 or "another service is listening" not in r.stderr or r.stderr.count("\n") != 1:
    fail("second service on the socket: exit %d, %r" % (r.returncode, r.stderr))
if os.path.exists(os.path.join(work, "other.db")):
    fail("the refused service created its database")

for bad, why in [("this is not json", "malformed JSON"), ('{"id": 2, "scenario": {"format": "x"}}', "$.format"),
                 ('{"id": 3, "op": "plan", "scenario_file": "%s", "seed": -1}' % os.path.join(work, "big.json"), "$.seed")]:
    line = ask(bad)
    if not line.endswith("\n") or line.count("\n") != 1:
        fail("answer to %r is not one line: %r" % (bad, line))
        continue
    a = json.loads(line)
    if a.get("ok") is not False or why not in a.get("error", ""):
        fail("bad request %r: %r" % (bad, line))
if json.loads(ask('{"id": 4, "op": "ping"}')).get("ok") is not True:
    fail("the service stopped serving after bad requests")

def interrupt(svc, request_id, method, sig):
    """Sends a long request on stdin, then sig 1.5 s into it: (answer line, exit code, seconds to stop)."""
    svc.stdin.write(json.dumps({"id": request_id, "scenario_file": os.path.join(work, "big.json"), "time_limit": 60,
                                "method": method}) + "\n")
    svc.stdin.flush()
    time.sleep(1.5)
    t0 = time.monotonic()
    svc.send_signal(sig)
    line = svc.stdout.readline()
    try:
        code = svc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        svc.kill(); code = "hung"
    return line, code, time.monotonic() - t0

# A long request on stdin, interrupted by SIGINT.
line, code, took = interrupt(svc, "long", "earc", signal.SIGINT)
if code != 0:
    fail("exit status after SIGINT: %s (%s)" % (code, svc.stderr.read()[-300:]))
if took > 10:
    fail("took %.1f s to stop after SIGINT" % took)
learned = []
try:
    a = json.loads(line)
    if a.get("id") != "long" or a.get("ok") is not True or a.get("interrupted") is not True or a.get("solved"):
        fail("interrupted request answered %s" % line[:300])
    learned = a["stats"]["db_learned_ids"]
except (ValueError, KeyError):
    fail("no answer to the interrupted request: %r" % line[:300])
if os.path.exists(sock_path):
    fail("socket file left behind")
r = subprocess.run([db_bin, "export", "--db", db, "-o", os.path.join(work, "e.jsonl")], capture_output=True, text=True)
ids = {json.loads(l)["id"] for l in open(os.path.join(work, "e.jsonl")).read().splitlines()[1:]} if r.returncode == 0 else set()
if not set(learned) <= ids:
    fail("learned ids missing from the file: %s" % sorted(set(learned) - ids)[:5])
print("SIGINT answered and exited in %.2f s; %d experiences learned before it, all in the file" % (took, len(learned)))

# SIGTERM during a Lightning request (OMPL's own solve loop) stops it too.
svc = subprocess.Popen([plan_bin, "serve", "--db", os.path.join(work, "l.db")], stdin=subprocess.PIPE,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
line, code, took = interrupt(svc, "lightning", "lightning", signal.SIGTERM)
if code != 0 or took > 10:
    fail("lightning request: exit %s after %.1f s of SIGTERM" % (code, took))
elif '"interrupted":true' not in line:
    fail("lightning request not answered as interrupted: %r" % line[:300])
else:
    print("SIGTERM during a Lightning request: answered and exited in %.2f s" % took)
def stops(svc, what, sig, twice=False):
    """Sends sig (twice: two at once) and checks a clean exit 0 within 10 s and the closing line naming it."""
    svc.send_signal(sig)
    if twice:
        svc.send_signal(sig)
    try:
        svc.stdin.close()
    except BrokenPipeError:
        pass
    try:
        code = svc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        svc.kill(); code = "hung"
    err = svc.stderr.read()
    name = "SIGINT" if sig == signal.SIGINT else "SIGTERM"
    if code != 0:
        fail("%s: exit %s after %s: %r" % (what, code, name, err[-300:]))
    elif ("earc-plan serve: %s:" % name) not in err:
        fail("%s: the closing line does not name %s: %r" % (what, name, err[-300:]))

# Idle, waiting for requests on the socket and stdin: two SIGINTs at once
# (every one is caught) end it cleanly, the socket file removed.
svc = subprocess.Popen([plan_bin, "serve", "--method", "arc", "--socket", sock_path], stdin=subprocess.PIPE,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
for _ in range(600):
    if os.path.exists(sock_path):
        break
    time.sleep(0.05)
stops(svc, "idle service", signal.SIGINT, twice=True)
if os.path.exists(sock_path):
    fail("idle service: socket file left behind")

# Writing answers to a stdout nobody reads (the pipe full): SIGTERM still
# ends it, the blocked write interrupted.
svc = subprocess.Popen([plan_bin, "serve", "--method", "arc"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
svc.stdin.write('{"id": "a long id to fill the pipe sooner", "op": "ping"}\n' * 1500)  # 85 kB: the pipe to it holds what it leaves unread
svc.stdin.flush()
time.sleep(1.0)
stops(svc, "service blocked on stdout", signal.SIGTERM)
print("idle and blocked-on-stdout services: clean exits on SIGINT and SIGTERM")
for m in failures:
    print("FAIL:", m)
sys.exit(1 if failures else 0)
PY
