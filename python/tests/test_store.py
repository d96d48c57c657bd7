"""Experience stores from Python: build, open, inspect, export, import, plan."""
import pytest

import earc


@pytest.fixture
def built(dataset, tmp_path):
    scenario = earc.load_scenario(dataset("mobile-obst-16-s1.json"))
    db = tmp_path / "exp.sqlite"
    report = earc.build_store(db, scenario, count=40, seed=5, threads=1, deterministic=True)
    return scenario, db, report


def test_build_open_inspect(built):
    _, db, report = built
    assert report["problems"] == 40 and report["inserted"] > 0
    with earc.open_store(db, read_only=True) as store:
        assert len(store) == report["inserted"]
        classes = store.classes()
        assert sum(c["entries"] for c in classes) == len(store)
        assert store.read_only
    info = earc.inspect_store(db)
    assert info["format"] == "earc.inspect.v1" and info["entries"] == report["inserted"]
    assert earc.verify_store(db)["ok"]


def test_build_is_deterministic(built, tmp_path):
    scenario, db, report = built
    again = earc.build_store(tmp_path / "again.sqlite", scenario, count=40, seed=5, threads=1, deterministic=True)
    assert again["inserted_per_class"] == report["inserted_per_class"]


def test_export_import_round_trip(built, tmp_path):
    _, db, report = built
    rows = earc.export_store(db, tmp_path / "rows.jsonl")
    assert rows == report["inserted"]
    with earc.open_store(tmp_path / "copy.sqlite") as copy:
        got = earc.import_store(copy, [str(tmp_path / "rows.jsonl")])
        assert got["inserted"] == rows and len(copy) == rows


def test_plan_earc_with_the_store(built):
    scenario, db, _ = built
    r = earc.plan(scenario, "earc", db=db, seed=1, deterministic=True, learn=False)
    assert r.success and "db_queries" in r.stats


def test_not_a_database_is_an_input_error(tmp_path):
    bad = tmp_path / "bad.sqlite"
    bad.write_text("not a database")
    with pytest.raises(earc.InputError, match="bad.sqlite"):
        earc.open_store(bad, read_only=True)
