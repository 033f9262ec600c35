// `invfree live`: the interactive classroom window (app/live/live_app.h). Also what plain
// `invfree` runs when a display is available. Without a display it prints one line
// suggesting `invfree render` or xvfb-run and exits with code 4 (the window, its output,
// could not be opened).
#include <cstdio>

#include "app/cli_checks.h"
#include "app/command.h"
#include "app/commands.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/live/course.h"
#include "app/live/key_bindings.h"
#include "app/live/live_app.h"
#include "app/output_files.h"
#include "app/render/projector_mesh.h"
#include "app/scene_options.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "triangle_fields.h"

namespace invfree {

namespace {

struct LiveCommandOptions {
  SceneOptions scene;  // the one shown first; the --set overrides apply to it
  std::vector<std::string> scene_files;
  std::string size = "1280x720";
  std::string det_f_panel = "beside";  // beside | over | hidden
  // The defaults are for a projector (docs/live.md), as `invfree render`'s:
  // colours scaled to the run, a camera on the bodies, a mesh fine enough for a gradient.
  std::string color_range = "run";     // render::parse_color_range_mode
  std::string camera = "follow";       // follow | fixed
  int min_n_seg = render::kProjectorMinSegments;  // each square's n_seg raised to this
  std::string color_by = "det-f";      // kTriangleFieldNames
  live::LiveOptions live;
};

// The scene picker: every built-in scene (the course's first, in chapter order), then the files
// named on the command line; the
// --scene one is selected and gets the --set overrides.
int build_scenes(const LiveCommandOptions& opt, live::LiveOptions* out) {
  std::vector<std::string> names;
  for (const auto& e : builtin_scenes()) names.emplace_back(e.name);
  live::put_course_first(names);
  auto add = [&](const std::string& n) {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return static_cast<int>(i);
    names.push_back(n);
    return static_cast<int>(names.size()) - 1;
  };
  for (const auto& f : opt.scene_files) add(f);
  const int selected = add(opt.scene.scene);
  out->scenes.clear();
  for (int i = 0; i < static_cast<int>(names.size()); ++i) {
    SceneLoad load;
    if (i == selected)
      load.scene = opt.scene.resolve(&load.error);
    else
      load = load_scene(names[i]);
    if (!load.scene) return fail(exit_code::kBadInput, load.error);
    out->scenes.push_back({names[i], *load.scene});
  }
  out->selected = selected;
  return exit_code::kOk;
}

int run_live_command(const LiveCommandOptions& opt) {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(opt.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 320 || h < 240 ||
      w > 8192 || h > 8192)
    return fail(exit_code::kBadInput,
                "--size " + opt.size + ": expected WIDTHxHEIGHT between 320x240 and 8192x8192");
  live::LiveOptions lo = opt.live;
  lo.width = w;
  lo.height = h;
  if (int code = build_scenes(opt, &lo); code != exit_code::kOk) return code;
  // Outputs are checked before the window opens, by the rules `render` follows
  // (docs/outputs.md): a file that cannot be written, an existing --screenshot FILE or a
  // non-empty --record DIR without --force (exit 2), and so on.
  if (auto e = check_outputs_apart({{"--screenshot", lo.screenshot_file}},
                                   {{"--record", lo.record_dir}}))
    return fail(e.exit_code, e.message);
  if (!lo.screenshot_file.empty()) {
    std::vector<std::string> inputs = opt.scene.input_files();
    inputs.insert(inputs.end(), opt.scene_files.begin(), opt.scene_files.end());
    if (auto e = check_output_files({lo.screenshot_file}, inputs, lo.record_force))
      return fail(e.exit_code, e.message);
  }
  if (!lo.record_dir.empty()) {
    OutputDirectory probe;
    if (auto e = probe.open(lo.record_dir, lo.record_force)) return fail(e.exit_code, e.message);
  }
  lo.det_f_panel = opt.det_f_panel == "over"     ? render::PanelMode::Overlay
                   : opt.det_f_panel == "hidden" ? render::PanelMode::Hidden
                                                 : render::PanelMode::Side;
  lo.color_range = *render::parse_color_range_mode(opt.color_range);
  lo.follow_camera = opt.camera == "follow";
  lo.min_n_seg = opt.min_n_seg;
  // The starting scene's own mesh where the command line sets it, or names inspect's
  // triangle (--select-triangle T), as render does.
  lo.keep_selected_mesh =
      lo.select_triangle >= 0 || render::overrides_set_n_seg(opt.scene.overrides);
  lo.color_by = *enum_from_name(kTriangleFieldNames, opt.color_by);
  if (lo.select_triangle >= 0) {
    // Checked before the window opens, as the outputs are: an index off the mesh is a
    // mistake in the command line (the mesh is built once here to count its triangles).
    const int n = make_simulation(lo.scenes[lo.selected].scene).mesh.triangle_count();
    if (lo.select_triangle >= n)
      return fail(exit_code::kBadInput, "--select-triangle " + std::to_string(lo.select_triangle) +
                                            ": the scene's mesh has " + std::to_string(n) +
                                            " triangles (0 to " + std::to_string(n - 1) + ")");
  }
  // Scripted runs draw as fast as they can: no waiting for the screen's refresh.
  if (lo.frames > 0 || lo.bench) lo.vsync = false;
  lo.stop = [] { return interrupted(); };
  const int code = live::run_live(lo);
  if (code == exit_code::kOk && interrupted()) {
    return fail(interrupted_exit_code(),
                "live: interrupted; recordings and screenshots are complete");
  }
  return code;
}

}  // namespace

void register_live_command(CLI::App& app, int& exit_code) {
  auto [cmd, opt] = add_command<LiveCommandOptions>(
      app, exit_code, "live",
      "interactive window: the running simulation with sliders for mu and lambda (the default "
      "command when a display is available)",
      run_live_command);
  opt.scene.add_to(cmd, "scene to start with: built-in", "override a value of the starting scene");
  cmd->add_option("scene_files", opt.scene_files, "more TOML scene files for the scene picker")
      ->type_name("FILE ...");
  cmd->add_option("--frames", opt.live.frames,
                  "run this many frames, then exit (0: until the window is closed)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000000));
  cmd->add_option("--screenshot", opt.live.screenshot_file,
                  "save the last frame (window as shown) as a PNG")
      ->type_name("FILE")
      ->check(non_empty_path());
  cmd->add_option("--screenshot-dir", opt.live.screenshot_dir,
                  "where Ctrl+P saves invfree_NNNN.png and Record makes invfree_recording_NNNN/")
      ->capture_default_str()
      ->type_name("DIR")
      ->check(non_empty_path());
  cmd->add_option("--record", opt.live.record_dir,
                  "record from the start: DIR/frame_000000.png, ... (as `invfree render`); DIR "
                  "must be empty or new (see --force); checked before the window opens")
      ->type_name("DIR")
      ->check(non_empty_path());
  cmd->add_flag("--force", opt.live.record_force,
                "--screenshot over an existing file, --record into a non-empty directory: this "
                "run's frames replace those of the same number (as `invfree render --force`)");
  cmd->add_option("--ui-scale", opt.live.ui_scale,
                  "size of the panel's text and of the det F panel, 0.75 to 3 (default: from the "
                  "screen: 1 at 1280x720, 1.5 at 1920x1080; keys + and -)")
      ->check(finite_range(live::kMinUiScale, live::kMaxUiScale));
  cmd->add_option("--det-f-panel", opt.det_f_panel,
                  "the det F panel (colour bar): beside the picture, over it, or hidden (key D)")
      ->capture_default_str()
      ->check(CLI::IsMember({"beside", "over", "hidden"}));
  cmd->add_option("--color-range", opt.color_range,
                  "det F colours: run (default: automatic, from the bulk of det F over the run "
                  "so far; R and a new scene start it again), fixed (0.25..4) or frame "
                  "(automatic per frame) (key C)")
      ->capture_default_str()
      ->check(CLI::IsMember({"fixed", "run", "frame"}));
  cmd->add_option("--camera", opt.camera,
                  "follow (default: keeps the bodies framed, moving smoothly; a pan or zoom "
                  "takes over until F) or fixed (the scene's whole stage)")
      ->capture_default_str()
      ->check(CLI::IsMember({"fixed", "follow"}));
  cmd->add_option("--min-n-seg", opt.min_n_seg,
                  "mesh each scene's square body of its own elasticity at least this fine for "
                  "the picture (the n_seg slider shows it), unless --set mesh.n_seg is given (0: "
                  "the scenes' meshes; the course's mass-spring grids and reduced bases are "
                  "kept)")
      ->capture_default_str()
      ->check(CLI::Range(0, 4096));
  std::vector<std::string> fields;
  for (const auto& f : kTriangleFieldNames) fields.emplace_back(f.name);
  cmd->add_option("--color-by", opt.color_by,
                  "colour the triangles by det F, psi (energy density), stress (the principal "
                  "Cauchy stress of largest magnitude, signed) or clamped (eigenvalues of dP/dF "
                  "the projection clamps); also in the panel's view section")
      ->capture_default_str()
      ->check(CLI::IsMember(fields));
  cmd->add_flag("--stress-glyphs", opt.live.stress_glyphs,
                "draw each triangle's principal stresses as a pair of strokes");
  cmd->add_flag("--landscape", opt.live.show_landscape,
                "open the energy landscape's window (psi over the singular values)");
  cmd->add_option("--select-triangle", opt.live.select_triangle,
                  "inspect this triangle from the start (as a click on it does; Esc releases it)")
      ->type_name("T")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--bench", opt.live.bench,
                "print frames per second (with the simulation running) at the end");
  cmd->add_flag("--paused", opt.live.paused, "start paused");
  cmd->add_flag("--no-panel", opt.live.hide_panel, "start with the panel hidden (Tab shows it)");
  cmd->add_flag("--presentation", opt.live.presentation,
                "start in presentation mode: full screen, no panel, large readouts (P leaves)");
  cmd->add_option("--size", opt.size, "window size")->capture_default_str()->type_name("WxH");
  cmd->add_option("--steps-per-frame", opt.live.steps_per_frame, "time steps per displayed frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));
  cmd->add_option(
         "--max-n-seg", opt.live.max_segments,
         "the n_seg slider's maximum (default: the largest mesh measured at >= 30 frames/s)")
      ->capture_default_str()
      ->check(CLI::Range(2, 1024));
  cmd->footer("\n" + live::help_text() +
              "\nWithout a display: use `invfree render`, or run `xvfb-run -a invfree live ...`.");
}

int run_default_command() {
  if (!live::display_available()) {
    std::fprintf(
        stderr,
        "invfree: a subcommand is required when there is no display (plain `invfree` opens the "
        "live "
        "window only on one); try `invfree simulate` or `invfree render` (see invfree --help)\n");
    return exit_code::kBadInput;
  }
  LiveCommandOptions opt;
  return run_live_command(opt);
}

}  // namespace invfree
