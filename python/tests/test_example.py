"""python/examples/plot_plan.py plots a plan."""
import os
import pathlib
import subprocess
import sys

import pytest

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "plot_plan.py"


def test_plot_plan_writes_an_image(dataset, tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "plan.png"
    done = subprocess.run([sys.executable, str(EXAMPLE), str(dataset("mobile-obst-16-s1.json")), str(out),
                           "--seed", "2"], capture_output=True, text=True, env=dict(os.environ), check=True)
    assert out.stat().st_size > 10000
    assert "16 robots" in done.stdout
