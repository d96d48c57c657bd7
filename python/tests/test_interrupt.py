"""Ctrl-C during earc.plan: the plan stops and KeyboardInterrupt is raised."""
import os
import signal
import threading
import time

import pytest

import earc


def test_sigint_stops_a_long_plan(dataset):
    # The coupled baseline on 32 robots runs to its limit: far longer than
    # the signal's delay, so the interrupt is all that can end it early.
    s = earc.load_scenario(dataset("mobile-obst-32-s1.json"))
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            earc.plan(s, "coupled", seed=1, time_limit=120)
    finally:
        timer.cancel()
    elapsed = time.monotonic() - start
    assert 0.9 <= elapsed < 5.0, elapsed
    # The module plans normally afterwards (nothing left stopped).
    r = earc.plan(earc.load_scenario(dataset("mobile-4-s1.json")), "prioritized", seed=1)
    assert r.success
