"""Shared helpers of the module's tests: the build's programs and a small scene."""
import os
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD = os.environ.get("SHADOWLAB_BUILD", os.path.join(ROOT, "build"))


def program(name):
    return os.path.join(BUILD, "programs", name)


def run(name, *args, ok=True):
    """Runs build/programs/NAME; returns (exit code, stdout, stderr)."""
    p = subprocess.run([program(name), *args], cwd=ROOT, capture_output=True, text=True,
                       env={**os.environ, "SHADOWLAB_THREADS": "2"})
    if ok and p.returncode != 0:
        raise AssertionError(f"{name} {' '.join(args)} exited {p.returncode}: {p.stderr}")
    return p.returncode, p.stdout, p.stderr


@pytest.fixture(scope="session")
def sl():
    import shadowlab
    shadowlab.set_threads(2)
    return shadowlab
