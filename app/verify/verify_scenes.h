// The benchmark scenes of `invfree verify`, assets/scenes/verify/*.toml, embedded in the
// program at build time (app/verify/CMakeLists.txt), so the command needs no asset path and
// `invfree simulate --scene assets/scenes/verify/NAME.toml` runs the very same scene. They
// are not built-in scenes (`--scene NAME` does not offer them).
#pragma once

#include <span>

#include "scene_io/builtin_scenes.h"

namespace invfree {

// Every file of assets/scenes/verify/, in the order of their names.
std::span<const EmbeddedScene> verify_scene_files();

}  // namespace invfree
