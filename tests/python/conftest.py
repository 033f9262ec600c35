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
    no_cli = os.environ.get("INVFREE_NO_CLI")
    if no_cli:
        pytest.skip(no_cli)  # the sanitizer build: tests/python/CMakeLists.txt says why
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


@pytest.fixture(scope="session")
def cli_message():
    """The CLI's one-line error for the arguments (it must exit 2), for comparison with the
    module's exception; None where the command line is not built (the sanitizer build): the
    module's error paths still run there, under ASan, and check_message then asks only for
    one non-empty line."""
    exe = None if os.environ.get("INVFREE_NO_CLI") else (
        os.environ.get("INVFREE_EXE") or shutil.which("invfree"))
    if not os.environ.get("INVFREE_NO_CLI") and (not exe or not os.path.exists(exe)):
        pytest.fail("INVFREE_EXE must name the invfree program (the CLI) for this test")

    def run(*args):
        if exe is None:
            return None
        p = subprocess.run([exe, *args], capture_output=True, text=True, timeout=120)
        assert p.returncode == 2, p.stderr
        return cli_error(p.stderr)

    return run


def check_message(error, expected):
    """The exception's text is the CLI's message (or, without the CLI, one line)."""
    text = str(error.value)
    if expected is None:
        assert text and "\n" not in text, text
    else:
        assert text == expected
