#!/bin/bash
# earc-plan serve --socket: a client that sends requests and does not read
# its answers holds up no other client and no stop signal. Client x sends
# 20,000 pings (about 1 MB of answers, more than a socket holds) and reads
# nothing; client y's ping is answered at once; x then reads every answer,
# in order; a second such client is left unread when SIGTERM comes, and
# the service still exits 0 within seconds and removes its socket.
# Skipped (77) without /usr/bin/python3.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
needPython
needBuilt earc-plan

"$PY" - "$BUILD" "$WORK" <<'PY' || exit 1
import json, os, signal, socket, subprocess, sys, time

build, work = sys.argv[1], sys.argv[2]
sock_path = os.path.join(work, "s.sock")
def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)
N = 20000
svc = subprocess.Popen([os.path.join(build, "earc-plan"), "serve", "--db", os.path.join(work, "s.db"),
                        "--socket", sock_path], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
try:
    deadline = time.monotonic() + 60
    while not os.path.exists(sock_path):
        if svc.poll() is not None or time.monotonic() > deadline:
            fail("no socket: %s" % svc.stderr.read())
        time.sleep(0.01)

    def flood():
        c = socket.socket(socket.AF_UNIX)
        c.connect(sock_path)
        c.settimeout(30)
        try:
            c.sendall(b"".join(b'{"id": %d, "op": "ping"}\n' % i for i in range(N)))
        except socket.timeout:
            fail("the service stopped reading a client's requests for 30 s")
        return c
    x = flood()
    time.sleep(1)  # the service answers what it can and is left with a full socket
    y = socket.socket(socket.AF_UNIX)
    y.settimeout(10)
    y.connect(sock_path)
    y.sendall(b'{"id": "y", "op": "ping"}\n')
    try:
        answer = y.makefile().readline()
    except socket.timeout:
        fail("a client that does not read held up another client's ping for 10 s")
    if json.loads(answer).get("id") != "y":
        fail("y's answer: %r" % answer)

    x.settimeout(30)
    got = x.makefile()
    for i in range(N):
        line = got.readline()
        if json.loads(line).get("id") != i:
            fail("x's answer %d: %r" % (i, line))

    z = flood()  # left unread
    time.sleep(1)
    svc.send_signal(signal.SIGTERM)
    try:
        rc = svc.wait(timeout=15)
    except subprocess.TimeoutExpired:
        fail("SIGTERM did not stop the service within 15 s while a client did not read")
    if rc != 0:
        fail("exit %d after SIGTERM: %s" % (rc, svc.stderr.read()))
    if os.path.exists(sock_path):
        fail("the socket file was left")
finally:
    if svc.poll() is None:
        svc.kill()
PY
echo "ok: a client that does not read holds up no other client and no signal"
