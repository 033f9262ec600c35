"""The examples of examples/python/ run as a student runs them (matplotlib's Agg backend),
each writing its chart; their printed results are checked."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


def run_example(name, tmp_path, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    out = tmp_path / (name + ".png")
    p = subprocess.run([sys.executable, str(EXAMPLES / (name + ".py")), str(out), *args],
                       capture_output=True, text=True, cwd=tmp_path, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000  # a chart, not an empty image
    return p.stdout


def test_lecture_demo(tmp_path):
    out = run_example("lecture_demo", tmp_path, "300")
    m = re.search(r"compress: 300 steps, t = 3.00 s, min det F over the run ([0-9.]+)", out)
    assert m, out
    assert 0.0 < float(m.group(1)) < 0.9  # squashed, never inverted


def test_student_step_matches_invfree(tmp_path):
    out = run_example("student_step", tmp_path, "80")
    m = re.search(r"80 steps: the student's step and invfree's differ by at most (\S+) m "
                  r"\(lowest y over the run (\S+) m", out)
    assert m, out
    assert float(m.group(1)) < 1e-6
    assert float(m.group(2)) < -0.99  # the square reached the ground's barrier


def test_sweep_mu(tmp_path):
    out = run_example("sweep_mu", tmp_path, "200")
    lowest = [float(v) for v in re.findall(r"mu \S+ Pa: min det F ([0-9.]+)", out)]
    assert len(lowest) == 5, out
    assert all(0.0 < d < 1.0 for d in lowest)
    # lambda kept: a larger mu lowers the Poisson ratio, so the squashed square keeps less
    # of its area (a smaller mu is nearer incompressible)
    assert lowest == sorted(lowest, reverse=True)
