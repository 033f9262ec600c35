"""The Python module's two performance figures (issue 33), measured, never asserted:

 1. stepping through Python against the command line, compress at n_seg 64:
    `sim.run(N)` against `invfree simulate --steps N` (its stepping time: a run of N steps
    less a run of 0 steps, the same scene, so start-up, meshing and the solver's setup cancel);
    and, in the same process, `sim.run`'s wall time against the core's own time in its steps
    (the sum of the reports' wall_ms): what the binding adds per step, free of the machine's
    noise between two programs.
 2. reading `sim.x` (an (nodes, 2) copy) at n_seg 256: median and best of many reads.

    PYTHONPATH=build/release/python python3 python/bench_python.py \\
        --exe build/release/app/invfree [--steps 100] [--repeats 5]
"""
import argparse
import os
import statistics
import subprocess
import time

import invfree


def cli_seconds(exe, steps, n_seg):
    t0 = time.perf_counter()
    subprocess.run([exe, "simulate", "--scene", "compress", "--set", f"mesh.n_seg={n_seg}",
                    "--steps", str(steps)], check=True, capture_output=True)
    return time.perf_counter() - t0


def python_seconds(steps, n_seg):
    sim = invfree.Simulation(scene="compress", set={"mesh.n_seg": n_seg})
    t0 = time.perf_counter()
    reports = sim.run(steps)
    wall = time.perf_counter() - t0
    return wall, sum(r.wall_ms for r in reports) / 1000.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.environ.get("INVFREE_EXE", "build/release/app/invfree"))
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--n-seg", type=int, default=64)
    ap.add_argument("--read-n-seg", type=int, default=256)
    ap.add_argument("--reads", type=int, default=2000)
    a = ap.parse_args()
    print(f"threads {invfree.threads()}, compress at n_seg {a.n_seg}, {a.steps} steps, "
          f"{a.repeats} repeats (interleaved; medians)")

    cli_step, py_wall, py_core = [], [], []
    for _ in range(a.repeats):  # interleaved, so a busy spell on the machine hits both
        cli_step.append(cli_seconds(a.exe, a.steps, a.n_seg) - cli_seconds(a.exe, 0, a.n_seg))
        wall, core = python_seconds(a.steps, a.n_seg)
        py_wall.append(wall)
        py_core.append(core)
    c, w, k = (statistics.median(v) for v in (cli_step, py_wall, py_core))
    print(f"  simulate, stepping time:      {1000 * c / a.steps:8.3f} ms/step")
    print(f"  sim.run, wall:                {1000 * w / a.steps:8.3f} ms/step "
          f"({100 * (w / c - 1):+.2f}% against simulate)")
    overhead = [wi / ki - 1 for wi, ki in zip(py_wall, py_core)]
    print(f"  sim.run over its steps' own time: {100 * statistics.median(overhead):+.3f}% "
          f"(median; each run {', '.join(f'{100 * o:+.3f}%' for o in overhead)})")

    sim = invfree.Simulation(scene="compress", set={"mesh.n_seg": a.read_n_seg})
    nodes = sim.x.shape[0]
    times = []
    for _ in range(a.reads):
        t0 = time.perf_counter()
        x = sim.x
        times.append(time.perf_counter() - t0)
    del x
    print(f"reading sim.x at n_seg {a.read_n_seg} ({nodes} nodes, {16 * nodes / 1e6:.2f} MB): "
          f"median {1e6 * statistics.median(times):.1f} us, best {1e6 * min(times):.1f} us "
          f"over {a.reads} reads")


if __name__ == "__main__":
    main()
