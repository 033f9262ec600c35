"""The module's API: what each call returns, and that every bad input raises the documented
exception (ValueError with the CLI's one-line message, TypeError for a Python value of the
wrong kind, invfree.StepFailed for a failed step) without harming the simulation."""
import gc
import pathlib
import threading
import weakref

import numpy as np
import pytest

import invfree
from conftest import check_message

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_builtin_scenes_are_the_asset_files():
    names = {p.stem for p in (ROOT / "assets" / "scenes").glob("*.toml")
             if not p.stem.startswith("stress-")}
    assert set(invfree.builtin_scenes()) == names
    assert "compress" in invfree.builtin_scenes()


def test_a_scene_from_a_name_a_file_and_text_is_the_same_scene(tmp_path):
    by_name = invfree.Simulation(scene="compress")
    text = (ROOT / "assets" / "scenes" / "compress.toml").read_text()
    path = tmp_path / "mine.toml"
    path.write_text(text)
    by_path = invfree.Simulation(scene=str(path))
    by_pathlib = invfree.Simulation(scene=path)
    by_text = invfree.Simulation(scene=text)
    round_trip = invfree.Simulation(scene=by_name.scene_toml())
    sims = [by_name, by_path, by_pathlib, by_text, round_trip]
    for s in sims:
        s.run(20)
    for s in sims[1:]:
        assert np.array_equal(s.x, by_name.x)


def test_arrays_shapes_and_copies():
    sim = invfree.Simulation(set={"mesh.n_seg": 4})
    nodes = 25
    assert sim.x.shape == (nodes, 2) and sim.x.dtype == np.float64
    assert sim.v.shape == (nodes, 2)
    assert sim.rest.shape == (nodes, 2)
    assert np.array_equal(sim.x, sim.rest)  # compress starts at rest
    tri = sim.triangles
    assert tri.shape == (32, 3) and tri.min() == 0 and tri.max() == nodes - 1
    edges = sim.boundary_edges
    assert edges.shape == (16, 2)
    assert sim.det_f().shape == (32,)
    assert np.allclose(sim.det_f(), 1.0)
    assert sim.node_mass.sum() == pytest.approx(1000.0)  # density 1000, side 1
    # A copy: changing it changes nothing, and a later step does not change it.
    x = sim.x
    x[:] = 0.0
    assert not np.array_equal(sim.x, x)
    before = sim.x
    sim.step()
    assert np.array_equal(before, sim.rest)
    assert sim.step_count == 1 and sim.time == pytest.approx(0.01)


def test_energy_split():
    sim = invfree.Simulation()
    sim.run(30)
    e = sim.energy()
    assert set(e) == {"kinetic", "elastic", "gravitational", "contact", "total"}
    assert e["total"] == pytest.approx(e["kinetic"] + e["elastic"] + e["gravitational"]
                                       + e["contact"])
    v = sim.v
    assert e["kinetic"] == pytest.approx(0.5 * np.sum(sim.node_mass[:, None] * v * v), rel=1e-12)


def test_set_as_the_sliders_do():
    sim = invfree.Simulation()
    sim.run(10)
    x = sim.x
    assert sim.set("material.model", "stable-neo-hookean") is False  # kept the state
    assert sim.scene["material"]["model"] == "stable-neo-hookean"
    assert sim.step_count == 10 and np.array_equal(sim.x, x)
    assert sim.set("time.h", 0.005) is False
    assert sim.h == 0.005
    assert sim.set("mesh.n_seg", 6) is True  # a new mesh: restarted
    assert sim.step_count == 0 and sim.x.shape == (49, 2)
    assert sim.scene["mesh"]["n_seg"] == 6
    sim.step()


@pytest.mark.parametrize("key,value", [
    ("material.nu", 0.7),
    ("mesh.n_seg", 0),
    ("mesh.nope", 1),
    ("nope.key", 1),
    ("material.model", "rubber"),
    ("time.h", -1.0),
])
def test_bad_set_raises_the_clis_message(cli_message, key, value):
    text = f'"{value}"' if isinstance(value, str) else str(value)  # a Python str is a TOML string
    expected = cli_message("simulate", "--steps", "0", "--set", f"{key}={text}")
    sim = invfree.Simulation()
    with pytest.raises(ValueError) as e:
        sim.set(key, value)
    check_message(e, expected)
    with pytest.raises(ValueError) as e:
        invfree.Simulation(set={key: value})
    check_message(e, expected)
    sim.step()  # still usable


def test_mixed_material_is_refused_as_the_cli_does(cli_message):
    expected = cli_message("simulate", "--steps", "0", "--set", "material.E=1e5",
                           "--set", "material.mu=1e4")
    with pytest.raises(ValueError) as e:
        invfree.Simulation(set={"material.E": 1e5, "material.mu": 1e4})
    check_message(e, expected)


def test_bad_scene_raises_the_clis_message(cli_message, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\n[mesh]\nn_seg = -3\n')
    for scene in ["nope", str(tmp_path / "missing.toml"), str(bad)]:
        expected = cli_message("simulate", "--steps", "0", "--scene", scene)
        with pytest.raises(ValueError) as e:
            invfree.Simulation(scene=scene)
        check_message(e, expected)
    with pytest.raises(ValueError, match="mesh.n_seg"):
        invfree.Simulation(scene='name = "x"\n[mesh]\nn_seg = -3\n')


def test_wrong_python_types_raise_type_error():
    with pytest.raises(TypeError):
        invfree.Simulation(scene=42)
    with pytest.raises(TypeError):
        invfree.Simulation(set=["mesh.n_seg", 8])
    with pytest.raises(TypeError):
        invfree.Simulation(set={1: 8})
    sim = invfree.Simulation()
    with pytest.raises(TypeError):
        sim.set("material.E", object())
    with pytest.raises(TypeError):
        sim.run(3, callback=5)
    with pytest.raises(TypeError):
        sim.inspect("3")
    assert sim.step_count == 0


def test_run_arguments_and_callback():
    sim = invfree.Simulation()
    with pytest.raises(ValueError, match="out of range"):
        sim.run(-1)
    seen = []

    def callback(s, report):
        assert s is sim
        seen.append((report.step, s.step_count, s.det_f().min()))
        return report.step < 7  # False after step 7 stops the run

    reports = sim.run(20, callback=callback)
    assert [r.step for r in reports] == list(range(1, 8))
    assert [s for s, _, _ in seen] == [c for _, c, _ in seen] == list(range(1, 8))
    assert sim.step_count == 7

    def broken(s, report):
        raise KeyError("from the callback")

    with pytest.raises(KeyError):
        sim.run(5, callback=broken)
    assert sim.step_count == 8  # the step before the callback was taken
    assert sim.run(0) == []


def test_a_failed_step_raises_step_failed_and_the_simulation_stays_usable():
    sim = invfree.Simulation(set={"time.max_newton": 1, "time.tol": 1e-9})
    x, v = sim.x, sim.v
    with pytest.raises(invfree.StepFailed) as e:
        sim.step()
    err = e.value
    assert isinstance(err, RuntimeError)
    assert err.step == 1 and err.status == "newton-failed"
    assert str(err).startswith("step 1 failed: newton-failed: ")
    assert not err.report.ok and err.report.newton_iterations == 1
    assert sim.step_count == 0 and np.array_equal(sim.x, x) and np.array_equal(sim.v, v)
    with pytest.raises(invfree.StepFailed):
        sim.run(3)
    assert sim.step_count == 0
    sim.set("time.max_newton", 100)
    sim.set("time.tol", 1e-2)
    assert sim.run(3)[-1].ok and sim.step_count == 3


def test_writing_x_is_validated_and_continues_the_run():
    a = invfree.Simulation()
    a.run(20)
    b = invfree.Simulation()
    b.run(10)
    b.x = b.x  # the same state, a rebuilt solver: the run goes on bit for bit
    b.run(10)
    assert np.array_equal(a.x, b.x)

    sim = invfree.Simulation()
    sim.run(5)
    x = sim.x
    with pytest.raises(ValueError, match=r"x: expected an array of shape \(25, 2\)"):
        sim.x = x[:-1]
    with pytest.raises(ValueError, match="finite"):
        sim.x = np.where(np.arange(50).reshape(25, 2) == 3, np.nan, x)
    below = x.copy()
    below[0, 1] = -1.5
    with pytest.raises(ValueError, match="node 0 reaches or crosses a plane"):
        sim.x = below
    flipped = x.copy()
    flipped[:, 0] *= -1.0  # a mirror image: every triangle inverted
    with pytest.raises(ValueError, match="inverted"):
        sim.x = flipped
    with pytest.raises(ValueError, match="v: expected"):
        sim.v = np.zeros(3)
    assert np.array_equal(sim.x, x) and sim.step_count == 5
    moved = x + [0.05, 0.0]
    sim.x = moved
    sim.v = np.zeros_like(x)
    assert np.array_equal(sim.x, moved) and not sim.v.any()
    sim.run(5)
    assert sim.step_count == 10 and sim.det_f().min() > 0


def test_inspect():
    sim = invfree.Simulation()
    sim.run(10)
    d = sim.inspect(3)
    assert d["triangle"] == 3 and d["model"] == "neo-hookean"
    F = d["F"]
    assert np.allclose(d["U"] @ np.diag(d["sigma"]) @ d["V"].T, F)
    assert d["J"] == pytest.approx(sim.det_f()[3], rel=1e-12)
    assert np.all(d["projected_eigenvalues"] >= 0)
    centre = sim.x[sim.triangles[3]].mean(axis=0)
    assert sim.inspect(at=tuple(centre))["triangle"] == 3
    for bad in [-1, 32, 10**12]:
        with pytest.raises(ValueError, match="out of range: the mesh has 32 triangles"):
            sim.inspect(bad)
    with pytest.raises(ValueError, match="no triangle contains"):
        sim.inspect(at=(5.0, 5.0))
    with pytest.raises(ValueError, match="finite"):
        sim.inspect(at=(float("nan"), 0.0))
    with pytest.raises(ValueError):
        sim.inspect()
    particles = invfree.Simulation(scene="course-0-free-fall")
    with pytest.raises(ValueError, match="no triangles"):
        particles.inspect(0)
    springs = invfree.Simulation(scene="course-3-contact")
    assert springs.inspect(0)["psi"] is None


def test_arrays_outlive_a_freed_simulation():
    sim = invfree.Simulation(set={"mesh.n_seg": 8})
    sim.run(5)
    arrays = [sim.x, sim.v, sim.rest, sim.triangles, sim.boundary_edges, sim.det_f(),
              sim.node_mass, sim.inspect(0)["F"]]
    copies = [a.copy() for a in arrays]
    gone = weakref.ref(sim)
    del sim
    gc.collect()
    assert gone() is None  # nothing keeps the simulation alive (no reference leak)
    for a, c in zip(arrays, copies):
        assert np.array_equal(a, c)
        a += 1  # each array owns its memory
    again = invfree.Simulation(set={"mesh.n_seg": 8})  # reuses freed memory
    again.run(5)
    assert np.array_equal(copies[0], again.x)  # the same run again


def test_the_gil_is_released_while_stepping():
    sim = invfree.Simulation(set={"mesh.n_seg": 16})
    counted = 0
    t = threading.Thread(target=sim.run, args=(40,))
    t.start()
    while t.is_alive():
        counted += 1  # runs only while the stepping thread does not hold the GIL
    t.join()
    assert sim.step_count == 40
    assert counted > 1000


def test_two_threads_step_two_simulations_as_one_thread_would():
    expected = invfree.Simulation()
    expected.run(30)
    sims = [invfree.Simulation(), invfree.Simulation()]
    threads = [threading.Thread(target=s.run, args=(30,)) for s in sims]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for s in sims:
        assert np.array_equal(s.x, expected.x)


def test_threads_setting():
    before = invfree.threads()
    with pytest.raises(ValueError):
        invfree.set_threads(-1)
    invfree.set_threads(1)
    a = invfree.Simulation(set={"mesh.n_seg": 8})
    a.run(10)
    invfree.set_threads(2)
    b = invfree.Simulation(set={"mesh.n_seg": 8})
    b.run(10)
    invfree.set_threads(before)
    assert np.array_equal(a.x, b.x)  # the core's results do not depend on threads


def test_overrides_are_validated_together_as_the_cli_does(cli, tmp_path):
    # Valid only together (the CLI validates the scene the overrides make, once).
    overrides = {"fixed.enabled": True, "fixed.corners": "top"}
    args = ["simulate", "--scene", "course-3-contact", "--steps", "5", "--obj", str(tmp_path / "o")]
    for key, value in overrides.items():
        args += ["--set", f"{key}={str(value).lower() if isinstance(value, bool) else value}"]
    code, _, err = cli(*args)
    assert code == 0, err
    sim = invfree.Simulation(scene="course-3-contact", set=overrides)
    sim.run(5)
    x = np.array([[float(a), float(b)] for a, b in
                  (line.split()[1:3] for line in open(tmp_path / "o" / "5.obj")
                   if line.startswith("v "))])
    assert np.array_equal(sim.x, x)
