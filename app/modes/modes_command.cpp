// `invfree modes`: the linear modal analysis of a scene (core/modal/modal_analysis.h, the
// course's chapter 9 linear.py): the `count` smallest eigenpairs of K phi = lambda M phi
// with the scene's [fixed] degrees of freedom eliminated. Writes DIR/modes.csv (mode,
// eigenvalue, omega, frequency), DIR/mode_01.png ... (each mode shape: the rest mesh
// displaced by the mode scaled to --scale of the body's size, drawn by the offscreen
// renderer, its number and frequency as the panel's title) and with --mp4 DIR/modes.mp4
// (each mode in turn oscillating as sin(omega t) over two periods, slowed to one period
// per second of video, through ffmpeg as `render --mp4`). docs/modes.md.
// Everything is checked and solved before the first file is written; each file is
// written atomically (app/output_files.h), the movie's frames in a temporary folder that
// is removed.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "app/cli_checks.h"
#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/format_number.h"
#include "app/interrupt.h"
#include "app/movie.h"
#include "app/output_files.h"
#include "app/render/frame_writer.h"
#include "app/render/offscreen_context.h"
#include "app/render/renderer.h"
#include "app/render/view_choices.h"
#include "app/scene_options.h"
#include "modal/modal_analysis.h"
#include "scene/scene_mesh.h"

namespace invfree {

namespace {

struct ModesOptions {
  SceneOptions scene;
  int count = 8;
  std::string element;  // "": the scene's [modes] element
  std::string out = "modes";
  std::string size = "960x720";
  double scale = 0.15;
  bool mp4 = false;
  bool force = false;
};

// The movie: each mode for two periods at 30 frames per period, played at 30 frames/s.
constexpr int kFramesPerPeriod = 30, kPeriodsPerMode = 2;
constexpr double kMovieFps = 30.0;

// "mode_01.png": at least two digits, as many as the count needs.
std::string mode_file(int mode, int count) {
  const int digits = std::max(2, static_cast<int>(std::to_string(count).size()));
  char buf[32];
  std::snprintf(buf, sizeof buf, "mode_%0*d.png", digits, mode);
  return buf;
}

std::string modes_csv(const ModalResult& r) {
  std::string csv = "mode,eigenvalue,omega,frequency\n";
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    const double omega = angular_frequency(r.eigenvalues[k]);
    char row[160];
    std::snprintf(row, sizeof row, "%d,%.17g,%.17g,%.17g\n", static_cast<int>(k + 1),
                  r.eigenvalues[k], omega, omega / (2 * std::numbers::pi));
    csv += row;
  }
  return csv;
}

// What every picture shares: the rest mesh, the scene as drawn, the mode shapes scaled so
// that their largest nodal displacement is `amplitude` metres, and a camera that holds
// every drawn shape at either extreme.
struct ModePictures {
  SceneDef scene;  // as drawn: linear model, no planes
  Mesh mesh;
  std::vector<VecX> displacement;  // per mode, 2N, at sin = 1
  std::vector<double> frequency;   // Hz
  render::Camera camera;
  bool edges = true;
};

ModePictures mode_pictures(const SceneDef& scene, const ModalResult& r, double scale,
                           const render::FrameLayout& layout) {
  ModePictures p;
  p.scene = scene;
  p.scene.model = Model::Linear;  // the panel names the law the modes come from
  p.scene.has_ground = p.scene.has_ceiling = false;
  p.mesh = scene_mesh(scene);
  Eigen::AlignedBox2d rest;
  for (const Vec2& x : p.mesh.rest) rest.extend(x);
  const double amplitude = scale * rest.sizes().maxCoeff();
  Eigen::AlignedBox2d all = rest;
  for (Eigen::Index k = 0; k < r.shapes.cols(); ++k) {
    const double largest = r.shapes.col(k).cwiseAbs().maxCoeff();
    p.displacement.push_back(r.shapes.col(k) * (largest > 0 ? amplitude / largest : 0.0));
    for (int i = 0; i < p.mesh.node_count(); ++i)
      for (const double s : {-1.0, 1.0})
        all.extend(p.mesh.rest[i] + s * p.displacement.back().segment<2>(2 * i));
    p.frequency.push_back(angular_frequency(r.eigenvalues[k]) / (2 * std::numbers::pi));
  }
  const Vec2 margin = Vec2::Constant(0.04 * all.sizes().maxCoeff());
  p.camera = render::fit_camera({all.min().x() - margin.x(), all.max().x() + margin.x(),
                                 all.min().y() - margin.y(), all.max().y() + margin.y()},
                                layout.plot);
  double edge_sum = 0.0;
  for (const auto& t : p.mesh.triangles)
    for (int k = 0; k < 3; ++k)
      edge_sum += (p.mesh.rest[t[(k + 1) % 3]] - p.mesh.rest[t[k]]).norm();
  const double mean_edge = edge_sum / (3.0 * std::max<size_t>(p.mesh.triangles.size(), 1));
  p.edges = mean_edge * p.camera.pixels_per_metre >= render::kMinEdgeSpacingPixels;
  return p;
}

// Mode k (0-based) displaced by `phase` (sin(omega t)) of its amplitude, at time t.
render::FrameState mode_frame(const ModePictures& p, int k, double phase, double t, long step) {
  render::FrameState f;
  f.scene = p.scene;
  char title[96];
  std::snprintf(title, sizeof title, "mode %d · %.4g Hz", k + 1, p.frequency[k]);
  f.scene.name = title;
  f.x.resize(2 * p.mesh.node_count());
  for (int i = 0; i < p.mesh.node_count(); ++i)
    f.x.segment<2>(2 * i) = p.mesh.rest[i] + phase * p.displacement[k].segment<2>(2 * i);
  f.triangles = p.mesh.triangles;
  // Coloured by 1 + tr(eps), the small-strain area change (what det F linearises to): the
  // drawn mesh's own det F adds the linearised rotation's spurious stretch (1 + theta^2),
  // which would paint a bending mode red all over instead of its tension and compression.
  f.det_f.reserve(p.mesh.triangles.size());
  for (size_t t = 0; t < p.mesh.triangles.size(); ++t) {
    const auto& v = p.mesh.triangles[t];
    const VecX& u = p.displacement[k];
    Mat2 du;
    du << u.segment<2>(2 * v[1]) - u.segment<2>(2 * v[0]),
        u.segment<2>(2 * v[2]) - u.segment<2>(2 * v[0]);
    f.det_f.push_back(1.0 + phase * (du * p.mesh.rest_shape_inverse[t]).trace());
  }
  f.color_by = TriangleField::DetF;
  f.field = f.det_f;
  f.time = t;
  f.step = step;
  return f;
}

// The det F colour range of mode k: from its two extremes, so that a mode's frames share it.
void mode_color_range(const ModePictures& p, int k, render::DrawOptions* draw) {
  render::ColorRangeTracker range;
  range.mode = render::ColorRangeMode::Run;
  for (const double s : {-1.0, 1.0}) {
    const render::FrameState f = mode_frame(p, k, s, 0.0, 0);
    const auto [lo, hi] = std::minmax_element(f.det_f.begin(), f.det_f.end());
    range.apply(*lo, *hi, draw);
  }
}

int run_modes(const ModesOptions& opt) {
  std::string error;
  auto scene = opt.scene.resolve(&error);
  if (!scene) return fail(exit_code::kBadInput, error);
  int width = 0, height = 0;
  if (auto e = parse_frame_size(opt.size, &width, &height); !e.empty())
    return fail(exit_code::kBadInput, e);
  const ModalElement element = opt.element.empty()
                                   ? scene->modes_element
                                   : *enum_from_name(kModalElementNames, opt.element);
  const std::string element_name = enum_name(kModalElementNames, element);
  const ModalModel model = scene_modal_model(*scene, element, &error);
  if (!error.empty()) return fail(exit_code::kBadInput, scene->name + ": " + error);
  const int free = model.free_dof_count();
  if (opt.count >= free)
    return fail(exit_code::kBadInput,
                "--count " + std::to_string(opt.count) + ": " + scene->name + " has " +
                    std::to_string(free) + " free degrees of freedom (" + element_name +
                    " elements, [fixed] ones eliminated); --count must be 1 to " +
                    std::to_string(free - 1));
  std::string ffmpeg;
  if (opt.mp4) {
    ffmpeg = find_on_path("ffmpeg");
    if (ffmpeg.empty())
      return fail(exit_code::kBadInput,
                  "--mp4 needs ffmpeg, which is not on PATH (install it: sudo apt-get install "
                  "ffmpeg; or leave out --mp4 to write the CSV and the PNGs only)");
  }
  OutputDirectory out_dir;
  if (auto e = out_dir.open(opt.out, opt.force)) return fail(e.exit_code, e.message);

  const ModalResult result = modal_analysis(model, opt.count);
  if (!result.error.empty())
    return fail(exit_code::kRunFailed, scene->name + ": modal analysis failed: " + result.error);

  auto context = render::OffscreenContext::create(&error);
  if (!context) return fail(exit_code::kOutputFailed, "offscreen rendering: " + error);
  auto renderer = render::Renderer::create(context->get_proc_address(), width, height, &error);
  if (!renderer) return fail(exit_code::kOutputFailed, "offscreen rendering: " + error);
  const ModePictures pictures = mode_pictures(*scene, result, opt.scale, renderer->layout());
  render::DrawOptions draw;
  draw.camera = pictures.camera;
  draw.edges = pictures.edges;

  // The stills: each mode at its largest displacement, sin(omega t) = 1 at t = pi / 2 omega.
  std::vector<std::uint8_t> pixels;
  for (int k = 0; k < opt.count; ++k) {
    if (interrupted())
      return fail(interrupted_exit_code(), "interrupted; the files written are complete");
    const double omega = angular_frequency(result.eigenvalues[k]);
    mode_color_range(pictures, k, &draw);
    renderer->draw(
        mode_frame(pictures, k, 1.0, omega > 0 ? std::numbers::pi / (2 * omega) : 0.0, 0), draw);
    renderer->read_pixels(&pixels);
    const std::string path = opt.out + "/" + mode_file(k + 1, opt.count);
    if (std::string e = render::write_png_file(path, pixels.data(), width, height, 6); !e.empty())
      return fail(exit_code::kOutputFailed, e);
  }
  const std::string csv_path = opt.out + "/modes.csv";
  if (std::string e = write_file_atomically(csv_path, modes_csv(result)); !e.empty())
    return fail(exit_code::kOutputFailed, e);

  std::string movie;
  if (opt.mp4) {
    // The frames in a folder of their own inside DIR, removed whatever happens.
    const std::string frames_dir = opt.out + "/.modes-frames-" + std::to_string(::getpid());
    struct RemoveFolder {
      std::string path;
      ~RemoveFolder() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
      }
    } cleanup{frames_dir};
    std::error_code ec;
    std::filesystem::create_directory(frames_dir, ec);
    if (ec) return fail(exit_code::kOutputFailed, frames_dir + ": cannot create: " + ec.message());
    render::FrameWriter writer(1, 1);
    int frame = 0;
    for (int k = 0; k < opt.count && !interrupted(); ++k) {
      const double omega = angular_frequency(result.eigenvalues[k]);
      mode_color_range(pictures, k, &draw);
      for (int i = 0; i < kFramesPerPeriod * kPeriodsPerMode && !interrupted(); ++i, ++frame) {
        const double theta = 2 * std::numbers::pi * i / kFramesPerPeriod;
        renderer->draw(
            mode_frame(pictures, k, std::sin(theta), omega > 0 ? theta / omega : 0.0, frame), draw);
        std::vector<std::uint8_t> buffer = writer.take_buffer();
        renderer->read_pixels(&buffer);
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%06d.png", frame);
        if (!writer.submit(frames_dir + name, width, height, std::move(buffer))) break;
      }
    }
    if (std::string e = writer.finish(); !e.empty()) return fail(exit_code::kOutputFailed, e);
    if (interrupted())
      return fail(interrupted_exit_code(),
                  "interrupted while drawing the movie's frames; modes.csv and the mode PNGs are "
                  "complete, no movie was made");
    bool made = false;
    movie = opt.out + "/modes.mp4";
    if (std::string e = make_movie(
            ffmpeg, frames_dir, frame, kMovieFps, false, [](int) {}, &made, movie);
        !e.empty())
      return fail(exit_code::kOutputFailed, e);
    if (!made)
      return fail(interrupted_exit_code(), "interrupted while making " + movie +
                                               " (none written); modes.csv and the mode PNGs are "
                                               "complete");
  }

  // The table and the summary.
  const double rigid_below = 1e-8 * (-result.shift * 1e9);
  int rigid = 0;
  std::printf("%4s  %24s  %24s  %24s\n", "mode", "eigenvalue (1/s^2)", "omega (rad/s)",
              "frequency (Hz)");
  for (int k = 0; k < opt.count; ++k) {
    const double lambda = result.eigenvalues[k], omega = angular_frequency(lambda);
    const bool is_rigid = std::abs(lambda) < rigid_below;
    rigid += is_rigid;
    std::printf("%4d  %24.17g  %24.17g  %24.17g%s\n", k + 1, lambda, omega,
                omega / (2 * std::numbers::pi), is_rigid ? "  rigid" : "");
  }
  std::printf(
      "%s: %d modes (%s elements, %d free degrees of freedom%s), %s .. %s Hz; wrote %s, "
      "%s .. %s%s\n",
      scene->name.c_str(), opt.count, element_name.c_str(), free,
      rigid ? (", " + std::to_string(rigid) + " rigid (eigenvalue about 0)").c_str() : "",
      format_number(pictures.frequency.front(), "%.4g").c_str(),
      format_number(pictures.frequency.back(), "%.4g").c_str(), csv_path.c_str(),
      (opt.out + "/" + mode_file(1, opt.count)).c_str(), mode_file(opt.count, opt.count).c_str(),
      movie.empty() ? "" : (", " + movie).c_str());
  return exit_code::kOk;
}

}  // namespace

void register_modes_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<ModesOptions>(
      app, exit_code, "modes",
      "linear modal analysis of a scene (the course's chapter 9, linear.py): the smallest "
      "eigenvalues of K phi = lambda M phi with the [fixed] nodes held; write modes.csv and a "
      "PNG per mode shape",
      run_modes);
  opt.out = "modes";
  opt.scene.add_to(cmd);
  cmd->add_option("--count", opt.count,
                  "how many modes, the lowest first (fewer than the free degrees of freedom)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  std::vector<std::string> elements;
  for (const auto& e : kModalElementNames) elements.emplace_back(e.name);
  cmd->add_option("--element", opt.element,
                  "triangle: linear triangles on the scene's own mesh (any shape); quad: bilinear "
                  "quads (2x2 Gauss, as linear.py) from the mesh's triangle pairs, which must "
                  "form a structured grid (the square's, a grid mesh file); default: the "
                  "scene's [modes] element (triangle unless it says)")
      ->check(CLI::IsMember(elements));
  add_output_directory_option(cmd, opt.out,
                              "output directory for modes.csv, mode_01.png ... and modes.mp4 "
                              "(must be empty or new, see --force)");
  cmd->add_option("--size", opt.size, "picture size in pixels")
      ->type_name("WxH")
      ->capture_default_str();
  cmd->add_option("--scale", opt.scale,
                  "the drawn mode's largest displacement, as a fraction of the body's size "
                  "(the longer side of its rest bounding box; linear.py's 0.15)")
      ->capture_default_str()
      ->check(finite_range(1e-6, 10.0));
  cmd->add_flag("--mp4", opt.mp4,
                "also write DIR/modes.mp4 with ffmpeg: each mode in turn oscillating as "
                "sin(omega t) for two periods, one period per second of video");
  add_force_option(cmd, opt.force, "write into a non-empty output directory");
}

}  // namespace invfree
