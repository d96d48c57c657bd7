#!/usr/bin/python3
"""Writes the hand-designed validator fixtures in tests/data/.

Each case is chosen to exercise one rule of shared/spec/formats.md; the
paths are spelled out here (waypoints and step counts) rather than typed
into JSON by hand. Re-run after editing a case:

    python3 tests/data/make_fixtures.py

Naming: scenarios/NAME.json is a scenario; solutions/NAME__CASE.json is a
solution of scenarios/NAME.json; bad/ holds files that are not valid input
(bad/NAME.json a bad scenario, bad/NAME__CASE.json a bad solution of
scenarios/NAME.json). tests/cli/validate_agrees_with_checker.sh pairs them
by these names. The expected verdict of each solution is in its
stats.expect ("stats" is free-form; a key of its own at the top would be
an unknown key, which readers ignore but warn of).
"""

import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
PI = math.pi


def write(rel, doc):
    path = os.path.join(HERE, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def write_text(rel, text):
    path = os.path.join(HERE, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def lerp(a, b, s):
    return [x + s * (y - x) for x, y in zip(a, b)]


def segment(a, b, steps):
    """States after a on the straight motion a -> b in `steps` steps."""
    return [lerp(a, b, k / steps) for k in range(1, steps + 1)]


def through(start, legs):
    """A path from start through (waypoint, steps) legs."""
    states = [list(start)]
    for goal, steps in legs:
        states += segment(states[-1], goal, steps)
    return states


def solution(scenario, paths, expect, solved=True, **extra):
    doc = {"format": "earc.solution.v1", "scenario": scenario, "method": "hand-made",
           "solved": solved, "paths": [{"robot": n, "states": s} for n, s in paths],
           "stats": {"planning_time_s": 0.0, "expect": expect}}
    doc["stats"].update(extra.pop("stats", {}))
    doc.update(extra)
    return doc


def disc(name, r, start, goal):
    return {"name": name, "type": "mobile", "shape": {"type": "disc", "radius": r},
            "start": start, "goal": goal}


def scenario(name, robots, obstacles=(), resolution=None, size=10):
    doc = {"format": "earc.scenario.v1", "name": name,
           "workspace": {"min": [0, 0], "max": [size, size]},
           "obstacles": list(obstacles), "robots": robots}
    if resolution is not None:
        doc["resolution"] = resolution
    return doc


# -- swap-discs: two discs trade places; big steps make midpoints matter ---
SWAP = scenario("swap-discs",
                [disc("m0", 0.3, [2, 5, 0], [3, 5, 0]), disc("m1", 0.3, [3, 5, 0], [2, 5, 0])],
                resolution={"translation": 1.0, "rotation": 0.5})
write("scenarios/swap-discs.json", SWAP)
m0_ok = [[2, 5, 0], [3, 5, 0]]
m1_ok = [[3, 5, 0], [3, 6, 0], [2, 6, 0], [2, 5, 0]]
write("solutions/swap-discs__valid.json",
      solution("swap-discs", [("m0", m0_ok), ("m1", m1_ok)], "valid"))
# Apart at t = 0 and t = 1, on top of each other at t = 0.5.
write("solutions/swap-discs__midpoint-swap.json",
      solution("swap-discs", [("m0", m0_ok), ("m1", [[3, 5, 0], [2, 5, 0]])], "invalid"))
# m0 drives into m1 while it waits: contact at steps and midpoints.
write("solutions/swap-discs__head-on.json",
      solution("swap-discs", [("m0", [[2, 5, 0], [3, 5, 0], [3, 5, 0]]),
                              ("m1", [[3, 5, 0], [3, 5, 0], [2, 5, 0]])], "invalid"))
write("solutions/swap-discs__not-solved.json",
      solution("swap-discs", [], "invalid", solved=False,
               stats={"planning_time_s": 1.0, "reason": "time limit"}))
write("solutions/swap-discs__missing-path.json",
      solution("swap-discs", [("m0", m0_ok)], "invalid"))
write("solutions/swap-discs__wrong-order.json",
      solution("swap-discs", [("m1", m1_ok), ("m0", m0_ok)], "invalid"))
write("solutions/swap-discs__unknown-robot.json",
      solution("swap-discs", [("m0", m0_ok), ("m1", m1_ok), ("ghost", [[1, 2]])], "invalid"))
write("solutions/swap-discs__other-scenario.json",
      solution("other-scenario", [("m0", m0_ok), ("m1", m1_ok)], "invalid"))

# -- open-disc: one disc, a circle obstacle, heading turns by 3.1 ----------
OPEN = scenario("open-disc", [disc("d0", 0.5, [1, 1, 0], [1, 3, 3.1])],
                obstacles=[{"type": "circle", "center": [5, 5], "radius": 1.0}],
                resolution={"translation": 0.5, "rotation": 0.3})
write("scenarios/open-disc.json", OPEN)
write("solutions/open-disc__valid.json",
      solution("open-disc", [("d0", through([1, 1, 0], [([1, 3, 3.1], 11)]))], "valid"))
# Turns the other way: headings cross the +-pi seam in the stored numbers
# (-2.7 -> 3.3) and the last one is the goal's plus 2 pi.
wrap = [[1, 1 + 2 * k / 11, -0.3 * k] for k in range(10)]
wrap += [[1, 1 + 20 / 11, 3.3], [1, 3, 3.1 + 2 * PI]]
write("solutions/open-disc__heading-wrap.json", solution("open-disc", [("d0", wrap)], "valid"))
write("solutions/open-disc__resolution.json",
      solution("open-disc", [("d0", through([1, 1, 0], [([1, 1.8, 0], 1), ([1, 3, 3.1], 11)]))],
               "invalid"))
write("solutions/open-disc__wrong-goal.json",
      solution("open-disc", [("d0", through([1, 1, 0], [([1, 3.5, 3.1], 11)]))], "invalid"))
write("solutions/open-disc__wrong-start.json",
      solution("open-disc", [("d0", through([1.1, 1, 0], [([1, 3, 3.1], 11)]))], "invalid"))
write("solutions/open-disc__leaves-workspace.json",
      solution("open-disc", [("d0", through([1, 1, 0], [([0.3, 1, 0], 2), ([1, 3, 3.1], 11)]))],
               "invalid"))
write("solutions/open-disc__through-obstacle.json",
      solution("open-disc", [("d0", through([1, 1, 0], [([5, 4, 0], 10), ([1, 3, 3.1], 11)]))],
               "invalid"))

# -- box-rotation: a 2 x 0.4 box turning next to a small circle -----------
BOX = scenario("box-rotation",
               [{"name": "b0", "type": "mobile", "shape": {"type": "box", "size": [2, 0.4]},
                 "start": [5, 5, 0], "goal": [5, 5, PI / 2]}],
               obstacles=[{"type": "circle", "center": [5.8, 5.8], "radius": 0.2}],
               resolution={"translation": 0.25, "rotation": 0.2})
write("scenarios/box-rotation.json", BOX)
# Turning in place sweeps the box's corner through the circle near 45 deg.
write("solutions/box-rotation__clips-obstacle.json",
      solution("box-rotation", [("b0", through([5, 5, 0], [([5, 5, PI / 2], 8)]))], "invalid"))
write("solutions/box-rotation__valid.json",
      solution("box-rotation", [("b0", through([5, 5, 0], [([5, 3.5, 0], 6), ([5, 3.5, PI / 2], 8),
                                                           ([5, 5, PI / 2], 6)]))], "valid"))

# -- arm-fold: a 4-link arm folds its middle joints -------------------------
ARM = scenario("arm-fold",
               [{"name": "a0", "type": "manipulator", "base": [5, 5, 0], "links": [1, 1, 1, 1],
                 "link_radius": 0.1,
                 "joint_limits": [[-PI, PI], [-2.8, 2.8], [-2.8, 2.8], [-0.5, 0.5]],
                 "start": [0, 0, 0, 0], "goal": [0, 1.5, 1.5, 0]}],
               obstacles=[{"type": "box", "center": [5, 8.5], "size": [0.6, 0.4], "angle": 0.2}],
               resolution={"joint": 0.1})
write("scenarios/arm-fold.json", ARM)
A0, AG = [0, 0, 0, 0], [0, 1.5, 1.5, 0]
write("solutions/arm-fold__valid.json",
      solution("arm-fold", [("a0", through(A0, [(AG, 15)]))], "valid"))
# Folding too far: link 3 crosses link 1.
write("solutions/arm-fold__self-collision.json",
      solution("arm-fold", [("a0", through(A0, [([0, 2.6, 2.6, 0], 26), (AG, 11)]))], "invalid"))
write("solutions/arm-fold__joint-limit.json",
      solution("arm-fold", [("a0", through(A0, [([0, 0, 0, 0.7], 7), (A0, 7), (AG, 15)]))], "invalid"))
# Raising the straight arm sweeps it through the box above the base.
write("solutions/arm-fold__hits-obstacle.json",
      solution("arm-fold", [("a0", through(A0, [([PI / 2, 0, 0, 0], 16), (A0, 16), (AG, 15)]))],
               "invalid"))
write("solutions/arm-fold__resolution.json",
      solution("arm-fold", [("a0", through(A0, [(AG, 5)]))], "invalid"))

# -- bad input: each file breaks the format or the scenario rules once -----
write_text("bad/malformed.json",
           '{"format": "earc.scenario.v1",\n "workspace": {"min": [0, 0], "max": [10, 10]},\n'
           ' "robots": [\n  {"name": "m0", "type": "mobile",]\n}\n')
write_text("bad/nan.json",
           '{"format": "earc.scenario.v1", "workspace": {"min": [0, 0], "max": [10, 10]},\n'
           ' "robots": [{"name": "m0", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},\n'
           '   "start": [1, NaN, 0], "goal": [3, 3, 0]}]}\n')
write_text("bad/byte-order-mark.json", "\ufeff" + json.dumps(SWAP))
write_text("bad/comment.json", "// two discs\n" + json.dumps(SWAP))
write_text("bad/trailing-comma.json", json.dumps(SWAP, indent=1).replace("\n  }\n ]", "\n  },\n ]", 1))
write_text("bad/duplicate-key.json",
           '{"format": "earc.scenario.v1", "workspace": {"min": [0, 0], "max": [10, 10]},\n'
           ' "robots": [{"name": "m0", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},\n'
           '   "start": [1, 1, 0], "start": [2, 2, 0], "goal": [3, 3, 0]}]}\n')
bad = json.loads(json.dumps(SWAP))
bad["obstacles"] = [{"type": "box", "center": [2, 5.2], "size": [0.5, 0.5]}]
write("bad/start-in-collision.json", bad)
bad = json.loads(json.dumps(SWAP))
bad["robots"][1]["start"] = [2.5, 5, 0]
write("bad/starts-touch.json", bad)
bad = json.loads(json.dumps(SWAP))
bad["robots"][0]["goal"] = [9.9, 5, 0]
write("bad/goal-outside-workspace.json", bad)
bad = json.loads(json.dumps(ARM))
bad["robots"][0]["start"] = [0, 2.6, 2.6, 0]
write("bad/arm-start-self-collision.json", bad)
bad = json.loads(json.dumps(ARM))
bad["robots"][0]["goal"] = [0, 1.5, 1.5, 0.6]
write("bad/arm-goal-outside-limits.json", bad)
bad = json.loads(json.dumps(ARM))
bad["robots"][0]["base"] = [-0.96, 5, 0]
write("bad/arm-base-outside.json", bad)
bad = json.loads(json.dumps(SWAP))
bad["robots"][0]["shape"] = {"type": "hexagon", "radius": 0.3}
write("bad/unknown-shape.json", bad)
bad = json.loads(json.dumps(ARM))
bad["robots"][0]["joint_limits"][1] = [1.0, -1.0]
write("bad/joint-limits-lo-above-hi.json", bad)
bad = json.loads(json.dumps(SWAP))
bad["robots"][1]["name"] = "m0"
write("bad/duplicate-robot-name.json", bad)
write("bad/swap-discs__wrong-dimension.json",
      solution("swap-discs", [("m0", [[2, 5], [3, 5]]), ("m1", m1_ok)], "malformed"))
write_text("bad/swap-discs__infinite-number.json",
           '{"format": "earc.solution.v1", "scenario": "swap-discs", "solved": true,\n'
           ' "paths": [{"robot": "m0", "states": [[2, 5, 0], [3, 5, 1e999]]},\n'
           '           {"robot": "m1", "states": [[3, 5, 0], [3, 6, 0], [2, 6, 0], [2, 5, 0]]}]}\n')
write_text("bad/swap-discs__truncated.json",
           '{"format": "earc.solution.v1", "scenario": "swap-discs", "solved": true,\n'
           ' "paths": [{"robot": "m0", "states": [[2, 5, 0], [3, 5,')
write("bad/swap-discs__solved-not-bool.json",
      solution("swap-discs", [("m0", m0_ok), ("m1", m1_ok)], "malformed", solved="yes"))
