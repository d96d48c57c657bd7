"""earc.load_scenario, earc.plan and earc.validate."""
import json
import subprocess
import threading
import time

import numpy as np
import pytest

import earc


def test_load_scenario_from_file_and_dict(dataset):
    from_file = earc.load_scenario(dataset("mobile-4-s1.json"))
    from_dict = earc.load_scenario(json.loads(dataset("mobile-4-s1.json").read_text()))
    assert len(from_file.robots) == 4
    assert from_file.to_dict() == from_dict.to_dict()


def test_plan_gives_numpy_paths_and_stats(dataset):
    s = earc.load_scenario(dataset("mobile-4-s1.json"))
    r = earc.plan(s, "arc", seed=2, time_limit=30)
    assert r.success and r.failures == []
    assert len(r.paths) == 4
    for times, q in r.paths:
        assert isinstance(q, np.ndarray) and q.dtype == np.float64
        assert q.ndim == 2 and q.shape[1] == 3 and q.shape[0] == len(times)
        assert list(times) == list(range(len(times)))
    assert r.stats["method"] == "arc" and r.stats["seed"] == 2
    assert r.stats["makespan"] == max(len(t) for t, _ in r.paths) - 1


def test_same_seed_same_paths_as_earc_plan(dataset, build_dir, tmp_path):
    scenario = dataset("mobile-obst-16-s1.json")
    out = tmp_path / "sol.json"
    subprocess.run([str(build_dir / "earc-plan"), "plan", str(scenario), "-o", str(out), "--seed", "3",
                    "--deterministic", "--refine", "0.5", "-q"], check=True)
    cli = json.loads(out.read_text())
    r = earc.plan(earc.load_scenario(scenario), "arc", seed=3, deterministic=True, refine=0.5)
    assert r.success
    # Refinement runs by the clock: compare the first plan's figures and,
    # for the paths, a plan without it.
    assert r.stats["refine"]["first_sum_of_costs"] == cli["stats"]["refine"]["first_sum_of_costs"]
    subprocess.run([str(build_dir / "earc-plan"), "plan", str(scenario), "-o", str(out), "--seed", "3",
                    "--deterministic", "-q"], check=True)
    cli = json.loads(out.read_text())
    r = earc.plan(earc.load_scenario(scenario), seed=3, deterministic=True)
    assert r.to_dict()["paths"] == cli["paths"]
    for (_, q), p in zip(r.paths, cli["paths"]):
        assert np.array_equal(q, np.array(p["states"]))


def test_validate_result_dict_and_file(dataset, tmp_path):
    s = earc.load_scenario(dataset("mobile-4-s1.json"))
    r = earc.plan(s, "prioritized", seed=1)
    assert earc.validate(s, r).valid
    sol = r.to_dict()
    r.save(tmp_path / "sol.json")
    assert earc.validate(s, tmp_path / "sol.json").valid
    # Robot 0 jumps to robot 1's goal at its last step: no longer its goal.
    sol["paths"][0]["states"][-1] = sol["paths"][1]["states"][-1]
    report = earc.validate(s, sol)
    assert not report.valid
    assert report.violations and report.violations[0]["type"] in ("goal", "Goal", "robot_robot", "resolution")


def test_bad_input_is_one_line_input_error(dataset):
    doc = json.loads(dataset("mobile-4-s1.json").read_text())
    doc["robots"] = 3
    with pytest.raises(earc.InputError, match=r"^scenario: \$\.robots: ") as e:
        earc.load_scenario(doc)
    assert "\n" not in str(e.value)
    assert issubclass(earc.InputError, ValueError)
    s = earc.load_scenario(dataset("mobile-4-s1.json"))
    with pytest.raises(earc.InputError, match="method: unknown method 'fast'"):
        earc.plan(s, "fast")
    with pytest.raises(earc.InputError, match="db: is for methods earc and lightning"):
        earc.plan(s, "prioritized", db="x.sqlite")
    with pytest.raises(earc.InputError, match="db_k: is for method earc"):
        earc.plan(s, "arc", db_k=3)
    with pytest.raises(earc.InputError, match="db: method earc needs an experience database"):
        earc.plan(s, "earc")
    with pytest.raises(earc.InputError, match="nothing.json"):
        earc.load_scenario("/nonexistent/nothing.json")


def test_plan_releases_the_gil(dataset):
    s = earc.load_scenario(dataset("mobile-obst-32-s1.json"))
    done = threading.Event()
    planner = threading.Thread(target=lambda: (earc.plan(s, "prioritized", seed=1), done.set()))
    start = time.monotonic()
    planner.start()
    ticks = 0
    while not done.is_set() and time.monotonic() - start < 120:
        ticks += 1
        time.sleep(0.001)
    planner.join()
    elapsed = time.monotonic() - start
    # Holding the GIL the planner would leave the loop a tick or two.
    assert elapsed < 0.05 or ticks >= 10
