"""Shared fixtures of the package's tests: the command-line binary the results are compared
with ($CUTICLE_BIN, as scripts/test sets it), and a runner for it."""

import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cuticle_bin():
    path = os.environ.get("CUTICLE_BIN")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("set CUTICLE_BIN to the release binary (scripts/test does)")
    return path


@pytest.fixture
def run_cli(cuticle_bin):
    """Runs `cuticle ARGS...`, failing the test with its stderr when it fails."""

    def run(*args):
        done = subprocess.run(
            [cuticle_bin, *map(str, args)], capture_output=True, text=True, timeout=120
        )
        assert done.returncode == 0, done.stderr
        return done

    return run
