// Loading the files that shapes name (issue 27): for the scene's [mesh] and each [[body]]
// whose shape is "svg" or "mesh", the file is read, parsed (scene_io/svg_outline.h,
// scene_io/mesh_file.h) and kept in ShapeFile `loaded`, so the core never opens a file. A
// scene file on disk finds its shape files on disk, relative to its own folder; a scene
// embedded in the program (scene_io/builtin_scenes.h, source "assets/scenes/NAME.toml")
// finds them among the files of assets/shapes/, embedded the same way, by their path
// relative to assets/scenes/ ("../shapes/bunny.svg"); so does a scene on disk whose file is
// not there (a built-in scene written out by scene_to_toml and read back elsewhere).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace invfree::scene_io {

// A shape file larger than this is refused before it is read.
inline constexpr std::uintmax_t kMaxShapeFileBytes = 64u << 20;  // 64 MiB

struct EmbeddedShapeFile {
  std::string_view path;  // relative to assets/, e.g. "shapes/bunny.svg"
  std::string_view text;
};
// Every file of assets/shapes/, by path.
std::span<const EmbeddedShapeFile> embedded_shape_files();

// Reads and parses every shape file of the scene: scene.shape (key "mesh.file") when its kind
// is svg or mesh and the scene has no [[body]] or a body takes the file from it, and each
// body whose shape (its own or the scene's) is svg or mesh (key "body.file", the file, path_id
// and scale its own or the scene's), filling their `loaded`. `source` is the scene file's
// path as load_scene and parse_scene_toml name it. Returns "" or a one-line error without
// the scene's name, e.g. "mesh.file: cannot open 'x.svg' (No such file or directory)" or
// "body.file: bunny.svg has no closed path (in [[body]] 2)"; then *body (when given) is the
// 0-based index of the body at fault, -1 for [mesh].
std::string load_shape_files(SceneDef& scene, const std::string& source, int* body = nullptr);

// One file's text, parsed as `kind` (svg; mesh: by the extension of `name`, .msh or .obj).
// Returns "" or the error (without the key).
std::string parse_shape_text(ShapeKind kind, std::string_view text, const std::string& name,
                             const std::string& path_id, double scale, ShapeFile& out);

}  // namespace invfree::scene_io
