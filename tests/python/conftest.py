"""Shared by the Python module's tests: the command line beside the module (SMITHLAB_EXE, set by ctest)."""
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs `smithlab ARGS...` and returns its stdout (the run must succeed)."""
    exe = os.environ.get("SMITHLAB_EXE")
    if not exe:
        pytest.skip("SMITHLAB_EXE is not set (ctest sets it)")

    def run(*args):
        return subprocess.run([exe, *args], check=True, capture_output=True, text=True).stdout

    return run
