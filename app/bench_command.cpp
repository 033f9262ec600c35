// `invfree bench`: the scaling curve. Runs a scene at each mesh size and writes
//   DIR/bench.csv  one row per size: n_seg, nodes, triangles, unknowns, steps, mean and
//                  median ms per step, Newton iterations per step, and where the time went
//                  (assembly, factorisation, solve, line search, other; mean ms per step),
//                  PCG iterations and factorisations per step, the linear solver used,
//                  and mesh_ms: the time to mesh the scene's bodies at that n_seg, cold;
//                  then threads, speedup and efficiency (one row per size and thread count),
//                  max_ms and max_step (the slowest step), and paired_speedup
//   DIR/bench.png  log-log chart of ms per step against degrees of freedom, with the
//                  least-squares slope (fitted over n_seg >= 32 when two such sizes ran)
// and a table on stdout. A scene with a reduced basis ([reduced]) also runs its full model on
// each mesh (the same scene with basis "full"): its median ms per step and Newton iterations
// per step are the columns full_median_ms and full_newton_per_step (empty otherwise), the
// table says how many times faster the reduced run is, and the chart draws the full model's
// curve. `--fps F` then finds, by bisection on n_seg, the largest mesh whose median step
// still fits in a frame of 1/F s (one step per frame: the live mode's
// n_seg slider). Times come from the step report's steady-clock split (core/simulation.h).
//
// `--threads 1,2,4` runs every size at every thread count (ascending; the core's
// set_thread_count, core/linalg/parallel.h), the counts' runs taking turns of 10 steps so
// that a drift in the machine's speed affects them alike, one row each: the speed-up of the
// median step against the smallest count, the parallel efficiency (speed-up / thread ratio),
// the paired speed-up (the median over the turns of the turns' time ratio), and
// whether every step's positions were bit-identical across the counts (the core's pool
// promises it). The chart then draws one line per thread count and a speed-up panel.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli_checks.h"
#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/format_number.h"
#include "app/interrupt.h"
#include "app/output_files.h"
#include "app/plot/chart.h"
#include "app/plot/loglog_fit.h"
#include "app/scene_options.h"
#include "app/sweep_command.h"
#include "linalg/parallel.h"
#include "scene/scene_mesh.h"
#include "scene_io/builtin_scenes.h"
#include "shape/shape_mesh.h"
#include "shape/shape_region.h"
#include "shape/triangulate.h"
#include "simulation.h"
#include "solver/step_workspace.h"

namespace invfree {

namespace {

struct BenchOptions {
  SceneOptions scene;
  std::string sizes = "4,8,16,32,64,128,256";
  int steps = 300;
  std::string out_dir = "bench";
  std::string threads;  // a list, e.g. "1,2,4", when threads_given
  bool threads_given = false;  // else every core (or INVFREE_THREADS)
  double fps = 0.0;
  ChartFormat format = ChartFormat::Png;
  bool force = false;
};

struct BenchRow {
  int n_seg = 0, nodes = 0, triangles = 0, dofs = 0, steps = 0;
  double mean_ms = 0, median_ms = 0, newton = 0;
  // The slowest step (ms, 1-based step): what a viewer sees as a stall, against the median.
  double max_ms = 0;
  int max_step = 0;
  // The step that took the most Newton iterations (1-based) and how many: how close the
  // run came to Newton's iteration cap (at n_seg 256, the fold steps near step 250).
  int newton_worst = 0, newton_worst_step = 0;
  double assembly = 0, factor = 0, solve = 0, line_search = 0, other = 0;
  double pcg = 0, factorizations = 0;
  double self_contact = 0;  // of the split above (mean ms per step)
  double mesh_ms = 0;       // meshing every body once, cold (cold_mesh_ms)
  std::string solver;
  // A reduced scene's full model on the same mesh (median ms, Newton per step); 0: none.
  double full_median_ms = 0, full_newton = 0;
  // The thread count the row ran at; the median step's speed-up against the smallest count
  // listed at the same size, and that over the thread ratio (1 and 1 for that count).
  int threads = 0;
  double speedup = 1.0, efficiency = 1.0;
  // The median over the turns (run_bench) of the smallest count's time for the turn's steps
  // over this count's: each ratio compares two turns a second or so apart, so a burst of
  // load on the machine spoils only its own turns (1 for the smallest count).
  double paired_speedup = 1.0;
  // A hash of the positions (x and the ceiling's height) after every step that ran.
  std::vector<std::uint64_t> step_hashes;
};

// The bits of the state's positions after a step: x (2N) and the ceiling's height, mixed
// word by word (states that differ in any bit of any coordinate almost surely hash apart).
std::uint64_t positions_hash(const Simulation& sim) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  auto mix = [&h](double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    h ^= bits + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 0xff51afd7ed558ccdull;
  };
  for (Eigen::Index i = 0; i < sim.x.size(); ++i) mix(sim.x[i]);
  mix(sim.ceiling_y);
  return h;
}

// The wall-clock ms to mesh every body of `scene` from its keys, as a scene's first load
// does: a square's grid, a meshed shape's region and CGAL's refinement. mesh_shape caches
// its last results (and validate_scene has just filled that cache), so a meshed shape goes
// to shape_region and triangulate_region directly, the work mesh_shape does on a miss; a
// mesh file is only checked and copied (mesh_shape). The square's grid and the mesh file
// are not cached.
double cold_mesh_ms(const SceneDef& scene) {
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < body_count(scene); ++k) {
    const PlacedBody b = placed_body(scene, k);
    if (b.shape.kind == ShapeKind::Square || b.shape.kind == ShapeKind::MeshFile) {
      (void)body_mesh(b);
      continue;
    }
    const double max_edge = shape_max_edge(b.shape, b.n_seg);
    const ShapeRegion region = shape_region(b.shape, max_edge);
    // The scene was validated: the step budget only has to let the refinement end.
    (void)triangulate_region(region.loops, max_edge, 100 * kMaxShapeTriangles);
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// "4,8,16" -> {4, 8, 16}; "" on success, else the reason.
std::string parse_sizes(const std::string& text, std::vector<int>& sizes) {
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    long v = 0;
    try {
      v = std::stol(item, &used);
    } catch (...) {
      used = 0;
    }
    if (item.empty() || used != item.size() || v < 1 || v > kMaxSegments)
      return "--sizes: \"" + item + "\" is not an n_seg between 1 and " +
             std::to_string(kMaxSegments);
    sizes.push_back(static_cast<int>(v));
  }
  if (sizes.empty()) return "--sizes: expected a comma-separated list of n_seg, e.g. 4,8,16";
  return "";
}

// "1,2,4" -> {1, 2, 4} (sorted ascending); "" on success, else the reason. Every count is a
// whole number from 1 to 256 (as INVFREE_THREADS), each listed once.
std::string parse_threads(const std::string& text, std::vector<int>& counts) {
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const bool digits = !item.empty() && item.size() <= 3 &&
                        item.find_first_not_of("0123456789") == std::string::npos;
    const int v = digits ? std::stoi(item) : 0;
    if (v < 1 || v > 256) {
      std::string shown = item.substr(0, 40);
      for (char& c : shown)
        if (c < ' ' || c == 127) c = '?';
      return "--threads: \"" + shown + (item.size() > 40 ? "...\"" : "\"") +
             " is not a thread count from 1 to 256 (a comma-separated list, e.g. 1,2,4)";
    }
    if (std::find(counts.begin(), counts.end(), v) != counts.end())
      return "--threads: " + std::to_string(v) + " is listed twice";
    counts.push_back(v);
  }
  if (counts.empty() || text.back() == ',')
    return "--threads: expected a comma-separated list of thread counts, e.g. 1,2,4";
  std::sort(counts.begin(), counts.end());
  return "";
}

constexpr int kStepsPerTurn = 10;  // run_bench: each thread count's share of the turns

// One size's run, a step at a time, so that the runs at several thread counts can take
// their steps in turn (run_bench). `begin` builds the simulation; each `step` runs and times
// one step (false, with *error and *code, when it fails or on Ctrl-C); `finish` fills the
// row's means and median from the steps that completed.
// With `hashes`, row.step_hashes gets the positions' hash after every step (outside the timing).
struct SizeRun {
  SceneDef scene;
  std::optional<Simulation> sim;
  BenchRow row;
  std::vector<double> ms;
  long newton = 0, pcg = 0, factorizations = 0;
  bool hashes = false;
  bool interrupted_run = false;  // stopped by Ctrl-C: the row is dropped (finish: no steps)

  bool begin(const SceneDef& base, int n_seg, int steps, bool keep_hashes, std::string* error,
             int* code) {
    scene = base;
    scene.n_seg = n_seg;
    hashes = keep_hashes;
    if (auto e = validate_scene(scene); !e.empty()) {
      *error = "n_seg " + std::to_string(n_seg) + ": " + e;
      *code = exit_code::kBadInput;
      return false;
    }
    sim.emplace(make_simulation(scene));
    row = BenchRow{};
    row.n_seg = n_seg;
    row.threads = thread_count();
    row.mesh_ms = cold_mesh_ms(scene);
    row.nodes = sim->mesh.node_count();
    row.triangles = sim->mesh.triangle_count();
    row.dofs = 2 * row.nodes + (scene.has_ceiling ? 1 : 0);
    row.solver =
        scene.integrator != Integrator::SymplecticEuler ? linear_solver_backend(*sim) : "explicit";
    if (scene.reduced_basis != ReducedBasis::Full)
      row.solver = "dense-ldlt-r" + std::to_string(sim->workspace->newton.reduced.basis.cols());
    ms.reserve(steps);
    return true;
  }

  bool step(std::string* error, int* code) {
    const int k = static_cast<int>(ms.size());
    const auto stop_interrupted = [&] {
      interrupted_run = true;
      *error = "interrupted at n_seg " + std::to_string(row.n_seg);
      *code = interrupted_exit_code();
      return false;
    };
    if (interrupted()) return stop_interrupted();
    const StepReport r = invfree::step(*sim);
    if (r.status != StepStatus::Ok && interrupted())  // a signal stopped Newton mid-step
      return stop_interrupted();
    if (r.status != StepStatus::Ok) {  // the row keeps the steps that completed
      *error = "n_seg " + std::to_string(row.n_seg) + ": step " + std::to_string(k + 1) +
               " failed: " + step_status_name(r.status) + ": " + r.message;
      *code = exit_code::kRunFailed;
      return false;
    }
    ms.push_back(r.wall_ms);
    if (r.wall_ms > row.max_ms) {
      row.max_ms = r.wall_ms;
      row.max_step = k + 1;
    }
    if (hashes) row.step_hashes.push_back(positions_hash(*sim));
    newton += r.newton_iterations;
    if (r.newton_iterations > row.newton_worst) {
      row.newton_worst = r.newton_iterations;
      row.newton_worst_step = k + 1;
    }
    pcg += r.pcg_iterations;
    factorizations += r.factorizations;
    row.assembly += r.assembly_ms;
    row.factor += r.factor_ms;
    row.solve += r.solve_ms;
    row.line_search += r.line_search_ms;
    row.self_contact += r.self_contact_ms;
    return true;
  }

  void finish() {
    const int steps = interrupted_run ? 0 : static_cast<int>(ms.size());
    row.steps = steps;
    if (steps == 0) return;
    double total = 0.0;
    for (double m : ms) total += m;
    std::vector<double> sorted = ms;
    std::nth_element(sorted.begin(), sorted.begin() + steps / 2, sorted.end());
    double median = sorted[steps / 2];
    if (steps % 2 == 0)
      median = 0.5 * (median + *std::max_element(sorted.begin(), sorted.begin() + steps / 2));
    const double inv = 1.0 / steps;
    row.mean_ms = total * inv;
    row.median_ms = median;
    row.newton = newton * inv;
    row.pcg = pcg * inv;
    row.factorizations = factorizations * inv;
    row.assembly *= inv;
    row.factor *= inv;
    row.solve *= inv;
    row.line_search *= inv;
    row.self_contact *= inv;
    row.other =
        std::max(0.0, row.mean_ms - row.assembly - row.factor - row.solve - row.line_search);
  }
};

// The median over the turns both runs completed of base's time for the turn over `other`'s
// (BenchRow::paired_speedup); 0 when no turn is complete in both.
double paired_speedup(const std::vector<double>& base, const std::vector<double>& other) {
  const std::size_t steps = std::min(base.size(), other.size());
  std::vector<double> ratios;
  for (std::size_t first = 0; first + kStepsPerTurn <= steps; first += kStepsPerTurn) {
    double a = 0.0, b = 0.0;
    for (std::size_t k = first; k < first + kStepsPerTurn; ++k) a += base[k], b += other[k];
    if (b > 0.0) ratios.push_back(a / b);
  }
  if (ratios.empty()) return 0.0;
  std::sort(ratios.begin(), ratios.end());
  const std::size_t m = ratios.size() / 2;
  return ratios.size() % 2 ? ratios[m] : 0.5 * (ratios[m - 1] + ratios[m]);
}

// Runs `steps` steps of `scene` at n_seg; false (and *error) when a step fails or on Ctrl-C.
bool run_size(const SceneDef& base, int n_seg, int steps, BenchRow& row, std::string* error,
              int* code) {
  SizeRun run;
  if (!run.begin(base, n_seg, steps, false, error, code)) return false;
  for (int k = 0; k < steps; ++k)
    if (!run.step(error, code)) break;
  run.finish();
  row = std::move(run.row);
  return *code == exit_code::kOk;
}

std::string csv_text(const std::vector<BenchRow>& rows) {
  std::ostringstream o;
  o << "n_seg,nodes,triangles,dofs,steps,mean_ms,median_ms,newton_per_step,newton_worst,"
       "newton_worst_step,assembly_ms,factor_ms,solve_ms,line_search_ms,other_ms,pcg_per_step,"
       "factorizations_per_step,solver,self_contact_ms,mesh_ms,full_median_ms,"
       "full_newton_per_step,threads,speedup,efficiency,max_ms,max_step,paired_speedup\n";
  for (const auto& r : rows)
    o << r.n_seg << "," << r.nodes << "," << r.triangles << "," << r.dofs << "," << r.steps << ","
      << format_number(r.mean_ms, "%.6g") << "," << format_number(r.median_ms, "%.6g") << ","
      << format_number(r.newton, "%.5g") << "," << r.newton_worst << "," << r.newton_worst_step
      << "," << format_number(r.assembly, "%.6g") << "," << format_number(r.factor, "%.6g") << ","
      << format_number(r.solve, "%.6g") << "," << format_number(r.line_search, "%.6g") << ","
      << format_number(r.other, "%.6g") << "," << format_number(r.pcg, "%.5g") << ","
      << format_number(r.factorizations, "%.5g") << "," << r.solver << ","
      << format_number(r.self_contact, "%.6g") << "," << format_number(r.mesh_ms, "%.6g") << ","
      << (r.full_median_ms > 0 ? format_number(r.full_median_ms, "%.6g") : "") << ","
      << (r.full_median_ms > 0 ? format_number(r.full_newton, "%.5g") : "") << "," << r.threads
      << "," << format_number(r.speedup, "%.5g") << "," << format_number(r.efficiency, "%.5g")
      << "," << format_number(r.max_ms, "%.6g") << "," << r.max_step << ","
      << format_number(r.paired_speedup, "%.5g") << "\n";
  return o.str();
}

// The log-log fit of median ms per step against unknowns over the rows with n_seg >= 32
// (the range the scaling target speaks of), or over every row when fewer than two qualify;
// *from_n: the smallest n_seg of that range. Not ok() when fewer than two rows are usable.
LogLogFit fit_cost(const std::vector<BenchRow>& rows, int* from_n) {
  for (int min_n : {32, 1}) {
    std::vector<double> dofs, ms;
    for (const auto& r : rows)
      if (r.n_seg >= min_n) {
        dofs.push_back(r.dofs);
        ms.push_back(r.median_ms);
      }
    *from_n = min_n;
    if (const LogLogFit fit = fit_loglog(dofs, ms); fit.ok()) return fit;
  }
  return {};
}

// The reference Python demo's median ms per step at n_seg 4, 8, 16, measured on the
// project's 2-core machine (AMD EPYC): the denominators of the "x the reference" column.
constexpr double kReferenceMs[3] = {36.0, 118.0, 495.0};
constexpr int kReferenceNseg[3] = {4, 8, 16};

// True when `scene` is the built-in `compress` (any n_seg): the reference applies.
bool is_reference_scene(SceneDef scene) {
  const auto compress = load_builtin_scene("compress").scene;
  scene.n_seg = compress->n_seg;
  return scene == *compress;
}

ChartSpec chart(const std::vector<BenchRow>& rows, const std::string& scene_name, bool reference) {
  ChartSpec spec;
  spec.title = "invfree bench: " + scene_name + ", time per step against unknowns";
  spec.x_label = "degrees of freedom (2 x nodes + ceiling)";
  spec.y_label = "ms per step";
  spec.log_x = spec.log_y = true;
  Series total{"median ms per step", {}, {}, Rgb{0.05f, 0.25f, 0.65f}};
  Series assembly{"assembly (mean)", {}, {}, Rgb{0.85f, 0.45f, 0.05f}};
  Series linear{"factorisation + solve (mean)", {}, {}, Rgb{0.15f, 0.6f, 0.25f}};
  Series search{"line search (mean)", {}, {}, Rgb{0.6f, 0.2f, 0.6f}};
  for (const auto& r : rows) {
    total.x.push_back(r.dofs), total.y.push_back(r.median_ms);
    assembly.x.push_back(r.dofs), assembly.y.push_back(r.assembly);
    linear.x.push_back(r.dofs), linear.y.push_back(r.factor + r.solve);
    search.x.push_back(r.dofs), search.y.push_back(r.line_search);
  }
  for (Series* s : {&assembly, &linear, &search}) s->lines = true;
  int from_n = 0;
  if (const LogLogFit fit = fit_cost(rows, &from_n); fit.ok()) {
    Series fitted{
        "fit: ms ~ DOF^" + format_number(fit.slope, "%.3g"), {}, {}, Rgb{0.8f, 0.1f, 0.1f}};
    fitted.markers = false;
    for (const auto& r : rows)
      if (r.n_seg >= from_n) {
        fitted.x.push_back(r.dofs);
        fitted.y.push_back(std::exp(fit.intercept + fit.slope * std::log(r.dofs)));
      }
    spec.series.push_back(fitted);
    spec.notes.push_back("fitted slope " + format_number(fit.slope, "%.3g") +
                         " over n_seg >= " + std::to_string(from_n));
  }
  if (reference) {
    Series python{"reference Python demo (median)", {}, {}, Rgb{0.45f, 0.45f, 0.45f}};
    Series target{"target: reference / 1000", {}, {}, Rgb{0.75f, 0.75f, 0.75f}};
    target.lines = false;
    for (int k = 0; k < 3; ++k) {
      const double dofs = 2.0 * (kReferenceNseg[k] + 1) * (kReferenceNseg[k] + 1) + 1.0;
      python.x.push_back(dofs), python.y.push_back(kReferenceMs[k]);
      target.x.push_back(dofs), target.y.push_back(kReferenceMs[k] / 1000.0);
    }
    spec.series.push_back(python);
    spec.series.push_back(target);
  }
  spec.series.push_back(total);
  if (!rows.empty() && rows.front().full_median_ms > 0) {
    Series full{"full model, same mesh (median)", {}, {}, Rgb{0.45f, 0.45f, 0.45f}};
    full.dash = 8.0;
    for (const auto& r : rows) full.x.push_back(r.dofs), full.y.push_back(r.full_median_ms);
    spec.series.push_back(full);
    spec.notes.push_back("reduced basis: Newton solves " + rows.front().solver.substr(12) +
                         " unknowns densely; assembly and the line search stay over the full "
                         "mesh (docs/scenes.md, \"Reduced bases\")");
  }
  spec.series.push_back(assembly);
  spec.series.push_back(linear);
  spec.series.push_back(search);
  if (!rows.empty()) {
    spec.notes.push_back("solver: " + rows.back().solver + ", " + std::to_string(thread_count()) +
                         " threads, " + std::to_string(rows.back().steps) + " steps per size");
  }
  return spec;
}

// The rows that ran at `threads` threads, in size order.
std::vector<BenchRow> rows_at(const std::vector<BenchRow>& rows, int threads) {
  std::vector<BenchRow> out;
  for (const auto& r : rows)
    if (r.threads == threads) out.push_back(r);
  return out;
}

std::string threads_label(int threads) {
  return std::to_string(threads) + (threads == 1 ? " thread" : " threads");
}

// A colour per thread count (then per size in the speed-up panel), in list order.
Rgb series_color(std::size_t k) {
  static constexpr Rgb palette[] = {{0.05f, 0.25f, 0.65f}, {0.85f, 0.45f, 0.05f},
                                    {0.15f, 0.6f, 0.25f},  {0.75f, 0.1f, 0.1f},
                                    {0.55f, 0.25f, 0.65f}, {0.1f, 0.6f, 0.65f},
                                    {0.55f, 0.4f, 0.2f},   {0.85f, 0.35f, 0.6f}};
  return palette[k % (sizeof palette / sizeof palette[0])];
}

// With several thread counts: the median step against unknowns, one line per count (and a
// reduced scene's full model, dashed, per count), then the speed-up against the thread
// count, one line per size, beside the ideal (linear in the thread ratio).
std::vector<ChartSpec> thread_charts(const std::vector<BenchRow>& rows, const std::vector<int>& counts,
                                     const std::string& scene_name) {
  ChartSpec time;
  time.title = "invfree bench: " + scene_name + ", time per step against unknowns, per thread count";
  time.x_label = "degrees of freedom (2 x nodes + ceiling)";
  time.y_label = "median ms per step";
  time.log_x = time.log_y = true;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    const std::vector<BenchRow> at = rows_at(rows, counts[k]);
    if (at.empty()) continue;
    Series s{threads_label(counts[k]) + " (median)", {}, {}, series_color(k)};
    for (const auto& r : at) s.x.push_back(r.dofs), s.y.push_back(r.median_ms);
    time.series.push_back(s);
    if (at.front().full_median_ms > 0) {
      Series full{threads_label(counts[k]) + ": full model, same mesh", {}, {}, series_color(k)};
      full.dash = 8.0;
      for (const auto& r : at) full.x.push_back(r.dofs), full.y.push_back(r.full_median_ms);
      time.series.push_back(full);
    }
  }
  if (!rows.empty())
    time.notes.push_back("solver: " + rows.back().solver + ", " +
                         std::to_string(rows.back().steps) + " steps per size and thread count");

  ChartSpec speed;
  speed.title = "speed-up of the median step against " + threads_label(counts.front());
  speed.x_label = "threads";
  speed.y_label = "speed-up";
  // Ticks at the counts run, never at fractions of a thread. A sweep over a factor of 4 or
  // more is drawn log-log, where ideal scaling is a straight line and doubling the threads
  // is the same step everywhere; its speed-up axis is then ticked at the ideal speed-ups
  // (a log axis's own labels would be the decades alone).
  speed.log_x = speed.log_y = counts.back() >= 4 * counts.front();
  for (int t : counts) {
    speed.x_ticks.push_back(t);
    if (speed.log_y) speed.y_ticks.push_back(double(t) / counts.front());
  }
  std::vector<int> sizes;
  for (const auto& r : rows)
    if (std::find(sizes.begin(), sizes.end(), r.n_seg) == sizes.end()) sizes.push_back(r.n_seg);
  Series ideal{"ideal (thread ratio)", {}, {}, Rgb{0.6f, 0.6f, 0.6f}};
  ideal.markers = false;
  ideal.dash = 8.0;
  for (int t : counts) ideal.x.push_back(t), ideal.y.push_back(double(t) / counts.front());
  speed.series.push_back(ideal);
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    Series s{"n_seg " + std::to_string(sizes[k]), {}, {}, series_color(k)};
    for (const auto& r : rows)
      if (r.n_seg == sizes[k]) s.x.push_back(r.threads), s.y.push_back(r.speedup);
    speed.series.push_back(s);
  }
  speed.notes.push_back("parallel efficiency = speed-up / thread ratio (bench.csv's efficiency)");
  return {time, speed};
}

// The largest n_seg in (lo, hi) whose median step fits in `budget_ms`, knowing lo fits
// and hi does not; each candidate runs as many steps as the sweep (a shorter run would
// see only the cheap falling phase).
int bisect_fps(const SceneDef& scene, int lo, int hi, int steps, double budget_ms,
               std::string* error, int* code) {
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    BenchRow row;
    if (!run_size(scene, mid, steps, row, error, code)) return -1;
    std::printf("  n_seg %4d: median %.3f ms/step\n", mid, row.median_ms);
    flush_standard_output();
    (row.median_ms <= budget_ms ? lo : hi) = mid;
  }
  return lo;
}

// The stdout table: its header, then one line per size (with the speed-up over the
// reference demo where it applies).
// With several thread counts (`threads`), three more columns: the count, the speed-up and
// the parallel efficiency.
void print_header(bool threads) {
  std::printf("%-6s ", "n_seg");
  if (threads) std::printf("%7s ", "threads");
  std::printf("%8s %10s %6s %10s %10s %10s ", "dofs", "triangles", "steps", "median_ms", "mean_ms",
              "max_ms");
  if (threads) std::printf("%7s %6s %7s ", "speedup", "effic", "paired");
  std::printf("%7s %6s %9s %9s %9s %9s %9s %6s %9s  %s\n", "newton", "worst", "assembly", "factor",
              "solve", "search", "contact", "pcg", "mesh_ms", "solver");
}
void print_row(const BenchRow& row, bool reference, bool threads) {
  std::string speedup;
  for (int k = 0; k < 3; ++k)
    if (reference && row.n_seg == kReferenceNseg[k] && row.median_ms > 0.0)
      speedup = "  " + format_number(kReferenceMs[k] / row.median_ms, "%.4g") + "x the reference";
  if (row.full_median_ms > 0.0 && row.median_ms > 0.0)
    speedup = "  full model " + format_number(row.full_median_ms, "%.4g") + " ms (" +
              format_number(row.full_newton, "%.3g") + " newton): " +
              format_number(row.full_median_ms / row.median_ms, "%.3g") + "x faster reduced";
  std::printf("%-6d ", row.n_seg);
  if (threads) std::printf("%7d ", row.threads);
  std::printf("%8d %10d %6d %10.4f %10.4f %10.4f ", row.dofs, row.triangles, row.steps,
              row.median_ms, row.mean_ms, row.max_ms);
  if (threads) std::printf("%6.3fx %6.3f %6.3fx ", row.speedup, row.efficiency, row.paired_speedup);
  std::printf("%7.2f %6d %9.4f %9.4f %9.4f %9.4f %9.4f %6.2f %9.3f  %s%s\n", row.newton,
              row.newton_worst, row.assembly, row.factor, row.solve, row.line_search,
              row.self_contact, row.pcg, row.mesh_ms, row.solver.c_str(), speedup.c_str());
  flush_standard_output();
}

// --fps: the largest n_seg whose median step fits in one frame, from the sizes that ran
// and, between the largest that fits and the smallest that does not, by bisection.
int report_fps(const SceneDef& scene, const std::vector<BenchRow>& rows, const BenchOptions& opt) {
  const double budget = 1000.0 / opt.fps;
  int lo = 0, hi = 0;
  for (const auto& r : rows) {
    if (r.median_ms <= budget)
      lo = std::max(lo, r.n_seg);
    else if (hi == 0 || r.n_seg < hi)
      hi = r.n_seg;
  }
  if (lo == 0) {
    std::printf("no size ran within %.1f ms per step (%.0f fps)\n", budget, opt.fps);
  } else if (hi == 0 || hi <= lo) {
    std::printf("largest n_seg at %.0f fps: at least %d (every size ran within %.1f ms per step)\n",
                opt.fps, lo, budget);
  } else {
    std::printf("bisecting n_seg in (%d, %d) for %.1f ms per step (%.0f fps):\n", lo, hi, budget,
                opt.fps);
    std::string error;
    int code = exit_code::kOk;
    const int best = bisect_fps(scene, lo, hi, opt.steps, budget, &error, &code);
    if (best < 0) return fail(code, error);
    std::printf("largest n_seg at %.0f fps (median step within %.1f ms): %d\n", opt.fps, budget,
                best);
  }
  return exit_code::kOk;
}

// Whether every size's runs at the different thread counts left the same positions after
// every step; "" when they did, else where they first differed. Sizes with one run are skipped.
std::string compare_across_threads(const std::vector<BenchRow>& rows) {
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const BenchRow* base = nullptr;
    for (std::size_t j = 0; j < k && !base; ++j)
      if (rows[j].n_seg == rows[k].n_seg) base = &rows[j];
    if (!base) continue;
    const auto& a = base->step_hashes;
    const auto& b = rows[k].step_hashes;
    const std::size_t common = std::min(a.size(), b.size());
    const auto diff = std::mismatch(a.begin(), a.begin() + common, b.begin()).first - a.begin();
    const std::string where = "n_seg " + std::to_string(rows[k].n_seg) + ", " +
                              threads_label(rows[k].threads) + " against " +
                              threads_label(base->threads);
    if (static_cast<std::size_t>(diff) < common)
      return where + ": the positions differ from step " + std::to_string(diff + 1);
    if (a.size() != b.size())
      return where + ": " + std::to_string(b.size()) + " steps against " + std::to_string(a.size());
  }
  return "";
}

int run_bench(const BenchOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  std::vector<int> sizes;
  if (auto e = parse_sizes(opt.sizes, sizes); !e.empty()) return fail(exit_code::kBadInput, e);
  // The thread counts; {0}: the count already set (every core, or INVFREE_THREADS).
  std::vector<int> counts;
  if (!opt.threads_given)
    counts = {0};
  else if (auto e = parse_threads(opt.threads, counts); !e.empty())
    return fail(exit_code::kBadInput, e);
  const bool several = counts.size() > 1;
  for (int n : sizes) {
    SceneDef s = *scene;
    s.n_seg = n;
    if (auto e = validate_scene(s); !e.empty())
      return fail(exit_code::kBadInput, "n_seg " + std::to_string(n) + ": " + e);
  }
  const std::string csv_path = opt.out_dir + "/bench.csv",
                    chart_path = opt.out_dir + "/bench." + chart_extension(opt.format);
  if (auto e = check_output_files({csv_path, chart_path}, opt.scene.input_files(), opt.force))
    return fail(e.exit_code, e.message);
  if (counts.front() > 0) set_thread_count(counts.front());
  if (counts.front() == 0) counts = {thread_count()};

  if (several)
    std::printf(
        "the thread counts' runs take turns of %d steps: a drift in the machine's speed "
        "affects them alike\n",
        kStepsPerTurn);
  print_header(several);
  const bool reference = is_reference_scene(*scene);
  std::vector<BenchRow> rows;
  int code = exit_code::kOk;
  bool ok = true;
  for (std::size_t i = 0; i < sizes.size() && ok; ++i) {
    const int n = sizes[i];
    // One run per thread count, taking turns of kStepsPerTurn steps (the pool is switched
    // between steps, never during one): a machine whose speed drifts over minutes slows
    // every count alike, so the speed-up compares like with like. Turns of several steps,
    // not one, keep a small mesh's data in cache from step to step as in a run alone.
    std::vector<SizeRun> runs(counts.size());
    for (std::size_t k = 0; k < counts.size() && ok; ++k) {
      if (several) set_thread_count(counts[k]);
      ok = runs[k].begin(*scene, n, opt.steps, several, &error, &code);
    }
    if (!ok) break;
    // A step that fails at one count is still tried at the others (it fails there too:
    // the runs are bit-identical); Ctrl-C stops at once.
    for (int first = 0; first < opt.steps && ok; first += kStepsPerTurn)
      for (std::size_t k = 0; k < counts.size() && !interrupted(); ++k) {
        if (several) set_thread_count(counts[k]);
        const int last = std::min(opt.steps, first + kStepsPerTurn);
        bool run_ok = true;
        for (int step = first; step < last && run_ok; ++step) run_ok = runs[k].step(&error, &code);
        ok = run_ok && ok;
      }
    double base_median = 0.0;
    for (std::size_t k = 0; k < counts.size(); ++k) {
      if (several) set_thread_count(counts[k]);
      runs[k].finish();
      BenchRow row = std::move(runs[k].row);
      if (ok && scene->reduced_basis != ReducedBasis::Full) {
        SceneDef full = *scene;
        full.reduced_basis = ReducedBasis::Full;
        BenchRow full_row;
        ok = run_size(full, n, opt.steps, full_row, &error, &code);
        if (ok) row.full_median_ms = full_row.median_ms, row.full_newton = full_row.newton;
      }
      if (row.steps == 0) break;
      if (row.steps < opt.steps)
        row.solver += " (failed at step " + std::to_string(row.steps + 1) + ")";
      if (k == 0) base_median = row.median_ms;
      if (k > 0 && row.median_ms > 0.0 && base_median > 0.0) {
        row.speedup = base_median / row.median_ms;
        row.efficiency = row.speedup * counts.front() / counts[k];
        row.paired_speedup = paired_speedup(runs.front().ms, runs[k].ms);
      }
      rows.push_back(row);
      print_row(row, reference, several);
    }
  }
  // Whatever completed is written, also after a failure or Ctrl-C.
  if (!rows.empty()) {
    if (several && code == exit_code::kOk) {
      const std::string diff = compare_across_threads(rows);
      std::printf("bit-identical across thread counts: %s\n",
                  diff.empty() ? "yes (the positions after every step, at every size)"
                               : ("no (" + diff + ")").c_str());
    }
    if (auto e = write_file_atomically(csv_path, csv_text(rows)); !e.empty())
      return fail(exit_code::kOutputFailed, e);
    const std::vector<ChartSpec> panels =
        several ? thread_charts(rows, counts, scene->name)
                : std::vector<ChartSpec>{chart(rows, scene->name, reference)};
    if (auto e = write_canvas(chart_path, *chart_canvas(panels, opt.format)); !e.empty())
      return fail(exit_code::kOutputFailed, e);
    for (int t : counts) {
      int from_n = 0;
      if (const LogLogFit fit = fit_cost(rows_at(rows, t), &from_n); fit.ok())
        std::printf("fitted slope%s: ms per step ~ DOF^%.3f over n_seg >= %d\n",
                    several ? (" at " + threads_label(t)).c_str() : "", fit.slope, from_n);
    }
    std::printf("wrote %s and %s\n", csv_path.c_str(), chart_path.c_str());
  }
  if (code != exit_code::kOk) return fail(code, error);

  if (opt.fps > 0.0) {
    // With several counts, at the largest (the thread count set last).
    if (several) std::printf("--fps at %s (the largest count listed):\n",
                             threads_label(counts.back()).c_str());
    return report_fps(*scene, rows_at(rows, counts.back()), opt);
  }
  return exit_code::kOk;
}

}  // namespace

void register_bench_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<BenchOptions>(
      app, exit_code, "bench",
      "time a scene at several mesh sizes; write bench.csv and a log-log chart bench.png",
      run_bench);
  opt.scene.add_to(cmd);
  cmd->add_option("--sizes", opt.sizes, "comma-separated n_seg values")->capture_default_str();
  cmd->add_option("--steps", opt.steps,
                  "time steps per size (the whole run of the scene by default)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  add_output_directory_option(cmd, opt.out_dir, "output directory for bench.csv and bench.png");
  add_chart_format_option(cmd, opt.format);
  add_force_option(cmd, opt.force, "overwrite bench.csv and the chart if they exist");
  cmd->add_option("--threads", opt.threads,
                  "worker threads, or a comma-separated list (1,2,4) to run every size at each "
                  "count and report the speed-up (default: every core)")
      ->each([&given = opt.threads_given](const std::string&) { given = true; });
  cmd->add_option("--fps", opt.fps,
                  "then find the largest n_seg whose median step fits in one frame at this rate")
      ->check(finite_range(1.0, 10000.0));
}

}  // namespace invfree
