#!/usr/bin/python3
"""What keeping roadmaps between requests saves `earc-plan serve` (Markdown
and a figure).

    /usr/bin/python3 tools/plots/serve_roadmaps.py BUILD_DIR WORK_DIR
        [--repeats N] [--seed S]

Makes the scenarios in WORK_DIR (32 mobile robots among 12 obstacles, 16
arms among obstacles, 16 robots on MovingAI's den520d) and the default
mobile and arm databases, then for each scenario and method (arc, earc)
sends the same request N times (default 15) to one service that keeps
roadmaps (the default) and to one that does not (--roadmap-cache-mib 0),
the two taking turns request by request. Requests are deterministic
(work budgets) and E-ARC's do not learn, so every answer to a request
must have the same paths: the script fails if not. The first request of
each service is left out (it builds the roadmaps either way).

Prints per scenario and method: median planning time with and without
kept roadmaps, the ratio of medians, the median of the paired ratios, and
the roadmaps' share of the time without them; writes
WORK_DIR/serve-roadmaps.png. Every error is one line, exit status 2.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys


def fail(msg):
    print("serve_roadmaps.py: " + msg, file=sys.stderr)
    sys.exit(2)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        fail("%s exited %d: %s" % (" ".join(cmd), p.returncode, (p.stderr or p.stdout).strip()[-300:]))


class Service:
    def __init__(self, plan, args):
        self.p = subprocess.Popen([plan, "serve"] + args, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                  stderr=subprocess.DEVNULL, text=True, bufsize=1)

    def ask(self, request):
        self.p.stdin.write(json.dumps(request) + "\n")
        self.p.stdin.flush()
        line = self.p.stdout.readline()
        if not line:
            fail("the service ended without answering")
        answer = json.loads(line)
        if not answer.get("ok") or not answer.get("solved"):
            fail("request not solved: %s" % line[:300])
        return answer

    def close(self):
        self.p.stdin.close()
        self.p.wait()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("build")
    ap.add_argument("work")
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    if a.repeats < 2:
        fail("--repeats must be at least 2")
    plan, scen, db = (os.path.join(a.build, p) for p in ("earc-plan", "earc-scenario", "earc-db"))
    for prog in (plan, scen, db):
        if not os.access(prog, os.X_OK):
            fail("%s: not an executable (give the build directory)" % prog)
    os.makedirs(a.work, exist_ok=True)
    w = lambda name: os.path.join(a.work, name)
    scenarios = [
        ("32 mobile robots, 12 obstacles", "mobile.db",
         ["generate", "--family", "mobile", "-n", "32", "--obstacles", "--seed", str(a.seed), "-o", w("mobile-obst-32.json")],
         w("mobile-obst-32.json")),
        ("16 arms among obstacles", "arms.db",
         ["generate", "--family", "arms", "-n", "16", "--obstacles", "--seed", str(a.seed), "-o", w("arms-obst-16.json")],
         w("arms-obst-16.json")),
        ("den520d, 16 robots", "mobile.db",
         ["movingai", "den520d", "--robots", "16", "--seed", str(a.seed), "-o", w("den520d-16.json")],
         w("den520d-16.json")),
    ]
    for _, _, args, path in scenarios:
        if not os.path.exists(path):
            run([scen] + args)
    for name, kind in (("mobile.db", "mobile"), ("arms.db", "arms")):
        if not os.path.exists(w(name)):
            print("building %s ..." % name, file=sys.stderr)
            run([db, "build", "--db", w(name), "--kind", kind, "--seed", "1"])

    rows = []
    for title, dbname, _, path in scenarios:
        scenario = json.load(open(path))
        for method in ("arc", "earc"):
            kept = Service(plan, ["--db", w(dbname), "--deterministic"])
            fresh = Service(plan, ["--db", w(dbname), "--deterministic", "--roadmap-cache-mib", "0"])
            request = {"scenario": scenario, "method": method, "seed": a.seed}
            if method == "earc":
                request["learn"] = False
            on, off, share, paths = [], [], [], None
            for i in range(a.repeats):
                print("\r%s, %s: request %d of %d" % (title, method, i + 1, a.repeats), end="", file=sys.stderr)
                x, y = kept.ask(request), fresh.ask(request)
                for answer in (x, y):
                    p = answer["solution"]["paths"]
                    if paths is None:
                        paths = p
                    elif p != paths:
                        fail("%s, %s: request %d gave other paths" % (title, method, i + 1))
                if i == 0:
                    continue
                sx, sy = x["stats"], y["stats"]
                if sx.get("roadmaps_reused", 0) != sx.get("roadmaps_built", 0):
                    fail("%s, %s: request %d built roadmaps again" % (title, method, i + 1))
                on.append(sx["planning_time_s"])
                off.append(sy["planning_time_s"])
                share.append(sy.get("roadmap_build_s", 0.0) / sy["planning_time_s"])
            print("", file=sys.stderr)
            kept.close()
            fresh.close()
            rows.append((title, method, statistics.median(on), statistics.median(off),
                         statistics.median([p / q for p, q in zip(on, off)]), statistics.median(share)))

    print("| scenario | method | kept (s) | built (s) | ratio of medians | paired | roadmaps' share |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for title, method, on, off, paired, share in rows:
        print("| %s | %s | %.4f | %.4f | %.2f | %.2f | %.0f%% |" % (title, method.upper().replace("EARC", "E-ARC"),
                                                               on, off, on / off, paired, 100 * share))
    print("\nmedians of %d requests each (the first left out), the two services taking turns" % (a.repeats - 1))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 3.6))
    short = {"32 mobile robots, 12 obstacles": "32 mobile,\nobstacles", "16 arms among obstacles": "16 arms,\nobstacles",
             "den520d, 16 robots": "den520d,\n16 robots"}
    labels = ["%s\n%s" % (short[t], m.upper().replace("EARC", "E-ARC")) for t, m, *_ in rows]
    xs = range(len(rows))
    ax.bar([x - 0.2 for x in xs], [r[3] * 1000 for r in rows], 0.4, label="roadmaps built per request")
    ax.bar([x + 0.2 for x in xs], [r[2] * 1000 for r in rows], 0.4, label="roadmaps kept (serve's default)")
    ax.set_xticks(list(xs))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("median planning time (ms)")
    ax.set_title("earc-plan serve, the same request again", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(w("serve-roadmaps.png"), dpi=120)
    print("figure: " + w("serve-roadmaps.png"))


if __name__ == "__main__":
    main()
