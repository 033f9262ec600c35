// The Python module `invfree` (issue 33; docs/python.md): the core driven from Python as a
// student of the course would, in a few lines:
//
//   import invfree
//   sim = invfree.Simulation(scene="compress", set={"mesh.n_seg": 8})
//   sim.run(100)
//   print(sim.x.shape, sim.det_f().min(), sim.energy())
//
// What it binds is the core's public API (core/invfree.h, energy_report.h, the scene reader);
// nothing here computes physics. Choices:
//  - sim.x and sim.v return copies (n x 2 float64, owned by the array): a step swaps the
//    state's buffers (core/simulation.cpp), so a view would silently change or dangle.
//    Assigning sim.x is supported and validated (shape, finite, the step's invariants); the
//    simulation is rebuilt around the new state, so no solver cache remembers the old one.
//  - Errors are the CLI's one-line messages: ValueError for bad input, invfree.StepFailed
//    for a failed step (the state stays the last good one), TypeError for a Python value of
//    the wrong kind. Nothing aborts the interpreter: every C++ exception becomes a Python one.
//  - The GIL is released while stepping. The core's thread pool is process-wide and not
//    reentrant, so every call into the core holds one process-wide lock, taken with the GIL
//    released (never wait for the lock while holding the GIL: no deadlock with a stepping
//    thread that needs the GIL for Ctrl-C or a callback).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "collision/intersection_check.h"
#include "energy_report.h"
#include "invfree.h"
#include "material/material.h"
#include "potential/elasticity.h"
#include "scene/boundary.h"
#include "scene/scene_fields.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace py = pybind11;

namespace invfree::python {

namespace {

// The process-wide lock around every call into the core (see the header comment).
std::mutex& core_mutex() {
  static std::mutex m;
  return m;
}

// Takes the core's lock with the GIL released, then gets the GIL back (the lock is held).
class CoreLock {
 public:
  CoreLock() {
    py::gil_scoped_release release;
    lock_ = std::unique_lock<std::mutex>(core_mutex());
  }

 private:
  std::unique_lock<std::mutex> lock_;
};

// The exception for a failed step (created in the module's init).
py::object& step_failed_type() {
  static py::object* type = new py::object();  // never destroyed: lives as long as the module
  return *type;
}

[[noreturn]] void value_error(const std::string& message) { throw py::value_error(message); }

// --- Python values as TOML text (the right-hand side of --set section.key=value) ----------

std::string toml_quoted(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

// A double that TOML reads back to the same double, always as a float ("1.0", "1e-05").
std::string toml_float(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  for (int digits = 1; digits <= 17; ++digits) {  // the shortest that round-trips
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string s = buf;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

std::string toml_value(py::handle value, const std::string& key) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) return toml_float(value.cast<double>());
  if (py::isinstance<py::str>(value)) return toml_quoted(value.cast<std::string>());
  // numpy scalars and anything else with __float__ / __index__.
  if (py::hasattr(value, "__index__"))
    return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())))
        .cast<std::string>();
  if (py::hasattr(value, "__float__")) return toml_float(py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>());
  if (py::isinstance<py::sequence>(value)) {
    std::string out = "[";
    bool first = true;
    for (py::handle item : value) {
      out += (first ? "" : ", ") + toml_value(item, key);
      first = false;
    }
    return out + "]";
  }
  throw py::type_error(key + ": a scene value is a bool, int, float, str or a list of them, not " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

// --- Scenes ---------------------------------------------------------------------------------

// A built-in name, a path to a TOML file, or TOML text (it has a newline or an '=').
SceneDef load_scene_argument(py::handle scene) {
  if (py::isinstance(scene, py::module_::import("os").attr("PathLike")))
    scene = py::module_::import("os").attr("fspath")(scene);
  if (!py::isinstance<py::str>(scene))
    throw py::type_error("scene: expected a built-in name, a TOML file's path or TOML text (str)");
  const std::string text = scene.cast<std::string>();
  const bool is_toml = text.find_first_of("\n=") != std::string::npos;
  SceneLoad load;
  {
    CoreLock lock;  // a meshed shape uses the core
    load = is_toml ? parse_scene_toml(text, "<scene text>") : load_scene(text);
  }
  if (!load.scene) value_error(load.error);
  return *load.scene;
}

// --set's overrides, checked as the command line checks them: E/nu and mu/lambda not mixed.
void apply_overrides(SceneDef& scene, const std::vector<std::pair<std::string, std::string>>& set) {
  std::string young, lame;
  for (const auto& [key, value] : set) {
    const SceneField* f = find_scene_field(key);
    if (!f || !f->input) continue;
    const bool is_young = f->input == &MaterialInput::E || f->input == &MaterialInput::nu;
    std::string& first = is_young ? young : lame;
    if (first.empty()) first = key;
  }
  if (!young.empty() && !lame.empty())
    value_error("--set " + young + " and --set " + lame +
                ": give either E and nu or mu and lambda, not both");
  // Read one by one, the scene they make validated once (scene_io's apply_overrides, as
  // the CLI's SceneOptions::resolve does), mesh.shape last.
  std::vector<std::string> ordered;
  for (const bool shape_pass : {false, true})
    for (const auto& [key, value] : set)
      if ((key == "mesh.shape") == shape_pass) ordered.push_back(key + "=" + value);
  if (std::string e = invfree::apply_overrides(scene, ordered); !e.empty()) value_error(e);
}

std::vector<std::pair<std::string, std::string>> overrides_of(py::handle set) {
  std::vector<std::pair<std::string, std::string>> out;
  if (set.is_none()) return out;
  if (!py::isinstance<py::dict>(set))
    throw py::type_error("set: expected a dict of \"section.key\": value");
  for (auto [key, value] : py::reinterpret_borrow<py::dict>(set)) {
    if (!py::isinstance<py::str>(key))
      throw py::type_error("set: keys are \"section.key\" strings");
    const std::string name = key.cast<std::string>();
    out.emplace_back(name, toml_value(value, name));
  }
  return out;
}

py::object toml_to_dict(const std::string& text) {
  return py::module_::import("tomllib").attr("loads")(text);
}

// --- Arrays -----------------------------------------------------------------------------------

// An n x 2 array copied from a 2n vector.
py::array_t<double> pairs_copy(const VecX& v) {
  const py::ssize_t n = v.size() / 2;
  py::array_t<double> out({n, py::ssize_t{2}});
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

py::array_t<double> matrix(const Mat2& m) {
  py::array_t<double> out({2, 2});
  auto r = out.mutable_unchecked<2>();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) r(i, j) = m(i, j);
  return out;
}

py::array_t<double> vector_of(const double* v, int n) {
  py::array_t<double> out(n);
  std::copy(v, v + n, out.mutable_data());
  return out;
}

// An n x 2 float64 array (anything numpy converts) as a 2n vector; ValueError names `what`.
VecX state_vector(py::handle value, int nodes, const char* what) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 2 || a.shape(0) != nodes || a.shape(1) != 2) {
    std::string shape = "?";
    if (a) {
      shape = "(";
      for (py::ssize_t d = 0; d < a.ndim(); ++d)
        shape += (d ? ", " : "") + std::to_string(a.shape(d));
      shape += a.ndim() == 1 ? ",)" : ")";
    }
    value_error(std::string(what) + ": expected an array of shape (" + std::to_string(nodes) +
                ", 2), got " + (a ? "shape " + shape : "no numeric array"));
  }
  VecX out(2 * nodes);
  std::copy(a.data(), a.data() + 2 * nodes, out.data());
  if (!out.allFinite()) value_error(std::string(what) + ": every value must be finite");
  return out;
}

// --- The step report --------------------------------------------------------------------------

struct Report {
  StepReport r;
  long step = 0;  // the step this report is of (1 = the first)
  double time = 0.0;
};

std::string failure_message(const Simulation& sim, const StepReport& r) {
  char t[32];
  std::snprintf(t, sizeof t, "%.4g", sim.time + sim.scene.h);
  return "step " + std::to_string(sim.step_count + 1) + " failed: " + step_status_name(r.status) +
         ": " + r.message + " (t = " + t + " s)";
}

// --- The simulation ---------------------------------------------------------------------------

class PySimulation {
 public:
  PySimulation(py::handle scene, py::handle set) {
    SceneDef def = load_scene_argument(scene);
    const auto overrides = overrides_of(set);
    {
      CoreLock lock;
      apply_overrides(def, overrides);
      sim_ = make_simulation(def);
    }
  }

  Report step() {
    Report out;
    {
      CoreLock lock;
      py::gil_scoped_release release;
      out.r = invfree::step(sim_);
    }
    return finish(out);
  }

  py::list run(long steps, py::object callback) {
    if (steps < 0 || steps > 100000000)
      value_error("steps " + std::to_string(steps) + " is out of range: expected 0 to 100000000");
    if (!callback.is_none() && !PyCallable_Check(callback.ptr()))
      throw py::type_error("callback: expected a callable callback(sim, report) or None");
    py::list reports;
    if (!callback.is_none()) {
      for (long k = 0; k < steps; ++k) {
        Report r = step();  // raises StepFailed
        py::object self = py::cast(this, py::return_value_policy::reference);
        py::object keep = callback(self, r);
        reports.append(r);
        if (keep.ptr() == Py_False) break;  // the callback returned False: stop
      }
      return reports;
    }
    // No callback: every step with the GIL released; the GIL is taken back every 50 ms
    // for Ctrl-C (KeyboardInterrupt between two steps, the state the last good one).
    std::vector<Report> done;
    done.reserve(static_cast<size_t>(std::min<long>(steps, 1 << 20)));
    bool failed = false, interrupted = false;
    {
      CoreLock lock;
      py::gil_scoped_release release;
      auto last_check = std::chrono::steady_clock::now();
      for (long k = 0; k < steps; ++k) {
        Report out;
        out.r = invfree::step(sim_);
        out.step = sim_.step_count + (out.r.status == StepStatus::Ok ? 0 : 1);
        out.time = sim_.time;
        done.push_back(out);
        if (out.r.status != StepStatus::Ok) {
          failed = true;
          break;
        }
        if (std::chrono::steady_clock::now() - last_check > std::chrono::milliseconds(50)) {
          last_check = std::chrono::steady_clock::now();
          py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() != 0) {
            PyErr_Clear();
            interrupted = true;
            break;
          }
        }
      }
    }
    for (size_t k = 0; k + (failed ? 1 : 0) < done.size(); ++k) reports.append(done[k]);
    if (failed) raise_step_failed(done.back());
    if (interrupted) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
    return reports;
  }

  py::array_t<double> x() {
    CoreLock lock;
    return pairs_copy(sim_.x);
  }
  py::array_t<double> v() {
    CoreLock lock;
    return pairs_copy(sim_.v);
  }

  // A new position: validated as a step's result is (finite, strictly between the planes,
  // det F > 0 where the model forbids inversion, no boundary crossing with self-contact),
  // then the simulation is rebuilt around it with the rest of the state kept.
  void set_x(py::handle value) {
    CoreLock lock;
    VecX x = state_vector(value, sim_.mesh.node_count(), "x");
    const SceneDef& s = sim_.scene;
    for (int i = 0; i < sim_.mesh.node_count(); ++i) {
      const double y = x[2 * i + 1];
      if ((s.has_ground && !(ground_gap(s, x[2 * i], y) > 0.0)) ||
          (s.has_ceiling && !(y < sim_.ceiling_y)))
        value_error("x: node " + std::to_string(i) + " reaches or crosses a plane");
    }
    if (s.has_triangle_elasticity() && !model_allows_inversion(s.model))
      for (int t = 0; t < sim_.mesh.triangle_count(); ++t)
        if (!(triangle_deformation_gradient(sim_.mesh, x.data(), t).determinant() > 0.0))
          value_error("x: triangle " + std::to_string(t) + " is inverted (det F <= 0) and " +
                      model_name(s.model) + " forbids it");
    if (s.self_contact_on() && sim_.mesh.triangle_count() > 0) {
      const Boundary boundary = find_boundary(sim_.mesh);
      BroadPhaseGrid grid;
      std::vector<std::array<int, 2>> scratch;
      if (const auto hit = find_self_intersection(boundary, x, grid, scratch)) {
        const auto& a = boundary.edges[hit->edge_a];
        const auto& b = boundary.edges[hit->edge_b];
        value_error("x: boundary edges " + std::to_string(a[0]) + "-" + std::to_string(a[1]) +
                    " and " + std::to_string(b[0]) + "-" + std::to_string(b[1]) + " intersect");
      }
    }
    Simulation next = make_simulation(s);
    next.x = std::move(x);
    next.v = sim_.v;
    next.ceiling_y = sim_.ceiling_y;
    next.ceiling_nominal = sim_.ceiling_nominal;
    next.ceiling_stiffness = sim_.ceiling_stiffness;
    next.time = sim_.time;
    next.step_count = sim_.step_count;
    next.pull = sim_.pull;
    sim_ = std::move(next);
  }

  void set_v(py::handle value) {
    CoreLock lock;
    sim_.v = state_vector(value, sim_.mesh.node_count(), "v");
  }

  py::array_t<int> triangles() {
    CoreLock lock;
    const auto& t = sim_.mesh.triangles;
    py::array_t<int> out({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
    for (size_t k = 0; k < t.size(); ++k)
      std::copy(t[k].begin(), t[k].end(), out.mutable_data() + 3 * k);
    return out;
  }

  py::array_t<int> boundary_edges() {
    CoreLock lock;
    const Boundary b = find_boundary(sim_.mesh);
    py::array_t<int> out({static_cast<py::ssize_t>(b.edges.size()), py::ssize_t{2}});
    for (size_t k = 0; k < b.edges.size(); ++k)
      std::copy(b.edges[k].begin(), b.edges[k].end(), out.mutable_data() + 2 * k);
    return out;
  }

  py::array_t<double> rest() {
    CoreLock lock;
    const auto& r = sim_.mesh.rest;
    py::array_t<double> out({static_cast<py::ssize_t>(r.size()), py::ssize_t{2}});
    for (size_t k = 0; k < r.size(); ++k) {
      out.mutable_data()[2 * k] = r[k](0);
      out.mutable_data()[2 * k + 1] = r[k](1);
    }
    return out;
  }

  py::array_t<double> node_mass() {
    CoreLock lock;
    return vector_of(sim_.node_mass.data(), static_cast<int>(sim_.node_mass.size()));
  }

  py::array_t<double> det_f() {
    CoreLock lock;
    const std::vector<double> d = triangle_det_f(sim_);
    return vector_of(d.data(), static_cast<int>(d.size()));
  }

  py::dict energy() {
    EnergyReport e;
    {
      CoreLock lock;
      e = energy_report(sim_);
    }
    py::dict d;
    d["kinetic"] = e.kinetic;
    d["elastic"] = e.elastic;
    d["gravitational"] = e.gravitational;
    d["contact"] = e.contact;
    d["total"] = e.total();
    return d;
  }

  double min_gap() {
    CoreLock lock;
    return min_plane_gap(sim_);
  }
  double min_self_gap_() {
    CoreLock lock;
    return min_self_gap(sim_);
  }
  bool self_intersecting() {
    CoreLock lock;
    if (sim_.mesh.triangle_count() == 0) return false;
    const Boundary boundary = find_boundary(sim_.mesh);
    BroadPhaseGrid grid;
    std::vector<std::array<int, 2>> scratch;
    return find_self_intersection(boundary, sim_.x, grid, scratch).has_value();
  }

  py::dict inspect(py::object triangle, py::object at) {
    CoreLock lock;
    const int count = sim_.mesh.triangle_count();
    if (count == 0)
      value_error("scene " + sim_.scene.name +
                  " has no triangles (particles and springs only): nothing to inspect");
    if (triangle.is_none() == at.is_none())
      value_error("inspect needs a triangle index or at=(x, y), not both");
    int t = 0;
    if (!triangle.is_none()) {
      if (!py::isinstance<py::int_>(triangle) && !py::hasattr(triangle, "__index__"))
        throw py::type_error("triangle: expected an int");
      const long long index = py::int_(triangle).cast<long long>();
      if (index < 0 || index >= count)
        value_error("triangle " + std::to_string(index) + " is out of range: the mesh has " +
                    std::to_string(count) + " triangles (0 to " + std::to_string(count - 1) + ")");
      t = static_cast<int>(index);
    } else {
      double p[2] = {NAN, NAN};
      try {
        const auto pair = at.cast<std::vector<double>>();
        if (pair.size() == 2) p[0] = pair[0], p[1] = pair[1];
      } catch (const py::cast_error&) {
      }
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
        value_error("at: expected (x, y), two finite numbers in m (e.g. at=(-0.1, 0.2))");
      const std::optional<int> hit = triangle_at(sim_, Vec2(p[0], p[1]));
      if (!hit) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "no triangle contains the point (%.6g, %.6g) at step %ld",
                      p[0], p[1], sim_.step_count);
        value_error(buf);
      }
      t = *hit;
    }
    const bool elastic = sim_.scene.has_triangle_elasticity();
    StressAnalysis a;
    FiniteDifferenceErrors fd;
    if (elastic) {
      a = analyze_triangle(sim_, t);
      fd = finite_difference_errors(a.model, a.F, a.lame);
    } else {
      a = analyze_stress(sim_.scene.model, triangle_deformation_gradient(sim_, t), Lame{});
    }
    const bool stress = elastic && a.finite;
    const py::object none = py::none();
    py::dict d;
    d["triangle"] = t;
    d["step"] = sim_.step_count;
    d["model"] = elastic ? std::string(model_name(a.model)) : std::string("mass-spring");
    d["mu"] = elastic ? py::object(py::float_(a.lame.mu)) : none;
    d["lambda"] = elastic ? py::object(py::float_(a.lame.lambda)) : none;
    d["F"] = matrix(a.F);
    d["U"] = matrix(a.svd.U);
    d["sigma"] = vector_of(a.svd.sigma.data(), 2);
    d["V"] = matrix(a.svd.V);
    d["J"] = a.J;
    d["psi"] = stress ? py::object(py::float_(a.psi)) : none;
    d["P"] = stress ? py::object(matrix(a.P)) : none;
    d["cauchy"] = stress ? py::object(matrix(a.cauchy)) : none;
    if (stress) {
      py::dict principal;
      principal["values"] = vector_of(a.principal_stress.data(), 2);
      const Mat2 dirs = a.principal_directions.transpose();  // rows: the directions
      principal["directions"] = matrix(dirs);
      d["principal_stress"] = principal;
    } else {
      d["principal_stress"] = none;
    }
    d["eigenvalues"] = stress ? py::object(vector_of(a.eigenvalues.data(), 4)) : none;
    d["projected_eigenvalues"] =
        stress ? py::object(vector_of(a.projected_eigenvalues.data(), 4)) : none;
    d["clamped"] = stress ? py::object(py::int_(a.clamped)) : none;
    d["fd_error_P"] = stress ? py::object(py::float_(fd.P)) : none;
    d["fd_error_dPdF"] = stress ? py::object(py::float_(fd.dPdF)) : none;
    return d;
  }

  py::object scene() {
    std::string text;
    {
      CoreLock lock;
      text = scene_to_toml(sim_.scene);
    }
    return toml_to_dict(text);
  }

  std::string scene_toml() {
    CoreLock lock;
    return scene_to_toml(sim_.scene);
  }

  // As the live window's sliders: validated, applied to the running state; a key that
  // changes the mesh rebuilds it and restarts from the initial state (returns True then).
  bool set(const std::string& key, py::handle value) {
    const std::string text = toml_value(value, key);
    CoreLock lock;
    SceneDef next = sim_.scene;
    if (std::string e = apply_override(next, key + "=" + text); !e.empty()) value_error(e);
    if (next == sim_.scene) return false;
    if (std::string e = validate_scene(next); !e.empty()) value_error("--set " + key + ": " + e);
    if (next.has_triangle_elasticity() && !model_allows_inversion(next.model) &&
        model_allows_inversion(sim_.scene.model)) {
      const std::vector<double> det = triangle_det_f(sim_);
      const auto inverted = std::count_if(det.begin(), det.end(), [](double d) { return !(d > 0); });
      if (inverted > 0)
        value_error(std::string("--set ") + key + ": " + model_name(next.model) +
                    " needs det F > 0, but " + std::to_string(inverted) +
                    " triangle(s) are inverted now");
    }
    const bool restart = needs_new_mesh(sim_.scene, next);
    update_scene(sim_, next);  // rebuilds when the mesh changes
    return restart;
  }

  Simulation& core() { return sim_; }

 private:
  Report finish(Report out) {
    out.step = sim_.step_count + (out.r.status == StepStatus::Ok ? 0 : 1);
    out.time = sim_.time;
    if (out.r.status != StepStatus::Ok) raise_step_failed(out);
    return out;
  }

  [[noreturn]] void raise_step_failed(const Report& r) {
    const std::string message = failure_message(sim_, r.r);
    py::object e = step_failed_type()(message);
    e.attr("report") = py::cast(r);
    e.attr("step") = r.step;
    e.attr("status") = std::string(step_status_name(r.r.status));
    PyErr_SetObject(step_failed_type().ptr(), e.ptr());
    throw py::error_already_set();
  }

  Simulation sim_;
};

// INVFREE_THREADS as the command line reads it (app/main.cpp): 1 to 256, or unset.
void apply_thread_variable() {
  const char* value = std::getenv("INVFREE_THREADS");
  if (value == nullptr || *value == '\0') return;
  const std::string text = value;
  const bool digits =
      text.size() <= 3 && text.find_first_not_of("0123456789") == std::string::npos;
  if (digits && std::atoi(value) >= 1 && std::atoi(value) <= 256) {
    set_thread_count(std::atoi(value));
    return;
  }
  throw py::value_error("INVFREE_THREADS=\"" + text.substr(0, 40) +
                        "\": expected a whole number from 1 to 256 (or unset it to use every core)");
}

}  // namespace

}  // namespace invfree::python

PYBIND11_MODULE(invfree, m) {
  using namespace invfree;
  using namespace invfree::python;
  m.doc() =
      "invfree: inversion-free neo-Hookean elastodynamics (lecture 9), the C++ core from Python. "
      "docs/python.md has the whole API.";

  step_failed_type() = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("invfree.StepFailed",
                                "A time step failed (Newton's cap, a failed linear solve, "
                                "non-finite values or a broken invariant). The simulation keeps "
                                "its last good state. Attributes: step, status, report.",
                                PyExc_RuntimeError, nullptr));
  m.attr("StepFailed") = step_failed_type();

  apply_thread_variable();

  py::class_<Report>(m, "StepReport",
                     "One step's report: Newton iterations, residual, energy, where the time went.")
      .def_property_readonly("status",
                             [](const Report& r) { return std::string(step_status_name(r.r.status)); })
      .def_property_readonly("ok", [](const Report& r) { return r.r.status == StepStatus::Ok; })
      .def_property_readonly("step", [](const Report& r) { return r.step; })
      .def_property_readonly("time", [](const Report& r) { return r.time; })
      .def_property_readonly("newton_iterations", [](const Report& r) { return r.r.newton_iterations; })
      .def_property_readonly("residual", [](const Report& r) { return r.r.residual; })
      .def_property_readonly("energy", [](const Report& r) { return r.r.energy; })
      .def_property_readonly("wall_ms", [](const Report& r) { return r.r.wall_ms; })
      .def_property_readonly("message", [](const Report& r) { return r.r.message; })
      .def_property_readonly("assembly_ms", [](const Report& r) { return r.r.assembly_ms; })
      .def_property_readonly("factor_ms", [](const Report& r) { return r.r.factor_ms; })
      .def_property_readonly("solve_ms", [](const Report& r) { return r.r.solve_ms; })
      .def_property_readonly("line_search_ms", [](const Report& r) { return r.r.line_search_ms; })
      .def_property_readonly("self_contact_ms", [](const Report& r) { return r.r.self_contact_ms; })
      .def_property_readonly("factorizations", [](const Report& r) { return r.r.factorizations; })
      .def_property_readonly("pcg_iterations", [](const Report& r) { return r.r.pcg_iterations; })
      .def_property_readonly("energy_evaluations",
                             [](const Report& r) { return r.r.energy_evaluations; })
      .def_property_readonly("stopped_nodes", [](const Report& r) { return r.r.stopped_nodes; })
      .def_property_readonly("expanded_steps", [](const Report& r) { return r.r.expanded_steps; })
      .def_property_readonly("penalty_doublings",
                             [](const Report& r) { return r.r.penalty_doublings; })
      .def("__repr__", [](const Report& r) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      "StepReport(step=%ld, status='%s', newton_iterations=%d, residual=%.3g, "
                      "energy=%.6g, wall_ms=%.3f)",
                      r.step, step_status_name(r.r.status), r.r.newton_iterations, r.r.residual,
                      r.r.energy, r.r.wall_ms);
        return std::string(buf);
      });

  py::class_<PySimulation>(m, "Simulation",
                           "A running simulation of a scene: Simulation(scene=\"compress\", "
                           "set={\"mesh.n_seg\": 8}).")
      .def(py::init<py::handle, py::handle>(), py::arg("scene") = "compress",
           py::arg("set") = py::none(),
           "scene: a built-in name (invfree.builtin_scenes()), a TOML file's path or TOML text; "
           "set: {\"section.key\": value} overrides, as the CLI's --set. ValueError on bad input.")
      .def("step", &PySimulation::step,
           "One time step; returns its StepReport. Raises StepFailed (the state unchanged).")
      .def("run", &PySimulation::run, py::arg("steps"), py::arg("callback") = py::none(),
           "steps time steps; returns the list of their StepReports. callback(sim, report) runs "
           "after each step; returning False stops the run. Raises StepFailed on a failed step.")
      .def_property("x", &PySimulation::x, &PySimulation::set_x,
                    "Positions, (nodes, 2) float64: a copy. Assigning one is validated (shape, "
                    "finite, between the planes, det F > 0, no crossing) and restarts the "
                    "solver at that state.")
      .def_property("v", &PySimulation::v, &PySimulation::set_v,
                    "Velocities, (nodes, 2) float64: a copy. Assigning one is validated (shape, "
                    "finite).")
      .def_property_readonly("rest", &PySimulation::rest, "Rest positions X, (nodes, 2).")
      .def_property_readonly("triangles", &PySimulation::triangles,
                             "Node indices per triangle, (triangles, 3) int32.")
      .def_property_readonly("boundary_edges", &PySimulation::boundary_edges,
                             "Boundary edges, (edges, 2) int32, each body on the left.")
      .def_property_readonly("node_mass", &PySimulation::node_mass, "Each node's mass (kg).")
      .def_property_readonly("time", [](PySimulation& s) { CoreLock l; return s.core().time; })
      .def_property_readonly("step_count",
                             [](PySimulation& s) { CoreLock l; return s.core().step_count; })
      .def_property_readonly("ceiling_y", [](PySimulation& s) -> py::object {
        CoreLock l;
        if (!s.core().scene.has_ceiling) return py::none();
        return py::float_(s.core().ceiling_y);
      }, "The ceiling's height (m), None without a ceiling.")
      .def_property_readonly("name", [](PySimulation& s) { CoreLock l; return s.core().scene.name; })
      .def_property_readonly("h", [](PySimulation& s) { CoreLock l; return s.core().scene.h; })
      .def_property_readonly("linear_solver",
                             [](PySimulation& s) { CoreLock l; return std::string(linear_solver_backend(s.core())); })
      .def("det_f", &PySimulation::det_f, "det F per triangle (area now / area at rest).")
      .def("energy", &PySimulation::energy,
           "The energy split of the current state (J): kinetic, elastic, gravitational, "
           "contact, total.")
      .def("min_gap", &PySimulation::min_gap,
           "Smallest node distance to the ground or ceiling (m); inf without planes.")
      .def("min_self_gap", &PySimulation::min_self_gap_,
           "Smallest boundary node-edge distance below dhat (m); inf when none is that close.")
      .def("self_intersecting", &PySimulation::self_intersecting,
           "Whether two boundary edges cross (the CSV's self_intersecting column).")
      .def("inspect", &PySimulation::inspect, py::arg("triangle") = py::none(), py::kw_only(),
           py::arg("at") = py::none(),
           "One triangle's F, polar SVD, psi, P, Cauchy stress and dP/dF eigenvalues (the "
           "keys of `invfree inspect --json`), by index or at=(x, y).")
      .def_property_readonly("scene", &PySimulation::scene,
                             "The scene as a dict of sections (a copy; change it with set()).")
      .def("scene_toml", &PySimulation::scene_toml, "The scene as TOML text (a scene file).")
      .def("set", &PySimulation::set, py::arg("key"), py::arg("value"),
           "Sets \"section.key\" as the live sliders do (validated; ValueError otherwise). "
           "Returns True when the change rebuilt the mesh and restarted the run.")
      .def("__repr__", [](PySimulation& s) {
        CoreLock l;
        const Simulation& c = s.core();
        return "<invfree.Simulation '" + c.scene.name + "': " +
               std::to_string(c.mesh.node_count()) + " nodes, " +
               std::to_string(c.mesh.triangle_count()) + " triangles, step " +
               std::to_string(c.step_count) + ">";
      });

  m.def(
      "builtin_scenes",
      [] {
        std::vector<std::string> names;
        for (const auto& e : builtin_scenes()) names.emplace_back(e.name);
        return names;
      },
      "The built-in scenes' names.");
  m.def(
      "set_threads",
      [](int n) {
        if (n < 0 || n > 256)
          throw py::value_error("threads " + std::to_string(n) +
                                ": expected a whole number from 1 to 256 (0: every core)");
        CoreLock lock;
        set_thread_count(n);
      },
      py::arg("n"), "The core's worker threads (0: one per core). Results do not depend on it.");
  m.def("threads", [] { return thread_count(); }, "The core's worker threads.");
}
