"""pytest setup for the Python module's tests (tests/python/CMakeLists.txt runs them).

The module is found through PYTHONPATH (ctest sets it to the build's python/ folder), the
command line through INVFREE_EXE; run by hand:
    PYTHONPATH=build/release/python INVFREE_EXE=build/release/app/invfree \\
        python3 -m pytest tests/python
"""
import os
import shutil
import subprocess

import matplotlib
import pytest

matplotlib.use("Agg")


@pytest.fixture(scope="session")
def invfree_exe():
    exe = os.environ.get("INVFREE_EXE") or shutil.which("invfree")
    if not exe or not os.path.exists(exe):
        pytest.fail("INVFREE_EXE must name the invfree program (the CLI) for this test")
    return exe


@pytest.fixture(scope="session")
def cli(invfree_exe):
    """Runs the CLI; returns (exit code, stdout, stderr)."""

    def run(*args):
        p = subprocess.run([invfree_exe, *args], capture_output=True, text=True, timeout=120)
        return p.returncode, p.stdout, p.stderr

    return run


def cli_error(stderr):
    """The CLI's one-line message: stderr's last line without the "invfree: " prefix."""
    line = stderr.strip().splitlines()[-1]
    assert line.startswith("invfree: "), stderr
    return line[len("invfree: "):]
