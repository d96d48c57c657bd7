#!/bin/bash
# earc-plan serve --socket: once the socket file exists, a client can
# connect. The service's listen() is held up for a second (strace's
# syscall delay), a client connects the moment the file appears and must
# be answered; a socket bound at its path before listening would refuse it
# for that second. No binding name is left in the directory afterwards.
# Skipped (77) without /usr/bin/python3 or a working strace
# (tools/setup.sh --tests installs it).
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan
command -v strace > /dev/null || { echo "skipped: no strace"; exit 77; }
strace -qq -o /dev/null true 2> /dev/null || { echo "skipped: strace cannot trace here"; exit 77; }

"$PY" - "$BUILD" "$WORK" <<'PY' || exit 1
import glob, json, os, signal, socket, subprocess, sys, time

build, work = sys.argv[1], sys.argv[2]
db, sock_path = os.path.join(work, "s.db"), os.path.join(work, "s.sock")
def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)

tracer = subprocess.Popen(["strace", "-f", "-qq", "-o", os.path.join(work, "strace.out"),
                           "-e", "trace=listen", "-e", "inject=listen:delay_enter=1000000",
                           os.path.join(build, "earc-plan"), "serve", "--db", db, "--socket", sock_path],
                          stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
def service_pid():
    for task in glob.glob("/proc/%d/task/*/children" % tracer.pid):
        with open(task) as f:
            kids = f.read().split()
        if kids:
            return int(kids[0])
    return None
try:
    deadline = time.monotonic() + 60
    while not os.path.exists(sock_path):
        if tracer.poll() is not None:
            fail("the service ended before its socket appeared: %s" % tracer.stderr.read().strip())
        if time.monotonic() > deadline:
            fail("no socket file after 60 s")
        time.sleep(0.001)
    s = socket.socket(socket.AF_UNIX)
    try:
        s.connect(sock_path)
    except OSError as e:
        fail("the socket file exists but connecting was refused: %s" % e)
    f = s.makefile("rw")
    f.write('{"id": 1, "op": "ping"}\n'); f.flush()
    answer = f.readline()
    if json.loads(answer) != {"id": 1, "ok": True, "protocol": "earc.service.v1"}:
        fail("ping: %r" % answer)
    s.close()
    with open(os.path.join(work, "strace.out")) as trace:
        if "listen(" not in trace.read():
            fail("strace saw no listen(): the delay was not applied")
    left = [n for n in os.listdir(work) if n.startswith(".earc-serve")]
    if left:
        fail("binding names left beside the socket: %s" % left)
finally:
    pid = service_pid()
    if pid:
        os.kill(pid, signal.SIGTERM)
    try:
        tracer.wait(timeout=60)
    except subprocess.TimeoutExpired:
        tracer.kill()
if os.path.exists(sock_path):
    fail("the socket file was not removed on SIGTERM")
PY
echo "ok: a client connects the moment the socket file appears"
