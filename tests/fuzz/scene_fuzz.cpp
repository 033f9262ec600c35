// libFuzzer target over the scene parser and the --set overrides (scene_io/scene_file.h).
// Input: TOML text, optionally followed by a line "%%" and then one --set assignment per
// line. Without "%%" the whole input is also tried as one assignment, so every seed
// exercises both entry points. Besides "no crash, no sanitizer report", it checks the
// contracts the tools rely on, and aborts (a finding) when one breaks:
//   - an override's error is one non-empty line starting with "--set "; a file's error is
//     one non-empty line per independent mistake (all are reported at once), each starting
//     with the file's name;
//   - a loaded scene passes validate_scene and survives scene_to_toml -> parse unchanged;
//   - a rejected override leaves the scene untouched, an accepted one leaves it valid.
// Built two ways: with clang -fsanitize=fuzzer (the fuzzer), and as a plain program that
// replays files (tests/fuzz/replay_main.cpp), so every stored input is a regression test.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <string_view>

#include "scene/scene.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"

namespace {

void require(bool ok, const char* what, const std::string& detail) {
  if (ok) return;
  std::fprintf(stderr, "scene_fuzz: contract broken: %s\n%s\n", what, detail.c_str());
  std::abort();
}

void check_error(const std::string& error, std::string_view prefix, bool one_line) {
  require(!error.empty(), "empty error", "");
  require(error.find('\r') == std::string::npos, "error has a carriage return", error);
  require(!one_line || error.find('\n') == std::string::npos, "error is not one line", error);
  for (size_t start = 0; start <= error.size();) {
    const size_t end = std::min(error.find('\n', start), error.size());
    const std::string_view line = std::string_view(error).substr(start, end - start);
    require(!line.empty(), "error has an empty line", error);
    require(line.substr(0, prefix.size()) == prefix, "error line does not start with its source",
            error);
    start = end + 1;
  }
}

void check_scene(const invfree::SceneDef& scene) {
  require(invfree::validate_scene(scene).empty(), "accepted scene fails validation",
          invfree::validate_scene(scene));
  const std::string text = invfree::scene_to_toml(scene);
  const invfree::SceneLoad back = invfree::parse_scene_toml(text, "roundtrip.toml");
  require(back.scene.has_value(), "scene_to_toml output does not load", back.error + "\n" + text);
  require(*back.scene == scene, "scene_to_toml does not round-trip", text);
}

void check_override(const invfree::SceneDef& base, std::string_view assignment) {
  invfree::SceneDef scene = base;
  const std::string error = invfree::apply_override(scene, assignment);
  if (error.empty()) {
    require(invfree::validate_scene(scene).empty(), "accepted override leaves an invalid scene",
            std::string(assignment));
  } else {
    check_error(error, "--set ", true);
    require(scene == base, "rejected override changed the scene", std::string(assignment));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const size_t split = input.find("\n%%\n");
  const std::string_view toml = input.substr(0, split);

  const invfree::SceneLoad load = invfree::parse_scene_toml(toml, "fuzz.toml");
  invfree::SceneDef base = *invfree::load_builtin_scene("compress").scene;
  if (load.scene) {
    check_scene(*load.scene);
    base = *load.scene;
  } else {
    check_error(load.error, "fuzz.toml", false);
  }

  if (split == std::string_view::npos) {
    if (size <= 4096) check_override(base, input);
    return 0;
  }
  std::string_view rest = input.substr(split + 4);
  for (int lines = 0; !rest.empty() && lines < 64; ++lines) {
    const size_t end = rest.find('\n');
    check_override(base, rest.substr(0, end));
    invfree::SceneDef next = base;
    if (invfree::apply_override(next, rest.substr(0, end)).empty())
      base = next;  // overrides accumulate
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
  }
  return 0;
}
