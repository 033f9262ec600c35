// `invfree render`: steps a scene and writes one PNG per frame through the offscreen
// renderer (OSMesa: no display, no X server), optionally also an MP4 through ffmpeg.
// Frame 0 is the initial state; frame i is the state after i * steps-per-frame steps.
//
// Pipeline (so that simulation, drawing and PNG encoding overlap on two cores): a thread
// steps the simulation and queues each frame's state; the main thread (which owns the GL
// context) draws it and reads the pixels back; a FrameWriter thread encodes and writes
// the PNG. So a frame costs about the largest of the three, not their sum.
// Progress (frame i/N, elapsed, ETA) goes to stderr when it is a terminal; a one-line
// summary to stdout.
#include <fcntl.h>
#include <pthread.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "app/cli_checks.h"
#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/movie.h"
#include "app/output_files.h"
#include "app/render/frame_writer.h"
#include "app/render/offscreen_context.h"
#include "app/render/projector_mesh.h"
#include "app/render/renderer.h"
#include "app/render/side_by_side.h"
#include "app/render/view_choices.h"
#include "app/scene_options.h"
#include "app/study/methods.h"
#include "enum_names.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree {

namespace {

struct RenderOptions {
  SceneOptions scene;
  int frames = 0;  // 0: until nothing moves (auto_frame_limit, settled_frames)
  int steps_per_frame = 0;  // 0: 1, or with a movie the lecture default (lecture_steps_per_frame)
  std::string out = "frames";
  std::string size;  // "": 1280x720, or 1920x1080 with --compare
  std::string compare;  // "A,B": two methods side by side (app/study/methods.h)
  bool no_edges = false;
  bool mp4 = false;
  bool gif = false;
  double fps = 0.0;  // 0: real time
  bool force = false;
  int png_level = 1;
  int writer_threads = 1;
  // The defaults are for a projector (docs/rendering.md, "Defaults"): colours scaled to the
  // run, a camera on the bodies, a mesh fine enough to show a gradient.
  std::string color_range = "run";  // render::parse_color_range_mode
  std::string camera = "follow";    // fixed | follow
  int min_n_seg = render::kProjectorMinSegments;  // a square's n_seg raised to this (0: the scene's)
  std::string paths = "auto";       // the bodies' paths: auto (several bodies), on, off
  std::string color_by = "det-f";     // kTriangleFieldNames (core/triangle_fields.h)
  bool stress_glyphs = false;
  int select_triangle = -1;  // outlined; -1: none
};

// The frame rates a movie may have (--fps, or the real-time rate it defaults to).
constexpr double kMinFps = 0.1, kMaxFps = 1000.0;

// A movie for a lecture plays in real time (its length is the simulated time) at about 30
// frames/s: the steps per frame closest to 1 / (30 h), at least 1 (a time step longer than
// 1/30 s then plays at 1 / h frames/s, still real time).
constexpr double kLectureFps = 30.0;
constexpr int kMaxStepsPerFrame = 1000000;  // --steps-per-frame's range
int lecture_steps_per_frame(double h) {
  return static_cast<int>(
      std::clamp(std::round(1.0 / (kLectureFps * h)), 1.0, double(kMaxStepsPerFrame)));
}

// The end of a run without --frames: the movie stops once nothing has moved for
// kSettledHold seconds of simulated time (so its last still pose is shown that long) -- no
// node faster than kSettledSpeed body sizes per second over a frame and the ceiling at
// rest -- or at the limit: 10 s of simulated time, 300 to 1000 frames.
constexpr double kSettledHold = 0.5, kSettledSpeed = 0.01, kAutoSeconds = 10.0;
int auto_frame_limit(double h, int steps_per_frame) {
  return static_cast<int>(
      std::clamp(std::ceil(kAutoSeconds / (h * steps_per_frame)) + 1.0, 300.0, 1000.0));
}

std::string frame_name(int i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06d.png", i);
  return buf;
}

// Steps the simulation on its own thread and hands over a FrameState per frame (frame 0:
// the initial state) through a short queue, so that the next frame is being simulated
// while this one is drawn and encoded.
class SimulationThread {
 public:
  // frames: the number to make, or with `until_settled` the most (see kSettledHold).
  SimulationThread(Simulation& sim, int frames, int steps_per_frame, bool until_settled,
                   const render::CaptureOptions& capture, std::mutex* core_lock = nullptr)
      : core_lock_(core_lock),
        sim_(sim),
        frames_(frames),
        steps_per_frame_(steps_per_frame),
        until_settled_(until_settled),
        capture_(capture),
        thread_([this] { run(); }) {}
  ~SimulationThread() { stop(); }

  // The next frame's state; false when there is none (all produced, a step failed, or
  // interrupted).
  bool next(render::FrameState* state) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return !queue_.empty() || done_; });
    if (queue_.empty()) return false;
    *state = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();
    return true;
  }
  // det F's range over every state the run reached (step 0 and each accepted step, not
  // only the frames'), as `invfree simulate` reports it; read after stop().
  double det_lo() const { return det_lo_; }
  double det_hi() const { return det_hi_; }
  // With until_settled: the time since when nothing moved (NaN: it still moved at the end).
  double settled_since() const { return settled_since_; }
  // Stops and joins the thread; returns the failed step's report (status Ok otherwise).
  StepReport stop() {
    {
      std::lock_guard lock(mutex_);  // so that a waiting run() cannot miss the change
      stopping_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
    return failure_;
  }

 private:
  void run() {
    pthread_setname_np(pthread_self(), "invfree-sim");  // for top and perf
    {
      const auto core = lock_core();
      measure_det_f();
    }
    const double size = body_size();
    for (int f = 0; f < frames_; ++f) {
      render::FrameState state;
      {
        const auto core = lock_core();  // (released before push, which may wait for the reader)
        if (f > 0) {
          const VecX x_before = sim_.x;
          const double ceiling_before = sim_.ceiling_nominal, t_before = sim_.time;
          for (int k = 0; k < steps_per_frame_; ++k) {
            if (interrupted() || stopping_) return finish();
            const StepReport r = step(sim_);
            if (r.status != StepStatus::Ok) {
              failure_ = r;
              // The last good state once more, marked as failed in the picture.
              state = render::capture_frame_state(sim_, nullptr, capture_);
              state.failure = "step " + std::to_string(sim_.step_count + 1) + " failed: " +
                              step_status_name(r.status) + ": " + r.message;
              break;
            }
            measure_det_f();
          }
          if (state.failure.empty()) {  // (a failed frame is pushed below, unlocked)
            const double dt = sim_.time - t_before;
            const double speed = dt > 0.0 ? max_node_move(x_before, sim_.x) / dt : 0.0;
            const bool still =
                speed < kSettledSpeed * size && sim_.ceiling_nominal == ceiling_before;
            if (!still) settled_since_ = std::numeric_limits<double>::quiet_NaN();
            else if (std::isnan(settled_since_)) settled_since_ = t_before;
          }
        }
        if (state.failure.empty()) state = render::capture_frame_state(sim_, nullptr, capture_);
      }
      if (!state.failure.empty()) {
        push(std::move(state));
        return finish();
      }
      if (!push(std::move(state))) break;
      if (until_settled_ && !std::isnan(settled_since_) &&
          sim_.time - settled_since_ >= kSettledHold - 1e-9)
        break;
    }
    finish();
  }
  // Runs side by side (--compare) share `core_lock` and step one at a time, so each has the
  // core's thread pool to itself (core/linalg/parallel.h: a caller that finds it busy runs
  // its tasks on its own thread); the frames wait for the slower run either way.
  std::unique_lock<std::mutex> lock_core() {
    return core_lock_ ? std::unique_lock<std::mutex>(*core_lock_) : std::unique_lock<std::mutex>();
  }
  bool push(render::FrameState state) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < kCapacity || stopping_; });
    if (stopping_) return false;
    queue_.push_back(std::move(state));
    changed_.notify_all();
    return true;
  }
  // Runs after every step: triangle_det_f's values (core/simulation.h, the same F and
  // determinant, so the same range bit for bit) folded into the range as they are computed,
  // without the vector it would allocate each time.
  void measure_det_f() {
    for (int t = 0; t < sim_.mesh.triangle_count(); ++t) {
      const double d = triangle_deformation_gradient(sim_, t).determinant();
      det_lo_ = std::min(det_lo_, d);
      det_hi_ = std::max(det_hi_, d);
    }
  }
  // The largest extent of the nodes at the start: "still" is relative to it.
  double body_size() const {
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (Eigen::Index i = 0; i + 1 < sim_.x.size(); i += 2) {
      lo = lo.cwiseMin(Vec2(sim_.x[i], sim_.x[i + 1]));
      hi = hi.cwiseMax(Vec2(sim_.x[i], sim_.x[i + 1]));
    }
    const double size = sim_.x.size() >= 2 ? (hi - lo).maxCoeff() : 0.0;
    return size > 0.0 ? size : 1.0;  // (a lone particle: metres)
  }
  static double max_node_move(const VecX& a, const VecX& b) {
    double m = 0.0;
    for (Eigen::Index i = 0; i + 1 < a.size(); i += 2)
      m = std::max(m, std::hypot(b[i] - a[i], b[i + 1] - a[i + 1]));
    return m;
  }
  void finish() {
    std::lock_guard lock(mutex_);
    done_ = true;
    changed_.notify_all();
  }

  static constexpr size_t kCapacity = 2;
  std::mutex* const core_lock_;
  Simulation& sim_;
  const int frames_, steps_per_frame_;
  const bool until_settled_;
  const render::CaptureOptions capture_;
  double det_lo_ = std::numeric_limits<double>::infinity(), det_hi_ = -det_lo_;
  double settled_since_ = std::numeric_limits<double>::quiet_NaN();
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<render::FrameState> queue_;
  bool done_ = false;
  std::atomic<bool> stopping_{false};
  StepReport failure_;
  std::thread thread_;  // last: starts once everything above is initialised
};

class Progress {
 public:
  Progress(int total) : total_(total), tty_(::isatty(STDERR_FILENO) != 0) {}
  void update(int done, double elapsed) {
    if (!tty_ || (elapsed - last_ < 0.1 && done < total_)) return;
    last_ = elapsed;
    const double eta = done > 0 ? elapsed / done * (total_ - done) : 0.0;
    std::fprintf(stderr, "\r\033[Krender: frame %d/%d  %.1f s elapsed  ETA %.1f s", done, total_,
                 elapsed, eta);
    std::fflush(stderr);
    shown_ = true;
  }
  // ffmpeg's progress while it makes the movie.
  void encoding(const std::string& movie, int done, double elapsed) {
    if (!tty_ || (elapsed - last_ < 0.1 && done < total_)) return;
    last_ = elapsed;
    std::fprintf(stderr, "\r\033[Krender: encoding %s with ffmpeg: frame %d/%d  %.1f s elapsed",
                 movie.c_str(), done, total_, elapsed);
    std::fflush(stderr);
    shown_ = true;
  }
  void clear() {
    if (shown_) std::fprintf(stderr, "\r\033[K");
    shown_ = false;
  }

 private:
  int total_;
  bool tty_;
  bool shown_ = false;
  double last_ = -1.0;
};

// One simulation a render shows: alone, or one side of --compare (then with its heading).
struct RenderRun {
  Simulation* sim = nullptr;
  int steps_per_frame = 1;         // each run's, so that every frame is the same time for all
  std::vector<std::string> title;  // DrawOptions::title; empty: none
};

// What one run did: the det F range over every step (not only the frames'), when nothing
// moved any more, and the failed step's report (status Ok when none failed).
struct RunOutcome {
  double det_lo = 1.0, det_hi = 1.0;
  double settled_since = std::numeric_limits<double>::quiet_NaN();
  StepReport failure;
};

// What a render produced: frames written and each run's outcome.
struct RenderedFrames {
  int frames = 0;
  std::vector<RunOutcome> runs;
};

// The pipeline (see the top of this file): a simulation thread per run, drawing here, PNG
// encoding on the writer's threads. Several runs (--compare) go in lockstep, frame i of
// each the state after i * its steps-per-frame steps, drawn side by side at the renderer's
// size each, with one colour scale (det F, Psi or stress) and one camera for all; a run
// that failed or settled keeps its last frame (a failed one marked) while the others go
// on. Stops when every run has ended, at a write error or Ctrl-C.
RenderedFrames render_frames(const std::vector<RenderRun>& runs, render::Renderer& renderer,
                             render::FrameWriter& writer, const RenderOptions& opt,
                             const std::function<double()>& elapsed) {
  const size_t n = runs.size();
  const Simulation& first = *runs.front().sim;
  render::DrawOptions draw_options;
  draw_options.stress_glyphs = opt.stress_glyphs;
  draw_options.selected_triangle = opt.select_triangle;
  render::CaptureOptions capture;
  capture.color_by = *enum_from_name(kTriangleFieldNames, opt.color_by);
  capture.stress_glyphs = opt.stress_glyphs;
  render::ColorRangeTracker color_range;
  color_range.mode = *render::parse_color_range_mode(opt.color_range);
  render::FollowCamera follow;
  std::vector<render::BodyPaths> paths(n);
  const bool draw_paths =
      opt.paths == "on" || (opt.paths == "auto" && render::paths_by_default(first.scene));
  // The dots: 4% of the bodies' start extent over their count (a body's size, roughly).
  double path_dot = 0.0;
  if (draw_paths && first.x.size() >= 2) {
    Vec2 lo(first.x[0], first.x[1]), hi = lo;
    for (Eigen::Index i = 0; i + 1 < first.x.size(); i += 2) {
      lo = lo.cwiseMin(Vec2(first.x[i], first.x[i + 1]));
      hi = hi.cwiseMax(Vec2(first.x[i], first.x[i + 1]));
    }
    path_dot = 0.04 * (hi - lo).maxCoeff() / std::max<size_t>(1, first.mesh.body_begin.size());
  }
  const render::FrameLayout layout = renderer.layout();
  const bool titled = std::any_of(runs.begin(), runs.end(),
                                  [](const RenderRun& r) { return !r.title.empty(); });
  // A titled view keeps its heading band clear of the bodies.
  const render::PixelRect framed = titled ? render::below_title(layout) : layout.plot;
  const bool until_settled = opt.frames == 0;
  const int frames = until_settled
                         ? auto_frame_limit(first.scene.h, runs.front().steps_per_frame)
                         : opt.frames;
  Progress progress(frames);
  RenderedFrames out;
  std::mutex core_lock;  // one run steps at a time (SimulationThread::lock_core)
  std::vector<std::unique_ptr<SimulationThread>> producers;
  for (const RenderRun& r : runs)
    producers.push_back(std::make_unique<SimulationThread>(
        *r.sim, frames, r.steps_per_frame, until_settled, capture, n > 1 ? &core_lock : nullptr));
  // Each run's frame as drawn (its paths' overlays added): a run that has ended is drawn
  // from it again.
  std::vector<render::FrameState> shown(n);
  std::vector<bool> running(n, true);
  std::vector<std::vector<std::uint8_t>> views(n);
  while (!interrupted()) {
    bool fresh = false;
    for (size_t i = 0; i < n; ++i) {
      render::FrameState state;
      if (running[i] && producers[i]->next(&state)) {
        if (draw_paths) paths[i].add(&state, path_dot);
        shown[i] = std::move(state);
        fresh = true;
      } else {
        running[i] = false;
      }
    }
    if (!fresh || interrupted()) break;
    std::vector<const render::FrameState*> states;
    for (const render::FrameState& s : shown) states.push_back(&s);
    if (std::any_of(states.begin(), states.end(), [](auto* s) { return !s->det_f.empty(); })) {
      const auto [lo, hi] = render::joint_bulk_det_f_range(states);
      color_range.apply(lo, hi, &draw_options);
    }
    color_range.apply_field(states, &draw_options);  // one Psi or stress scale for all views
    const render::Camera cam =
        opt.camera == "follow"
            ? (n == 1 ? follow.next(shown.front(), framed)
                      : follow.next(render::nodes_of_all(states), framed))
            : render::fit_camera(render::scene_world_box(first.scene), framed);
    draw_options.camera = cam;
    draw_options.edges = !opt.no_edges && render::edges_legible(first.scene, cam.pixels_per_metre);
    std::vector<std::uint8_t> pixels = writer.take_buffer();
    for (size_t i = 0; i < n; ++i) {
      draw_options.title = runs[i].title;
      renderer.draw(shown[i], draw_options);
      renderer.read_pixels(n == 1 ? &pixels : &views[i]);
    }
    if (n == 2)
      render::join_side_by_side(views[0], views[1], renderer.width(), renderer.height(), &pixels);
    if (!writer.submit(opt.out + "/" + frame_name(out.frames), renderer.width() * int(n),
                       renderer.height(), std::move(pixels)))
      break;
    ++out.frames;
    progress.update(out.frames, elapsed());
  }
  for (size_t i = 0; i < n; ++i) {
    RunOutcome r;
    r.failure = producers[i]->stop();  // joins; the simulation is the caller's again
    r.det_lo = producers[i]->det_lo();
    r.det_hi = producers[i]->det_hi();
    r.settled_since = producers[i]->settled_since();
    if (interrupted()) r.failure = {};  // a signal stopped Newton mid-step: an interruption
    out.runs.push_back(r);
  }
  progress.clear();
  return out;
}

// A projector needs a gradient across the body (render::refine_for_projector, shared with
// the live window and the page), unless the command line sets mesh.n_seg or names inspect's
// triangle (--select-triangle T: the scene's mesh). Returns the note for the summary ("" when
// the scene's mesh is kept).
std::string refine_for_projector(SceneDef& scene, const RenderOptions& opt) {
  if (opt.select_triangle >= 0 || render::overrides_set_n_seg(opt.scene.overrides)) return "";
  const int from = scene.n_seg;
  if (!render::refine_for_projector(scene, opt.min_n_seg)) return "";
  return "mesh n_seg " + std::to_string(from) + " -> " + std::to_string(opt.min_n_seg) +
         " for the picture (--min-n-seg 0 keeps the scene's)";
}

// --compare A,B: two different methods of `invfree stability`'s table, in the order given
// (left, right). Returns "" or a one-line error that lists the names.
std::string parse_compare(const std::string& text, std::vector<const Method*>* out) {
  std::string choices;
  for (const Method& m : stability_methods())
    choices += std::string(choices.empty() ? "" : ", ") + m.name;
  std::vector<std::string> names;
  for (size_t begin = 0; begin <= text.size();) {
    const size_t end = std::min(text.find(',', begin), text.size());
    names.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  if (names.size() != 2)
    return "--compare: name two methods, left,right (got " + std::to_string(names.size()) +
           " in '" + text + "'), e.g. lecture,no-projection; one of: " + choices;
  out->clear();
  for (const std::string& name : names) {
    const Method* m = find_method(name);
    if (!m) return "--compare: unknown method '" + name + "' (one of: " + choices + ")";
    out->push_back(m);
  }
  if (names[0] == names[1])
    return "--compare: '" + names[0] + "' twice; name two different methods (one of: " + choices +
           ")";
  return "";
}

// Returns a number for the summary: "%.4f" below 1e5, "%.4g" above.
std::string det_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, std::abs(v) < 1e5 ? "%.4f" : "%.4g", v);
  return buf;
}

int run_render(const RenderOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  std::vector<const Method*> compare;
  if (!opt.compare.empty())
    if (auto e = parse_compare(opt.compare, &compare); !e.empty())
      return fail(exit_code::kBadInput, e);
  const std::string refined = refine_for_projector(*scene, opt);
  // Two views side by side: each 960x1080 at the default size, as tall as a projector's
  // picture and as wide as half of it.
  const std::string size = !opt.size.empty() ? opt.size : compare.empty() ? "1280x720" : "1920x1080";
  int width = 0, height = 0;
  if (auto e = parse_frame_size(size, &width, &height); !e.empty())
    return fail(exit_code::kBadInput, e);
  if (!compare.empty() && width % 2 != 0)
    return fail(exit_code::kBadInput, "--size " + size +
                                          ": --compare needs an even width (two views of half "
                                          "the width each), e.g. " +
                                          std::to_string(width + 1) + "x" + std::to_string(height));
  std::string ffmpeg;
  const bool movie_wanted = opt.mp4 || opt.gif;
  const char* movie_flag = opt.mp4 ? "--mp4" : "--gif";
  if (movie_wanted) {
    ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty())
      return fail(exit_code::kBadInput,
                  std::string(movie_flag) +
                      " needs ffmpeg, which is not on PATH (install it: sudo apt-get install "
                      "ffmpeg; or leave out " +
                      movie_flag + " to write the PNG frames only)");
  }
  RenderOptions run = opt;
  if (run.steps_per_frame == 0)
    run.steps_per_frame = movie_wanted && opt.fps == 0.0 ? lecture_steps_per_frame(scene->h) : 1;
  const double fps = opt.fps > 0.0 ? opt.fps : 1.0 / (scene->h * run.steps_per_frame);
  if (movie_wanted && !(fps >= kMinFps && fps <= kMaxFps)) {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.6g", fps);
    return fail(exit_code::kBadInput,
                std::string(movie_flag) +
                    ": the real-time frame rate 1 / (h * steps-per-frame) = " + rate +
                    " frames/s is outside 0.1 to 1000; give --fps or change --steps-per-frame");
  }
  // The runs: the scene alone, or once per compared method (its settings applied; an
  // explicit method takes its substeps within each of the scene's steps, so that a frame
  // is the same simulated time on both sides).
  std::vector<std::unique_ptr<Simulation>> sims;
  std::vector<RenderRun> runs;
  if (compare.empty()) {
    sims.push_back(std::make_unique<Simulation>(make_simulation(*scene)));
    runs.push_back({sims.back().get(), run.steps_per_frame, {}});
  }
  for (const Method* m : compare) {
    SceneDef with = *scene;
    if (auto e = apply_method(*m, with, true); !e.empty())
      return fail(exit_code::kBadInput, "--compare: " + std::string(m->name) + ": " + e);
    sims.push_back(std::make_unique<Simulation>(make_simulation(with)));
    runs.push_back({sims.back().get(), run.steps_per_frame * m->substeps, {m->name, m->label}});
  }
  const Simulation& sim = *sims.front();
  if (opt.select_triangle >= sim.mesh.triangle_count())
    return fail(exit_code::kBadInput,
                "--select-triangle: " + std::to_string(opt.select_triangle) +
                    " is out of range: the scene has " + std::to_string(sim.mesh.triangle_count()) +
                    " triangles, 0.." + std::to_string(sim.mesh.triangle_count() - 1));
  OutputDirectory out_dir;
  if (auto e = out_dir.open(opt.out, opt.force)) return fail(e.exit_code, e.message);

  auto context = render::OffscreenContext::create(&error);
  if (!context) return fail(exit_code::kOutputFailed, "offscreen rendering: " + error);
  const int view_width = width / static_cast<int>(runs.size());
  auto renderer = render::Renderer::create(context->get_proc_address(), view_width, height, &error);
  if (!renderer) return fail(exit_code::kOutputFailed, "offscreen rendering: " + error);

  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  render::FrameWriter writer(opt.writer_threads, opt.png_level);
  const RenderedFrames done = render_frames(runs, *renderer, writer, run, elapsed);
  const std::string write_error = writer.finish();
  const double render_seconds = elapsed();
  if (!write_error.empty()) return fail(exit_code::kOutputFailed, write_error);
  const auto failed = [](const RunOutcome& r) { return r.failure.status != StepStatus::Ok; };
  const bool any_failed = std::any_of(done.runs.begin(), done.runs.end(), failed);

  std::string movie;
  const std::string movie_path = opt.out + (opt.gif ? "/movie.gif" : "/movie.mp4");
  bool movie_stopped = false;  // interrupted while ffmpeg ran
  for (const bool gif : {false, true}) {
    if (!(gif ? opt.gif : opt.mp4)) continue;
    // (A side by side shows a failed side's mark: that movie is what the comparison is for.)
    if ((compare.empty() && any_failed) || interrupted() || done.frames == 0) break;
    const std::string path = opt.out + (gif ? "/movie.gif" : "/movie.mp4");
    Progress progress(done.frames);
    const auto on_frame = [&](int n) { progress.encoding(path, n, elapsed()); };
    bool made = false;
    const std::string e = make_movie(ffmpeg, opt.out, done.frames, fps, gif, on_frame, &made);
    progress.clear();
    if (!e.empty()) return fail(exit_code::kOutputFailed, e);
    if (made) movie += ", " + path;
    movie_stopped = movie_stopped || !made;
  }
  const double seconds = elapsed();  // the movie's encoding included
  char rate_text[32], encode_text[32];
  std::snprintf(rate_text, sizeof rate_text, "%.4g", fps);
  std::snprintf(encode_text, sizeof encode_text, "%.1f s", seconds - render_seconds);
  // det F as `invfree simulate` gives it: over every state of the run, not only the frames'.
  const auto det_range = [&](const RunOutcome& r, const Simulation& s) {
    if (s.mesh.triangle_count() == 0) return std::string("no triangles");
    return "det F in [" + det_text(r.det_lo) + ", " + det_text(r.det_hi) + "] over steps 0.." +
           std::to_string(s.step_count);
  };
  const std::string movie_note =
      movie.empty() ? ""
                    : std::string("; movie: ") + rate_text + " frames/s, " +
                          std::to_string(run.steps_per_frame) + " step(s)/frame, encoded in " +
                          encode_text;
  double t_end = 0.0;  // the furthest run's time
  for (const auto& s : sims) t_end = std::max(t_end, s->time);
  std::printf("%s: %d frames %dx%d in %s/ (%s..%s%s), ", sim.scene.name.c_str(), done.frames,
              width, height, opt.out.c_str(), frame_name(0).c_str(),
              frame_name(std::max(done.frames - 1, 0)).c_str(), movie.c_str());
  if (compare.empty())
    std::printf("%ld steps, t = %.3f s, %.1f s, %.1f frames/s, %s%s\n", sim.step_count, sim.time,
                seconds, render_seconds > 0 ? done.frames / render_seconds : 0.0,
                det_range(done.runs[0], sim).c_str(), movie_note.c_str());
  else
    std::printf("%s (left) beside %s (right), t = %.3f s, %.1f s, %.1f frames/s%s\n",
                compare[0]->name, compare[1]->name, t_end, seconds,
                render_seconds > 0 ? done.frames / render_seconds : 0.0, movie_note.c_str());
  for (size_t i = 0; i < compare.size(); ++i) {  // each side's run
    const RunOutcome& r = done.runs[i];
    const Simulation& s = *sims[i];
    std::printf("render: %s %s: %ld steps, t = %.3f s, %s%s\n", i == 0 ? "left" : "right",
                compare[i]->name, s.step_count, s.time, det_range(r, s).c_str(),
                failed(r) ? ("; FAILED at step " + std::to_string(s.step_count + 1) + ": " +
                             step_status_name(r.failure.status) + ": " + r.failure.message +
                             " (its view keeps its last good state, marked)")
                                .c_str()
                          : "");
  }
  if (!refined.empty()) std::printf("render: %s\n", refined.c_str());
  if (opt.frames == 0 && !interrupted() && (!compare.empty() || !any_failed)) {
    // Ended by itself: every run failed or settled, or the limit with one still moving.
    const bool moving = std::any_of(done.runs.begin(), done.runs.end(), [&](const RunOutcome& r) {
      return !failed(r) && std::isnan(r.settled_since);
    });
    double settled = 0.0;
    for (const RunOutcome& r : done.runs)
      if (!failed(r)) settled = std::max(settled, r.settled_since);
    if (!moving && compare.empty())
      std::printf("render: ended %.2f s after nothing moved any more (t = %.2f s; no node "
                  "faster than %.0f%% of the body's size per second, the ceiling at rest); "
                  "--frames N renders N frames\n",
                  kSettledHold, settled, 100.0 * kSettledSpeed);
    else if (!moving)
      std::printf("render: ended when each side had failed or stopped moving (the last at t = "
                  "%.2f s, held %.2f s); --frames N renders N frames\n",
                  settled, kSettledHold);
    else
      std::printf("render: stopped at the limit of %d frames (t = %.2f s) while the bodies still "
                  "moved; --frames N renders N frames\n",
                  done.frames, t_end);
  }
  if (compare.empty() && any_failed)
    return fail(exit_code::kRunFailed, "step " + std::to_string(sim.step_count + 1) +
                                           " failed: " + step_status_name(done.runs[0].failure.status) +
                                           ": " + done.runs[0].failure.message);
  if (movie_stopped)
    return fail(interrupted_exit_code(), "interrupted while making " + movie_path +
                                             " (none written); the " + std::to_string(done.frames) +
                                             " frames are complete");
  if (interrupted() && movie_wanted)
    return fail(interrupted_exit_code(),
                "interrupted after frame " + std::to_string(done.frames) +
                    "; the frames written are complete, no movie was made (from them: ffmpeg "
                    "-framerate " +
                    rate_text + " -i " + opt.out + "/frame_%06d.png -pix_fmt yuv420p " + opt.out +
                    "/movie.mp4)");
  if (interrupted())
    return fail(interrupted_exit_code(), "interrupted after frame " + std::to_string(done.frames) +
                                             "; the frames written are complete");
  return exit_code::kOk;
}

}  // namespace

void register_render_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<RenderOptions>(app, exit_code, "render",
                                               "render a scene offscreen (no display needed) to "
                                               "DIR/frame_000000.png ... (frame 0: the initial "
                                               "state)",
                                               run_render);
  opt.scene.add_to(cmd);
  cmd->add_option("--frames", opt.frames,
                  "number of frames, the initial state included (default: until nothing has "
                  "moved for half a second of simulated time -- no node faster than 1% of the "
                  "body's size per second, the ceiling at rest -- at most ten seconds of "
                  "simulated time, 300 to 1000 frames)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--paths", opt.paths,
                  "draw each body's path (its centroid at every frame) and where it is now: auto "
                  "(default: in scenes of several bodies, where it shows what they did to each "
                  "other, e.g. stack-friction's top square dragging the bottom one), on or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd->add_option("--min-n-seg", opt.min_n_seg,
                  "mesh a square body of the scene's own elasticity at least this fine for the "
                  "picture, unless --set mesh.n_seg is given (0: the scene's mesh; the course's "
                  "mass-spring grids and reduced bases are kept)")
      ->capture_default_str()
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--steps-per-frame", opt.steps_per_frame,
                  "time steps between frames (default 1; with --mp4 or --gif and no --fps, the "
                  "lecture default: the steps that make real-time playback closest to 30 "
                  "frames/s, e.g. 3 for compress, whose h is 1/100 of a second: 33.3 frames/s)")
      ->check(CLI::Range(1, kMaxStepsPerFrame));
  add_output_directory_option(cmd, opt.out,
                              "output directory (must be empty or new, see --force; locked while "
                              "the run writes, see docs/outputs.md)");
  cmd->add_option("--size", opt.size,
                  "frame size in pixels (default 1280x720; with --compare 1920x1080: two views "
                  "of 960x1080)")
      ->type_name("WxH");
  cmd->add_option("--compare", opt.compare,
                  "render the scene twice in lockstep, side by side: method A on the left, B on "
                  "the right (names of `invfree stability --methods`, e.g. "
                  "lecture,no-projection), each view titled with its method, one colour scale "
                  "(det F, psi or stress) and one camera for both; a side that fails keeps its "
                  "last good state, marked, while the other goes on (and the exit status stays "
                  "0: the failure is what is shown)")
      ->type_name("A,B");
  cmd->add_flag("--no-edges", opt.no_edges,
                "do not draw the triangle edges (they are left out anyway where closer than 6 "
                "pixels)");
  cmd->add_option("--color-range", opt.color_range,
                  "det F colour scale: run (default: automatic, from the frames so far: only "
                  "widens), fixed (0.25..4) or frame (automatic per frame); automatic ranges are symmetric in "
                  "log det F around 1. psi and stress have no fixed scale: frame gives each "
                  "frame its own, fixed and run the widest so far")
      ->capture_default_str()
      ->check(CLI::IsMember({"fixed", "run", "frame"}));
  std::vector<std::string> fields;
  for (const auto& f : kTriangleFieldNames) fields.emplace_back(f.name);
  cmd->add_option("--color-by", opt.color_by,
                  "what colours the triangles: det-f (area now / area at rest), psi (energy "
                  "density, Pa, log scale), stress (the principal Cauchy stress of largest "
                  "magnitude, signed: tension red, compression blue, Pa) or clamped (how many of "
                  "dP/dF's four eigenvalues the PSD projection sets to 0: where Newton's Hessian "
                  "departs from the true one); psi and stress are scaled from the frames (see "
                  "--color-range, docs/rendering.md)")
      ->capture_default_str()
      ->check(CLI::IsMember(fields));
  cmd->add_flag("--stress-glyphs", opt.stress_glyphs,
                "draw a cross of principal stress strokes per triangle (length by magnitude, "
                "tension red, compression blue); where triangles are smaller than 28 pixels (at "
                "1280x720), one per 28-pixel cell");
  cmd->add_option("--select-triangle", opt.select_triangle,
                  "outline triangle T (as `invfree inspect --triangle T` reports it)")
      ->type_name("T")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  cmd->add_option("--camera", opt.camera,
                  "follow (default: frames the bodies, moving smoothly) or fixed (the scene's "
                  "whole stage, the same every frame)")
      ->capture_default_str()
      ->check(CLI::IsMember({"fixed", "follow"}));
  cmd->add_flag("--mp4", opt.mp4, "also write DIR/movie.mp4 (H.264, yuv420p) with ffmpeg");
  cmd->add_flag("--gif", opt.gif,
                "also write DIR/movie.gif with ffmpeg (one palette for the clip), for slides that "
                "cannot play video");
  cmd->add_option("--fps", opt.fps,
                  "frame rate of the movie (default: real time, 1 / (h * steps-per-frame))")
      ->check(finite_range(kMinFps, kMaxFps));
  cmd->add_option("--png-level", opt.png_level,
                  "PNG compression level (stb_image_write; 1 is fastest)")
      ->capture_default_str()
      ->check(CLI::Range(1, 9));
  cmd->add_flag("--force", opt.force,
                "write into a non-empty output directory: this run's frames replace those of the "
                "same number, later ones stay and are not in movie.mp4");
}

}  // namespace invfree
