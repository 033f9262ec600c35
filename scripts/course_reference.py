#!/usr/bin/python3
"""Reference trajectories of the course scenes from the public solid-sim-tutorial.

Runs each of the tutorial's chapters 1_mass_spring .. 5_mov_dirichlet, 7_self_contact and
8_self_friction (the scenes `stack` and `stack-friction`) as it is (its own
simulator.py, settings unchanged) with pygame replaced by a stub, Newton's tolerance set to
1e-6 instead of the scripts' 1e-2 (the only change, made by wrapping
time_integrator.step_forward), and writes the body's node positions every 10 steps over
200 steps to tests/data/course/<scene>.txt: one line per sample, "step x0 y0 x1 y1 ...".
With a tutorial that has chapter 9 (phys-sim-book/solid-sim-tutorial), also runs
9_reduced_DOF/linear.py up to its eigsh call (run_modes) and writes its 8 eigenvalues to
tests/data/course/modes-cantilever.txt; needs no matplotlib (it is stubbed: linear.py draws
only after eigsh).

Chapter 9 (9_reduced_DOF: course-9-affine, -quadratic, -cubic, -modal) runs its
simulator.py with its `method` and `order` lines set to the scene's basis (REDUCED_BASIS,
as a student edits them); for the modal scene NeoHookeanEnergy's two integer dP/dF arrays
are also made floating point (_float_stress_derivative says why). Chapter 9 needs
phys-sim-book/solid-sim-tutorial.

Chapter 0 (0_getting_started: course-0-free-fall, course-0-spring, course-0-mass-spring)
has no step_forward: run_chapter0 execs each simulatorN.py with a globals dict and records
the state from the pygame stub's event.get, which runs at the top of every loop
iteration (CHAPTER0 gives each one's steps and sampling).

Usage: scripts/course_reference.py TUTORIAL [OUT_DIR] [SCENE ...]
TUTORIAL is a checkout of github.com/liminchen/solid-sim-tutorial, or a bare git
directory of it (the files are then read with `git show HEAD:...`). Needs numpy and scipy.
Nothing of the tutorial is stored in this repository: only the numbers this script writes.
"""
import contextlib
import io
import os
import re
import subprocess
import sys
import tempfile
import types

CHAPTERS = [
    ("1_mass_spring", "course-1-mass-spring"),
    ("2_dirichlet", "course-2-dirichlet"),
    ("3_contact", "course-3-contact"),
    ("4_friction", "course-4-friction"),
    ("5_mov_dirichlet", "course-5-moving-dirichlet"),
    ("7_self_contact", "stack"),
    ("8_self_friction", "stack-friction"),
    ("9_reduced_DOF", "course-9-affine"),
    ("9_reduced_DOF", "course-9-quadratic"),
    ("9_reduced_DOF", "course-9-cubic"),
    ("9_reduced_DOF", "course-9-modal"),
]
# Chapter 9's basis, which its simulator.py sets in two lines (`method`, `order`: 1 and 1, the
# affine basis): the scene's (method, order), written into those lines before the script
# runs (_set_reduced_basis), as a student edits them. Modal: 12 modes (a count that splits no
# degenerate pair of the square's eigenvalues; docs/scenes.md).
REDUCED_BASIS = {
    "course-9-affine": (1, 1),
    "course-9-quadratic": (1, 2),
    "course-9-cubic": (1, 3),
    "course-9-modal": (2, 12),
}
STEPS = 200
EVERY = 10
TOL = 1e-6

# Chapter 0: (script, scene, samples every, steps at most, the nodes invfree has before the
# demo's). simulator0.py stops by itself where its particle reaches y = -1 (after 45 steps):
# every step is recorded until then. simulator1.py's spring hangs from the origin, invfree's
# node 0 (held by [fixed]).
CHAPTER0 = [
    ("simulator0.py", "course-0-free-fall", 1, STEPS, []),
    ("simulator1.py", "course-0-spring", EVERY, STEPS, [0.0, 0.0]),
    ("simulator2.py", "course-0-mass-spring", EVERY, STEPS, []),
]


class _Anything:
    """Stands for every pygame object and function: calls and attributes return itself."""

    def __call__(self, *args, **kwargs):
        return self

    def __getattr__(self, name):
        return self

    def __iter__(self):
        return iter(())


def _pygame_stub():
    stub = types.ModuleType("pygame")
    anything = _Anything()
    stub.init = stub.quit = anything
    stub.display = stub.draw = stub.time = anything
    stub.event = types.SimpleNamespace(get=lambda: [])
    stub.QUIT = object()
    return stub


def _chapter_files(tutorial, chapter, into):
    """Copies the chapter's .py files, its subfolders' too (7 and 8 have distance/)."""
    if os.path.isdir(os.path.join(tutorial, chapter)):
        src = os.path.join(tutorial, chapter)
        for root, _, files in os.walk(src):
            for name in files:
                if name.endswith(".py"):
                    rel = os.path.relpath(os.path.join(root, name), src)
                    os.makedirs(os.path.join(into, os.path.dirname(rel)), exist_ok=True)
                    with open(os.path.join(root, name)) as f, open(os.path.join(into, rel), "w") as g:
                        g.write(f.read())
        return
    names = subprocess.check_output(
        ["git", "--git-dir", tutorial, "ls-tree", "-r", "--name-only", "HEAD", chapter + "/"],
        text=True).split()
    for path in names:
        if path.endswith(".py"):
            rel = os.path.relpath(path, chapter)
            text = subprocess.check_output(["git", "--git-dir", tutorial, "show", "HEAD:" + path])
            os.makedirs(os.path.join(into, os.path.dirname(rel)), exist_ok=True)
            with open(os.path.join(into, rel), "wb") as g:
                g.write(text)


def _set_reduced_basis(source, method, order):
    """Chapter 9's simulator.py with its `method` and `order` lines set, as a student edits
    them (the script's own values are 1 and 1, the affine basis)."""
    lines = source.split("\n")
    for key, value in (("method", method), ("order", order)):
        hits = [k for k, line in enumerate(lines) if re.match(r"%s = \d+" % key, line)]
        if len(hits) != 1:
            raise RuntimeError("simulator.py: expected one line '%s = <n>'" % key)
        lines[hits[0]] = re.sub(r"= \d+", "= %d" % value, lines[hits[0]], count=1)
    return "\n".join(lines)


def _float_stress_derivative(work):
    """Chapter 9's NeoHookeanEnergy.d2Psi_div_dF2 fills two numpy arrays made from integer
    literals (`np.array([[0, 0, 0, 0]] * 4)`), so every entry of dP/dF it assigns is
    truncated to an integer: about 1e-4 relative at the square's mu = 7142.857. Newton only
    steers by that Hessian, so the converged steps are the same, but the modal basis is its
    eigenvectors at rest: the truncation tilts the subspace and the demo's trajectory moves by
    1.3e-5 m. For the modal scene the two arrays are made floating point (the one change
    besides the tolerance; docs/scenes.md, "Reduced bases")."""
    path = os.path.join(work, "NeoHookeanEnergy.py")
    text = open(path).read()
    for name in ("M", "dP_div_dF"):
        old = "%s = np.array([[0, 0, 0, 0]] * 4)" % name
        if text.count(old) != 1:
            raise RuntimeError("NeoHookeanEnergy.py: expected one line '%s'" % old)
        text = text.replace(old, "%s = np.array([[0.0, 0.0, 0.0, 0.0]] * 4)" % name)
    open(path, "w").write(text)


class _Done(Exception):
    pass


def run_chapter(tutorial, chapter, body_nodes_only=True, reduced_basis=None):
    samples = []
    with tempfile.TemporaryDirectory() as work:
        _chapter_files(tutorial, chapter, work)
        if reduced_basis is not None and reduced_basis[0] == 2:
            _float_stress_derivative(work)
        old_path, old_cwd = list(sys.path), os.getcwd()
        sys.path.insert(0, work)
        os.chdir(work)
        for name in ["square_mesh", "time_integrator", "utils", "InertiaEnergy", "MassSpringEnergy",
                     "GravityEnergy", "BarrierEnergy", "FrictionEnergy", "SpringEnergy",
                     "NeoHookeanEnergy"]:
            sys.modules.pop(name, None)
        for name in [m for m in sys.modules if m == "distance" or m.startswith("distance.")]:
            sys.modules.pop(name)
        sys.modules["pygame"] = _pygame_stub()
        try:
            import time_integrator


            original = time_integrator.step_forward
            state = {"step": 0}

            def record(x, n_body):
                samples.append((state["step"], [float(c) for p in x[:n_body] for c in p]))

            def step_forward(x, e, *args):
                n_body = max(max(edge) for edge in e) + 1  # the ceiling node is not in e
                if state["step"] == 0:
                    record(x, n_body)
                args = list(args)
                args[-1] = TOL  # the last argument of every chapter's step_forward is tol
                result = original(x, e, *args)
                state["step"] += 1
                if state["step"] % EVERY == 0:
                    record(result[0], n_body)
                if state["step"] == STEPS:
                    raise _Done()
                return result

            time_integrator.step_forward = step_forward
            with contextlib.redirect_stdout(io.StringIO()):
                try:
                    source = open("simulator.py").read()
                    if reduced_basis is not None:
                        source = _set_reduced_basis(source, *reduced_basis)
                    exec(compile(source, "simulator.py", "exec"),
                         {"__name__": "__main__"})
                except _Done:
                    pass
        finally:
            sys.path[:] = old_path
            os.chdir(old_cwd)
    return samples


# The course's chapter 9 linear modal analysis (9_reduced_DOF/linear.py, in
# phys-sim-book/solid-sim-tutorial only): the scene `modes-cantilever`.
MODES_SCRIPT = ("9_reduced_DOF", "linear.py")
MODES_SCENE = "modes-cantilever"


def _anything_module(name):
    module = types.ModuleType(name)
    module.__getattr__ = lambda attribute: _Anything()
    return module


def run_modes(tutorial):
    """Runs linear.py as it is (its settings unchanged) up to its eigsh call and returns the
    eigenvalues it computes, ascending. matplotlib is replaced by a stub (linear.py draws
    only after eigsh) and eigsh by a wrapper that records the result and stops the script,
    so that no GIF is made; both are restored afterwards."""
    import scipy.sparse.linalg

    chapter, script = MODES_SCRIPT
    stubbed = ["matplotlib", "matplotlib.pyplot", "matplotlib.tri", "matplotlib.animation"]
    saved = {name: sys.modules.get(name) for name in stubbed}
    original = scipy.sparse.linalg.eigsh
    result = {}

    def eigsh(*args, **kwargs):
        result["values"] = original(*args, **kwargs)[0]
        raise _Done()

    with tempfile.TemporaryDirectory() as work:
        _chapter_files(tutorial, chapter, work)
        old_cwd = os.getcwd()
        os.chdir(work)
        try:
            for name in stubbed:
                sys.modules[name] = _anything_module(name)
            scipy.sparse.linalg.eigsh = eigsh
            with contextlib.redirect_stdout(io.StringIO()):
                try:
                    exec(compile(open(script).read(), script, "exec"), {"__name__": "__main__"})
                except _Done:
                    pass
        finally:
            scipy.sparse.linalg.eigsh = original
            for name, module in saved.items():
                if module is None:
                    sys.modules.pop(name, None)
                else:
                    sys.modules[name] = module
            os.chdir(old_cwd)
    if "values" not in result:
        raise RuntimeError("%s/%s did not call eigsh" % MODES_SCRIPT)
    return sorted(float(v) for v in result["values"])


def _has_chapter(tutorial, chapter):
    """Whether the tutorial has this chapter (the older liminchen/solid-sim-tutorial stops
    at chapter 8)."""
    if os.path.isdir(tutorial):
        if os.path.isdir(os.path.join(tutorial, chapter)):
            return True
        if not os.path.exists(os.path.join(tutorial, "HEAD")):
            return False
    return subprocess.run(["git", "--git-dir", tutorial, "cat-file", "-e", "HEAD:" + chapter],
                          stderr=subprocess.DEVNULL).returncode == 0


def write_modes(tutorial, out_dir):
    values = run_modes(tutorial)
    path = os.path.join(out_dir, MODES_SCENE + ".txt")
    with open(path, "w") as f:
        f.write("# %s/%s of solid-sim-tutorial: eigsh(K, M, sigma=0), the %d smallest "
                "eigenvalues (1/s^2), ascending; made by scripts/course_reference.py\n"
                % (MODES_SCRIPT + (len(values),)))
        for v in values:
            f.write("%.17g\n" % v)
    print("%s: %d eigenvalues -> %s" % (MODES_SCENE, len(values), path))


def run_chapter0(tutorial, script, every, steps, fixed_nodes):
    """Runs 0_getting_started/<script> and returns [(step, [x0, y0, ...])], recorded at the
    top of every loop iteration (the stub's pygame.event.get) while time_step % every == 0,
    up to `steps` steps or the script's own stop (simulator0.py's input() at the ground)."""
    samples = []
    with tempfile.TemporaryDirectory() as work:
        _chapter_files(tutorial, "0_getting_started", work)
        old_path, old_cwd = list(sys.path), os.getcwd()
        sys.path.insert(0, work)
        os.chdir(work)
        sys.modules.pop("square_mesh", None)
        scope = {"__name__": "__main__"}

        def record():
            step = scope["time_step"]
            if step % every == 0:
                x = scope["x"]
                xs = [float(c) for c in (x.reshape(-1) if hasattr(x, "reshape") else x)]
                samples.append((step, fixed_nodes + xs))
            if step >= steps:
                raise _Done()
            return []

        def stop(*args):  # simulator0.py waits for a key once the particle is down
            raise _Done()

        stub = _pygame_stub()
        stub.event = types.SimpleNamespace(get=record)
        sys.modules["pygame"] = stub
        scope["input"] = stop
        try:
            with contextlib.redirect_stdout(io.StringIO()):
                try:
                    exec(compile(open(script).read(), script, "exec"), scope)
                except _Done:
                    pass
        finally:
            sys.path[:] = old_path
            os.chdir(old_cwd)
    return samples


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    tutorial = os.path.abspath(sys.argv[1])
    out_dir = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "course")
    os.makedirs(out_dir, exist_ok=True)
    only = sys.argv[3:] if len(sys.argv) > 3 else None
    for script, scene, every, steps, fixed_nodes in CHAPTER0:
        if only and scene not in only:
            continue
        samples = run_chapter0(tutorial, script, every, steps, fixed_nodes)
        path = os.path.join(out_dir, scene + ".txt")
        with open(path, "w") as f:
            f.write("# 0_getting_started/%s of solid-sim-tutorial (explicit), node positions (m) "
                    "every %d step(s) to step %d; made by scripts/course_reference.py\n"
                    % (script, every, samples[-1][0]))
            for step, xs in samples:
                f.write("%d %s\n" % (step, " ".join("%.17g" % v for v in xs)))
        print("%s: %d samples of %d nodes -> %s" % (scene, len(samples), len(samples[0][1]) // 2, path))
    for chapter, scene in CHAPTERS:
        if only and scene not in only:
            continue
        samples = run_chapter(tutorial, chapter, reduced_basis=REDUCED_BASIS.get(scene))
        path = os.path.join(out_dir, scene + ".txt")
        with open(path, "w") as f:
            basis = REDUCED_BASIS.get(scene)
            if basis:
                chapter += " (method = %d, order = %d%s)" % (
                    basis + ("; NeoHookeanEnergy's dP/dF arrays floating point" if basis[0] == 2 else "",))
            f.write("# %s of solid-sim-tutorial, tol %g, node positions (m) every %d steps; "
                    "made by scripts/course_reference.py\n" % (chapter, TOL, EVERY))
            for step, xs in samples:
                f.write("%d %s\n" % (step, " ".join("%.12g" % v for v in xs)))
        print("%s: %d samples of %d nodes -> %s" % (scene, len(samples), len(samples[0][1]) // 2, path))
    if (not only or MODES_SCENE in only) and _has_chapter(tutorial, MODES_SCRIPT[0]):
        write_modes(tutorial, out_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
