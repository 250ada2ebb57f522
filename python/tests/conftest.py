"""What the tests share: the `knotlab` command line to compare with (``KNOTLAB_CLI``, else the
repository's own build under target/), and a short learned skill."""

import os
import pathlib

import pytest

import knotlab

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> str:
    """The `knotlab` binary: ``KNOTLAB_CLI``, else target/debug/knotlab or target/release/knotlab of
    this repository (scripts/test builds the first). A test that compares with it fails without one."""
    given = os.environ.get("KNOTLAB_CLI")
    candidates = [pathlib.Path(given)] if given else [REPO / "target/debug/knotlab", REPO / "target/release/knotlab"]
    for path in candidates:
        if path.is_file() and os.access(path, os.X_OK):
            return str(path)
    pytest.fail(f"no knotlab binary at {[str(c) for c in candidates]}: build it (cargo build) or set KNOTLAB_CLI")


@pytest.fixture(scope="session")
def skill() -> knotlab.Skill:
    """The shipped demonstration learned with the shipped pattern."""
    return knotlab.learn()
