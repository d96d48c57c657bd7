"""Shared by the earc module's tests: where the build and the datasets are."""
import os
import pathlib

import pytest

SRC = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def build_dir():
    """The build directory (EARC_BUILD, set by the CTest entry)."""
    build = os.environ.get("EARC_BUILD")
    if not build:
        pytest.skip("EARC_BUILD is not set")
    return pathlib.Path(build)


@pytest.fixture
def dataset():
    """A file of datasets/ by name."""
    return lambda name: SRC / "datasets" / name
