// The files that shapes name: found (on disk, or among the embedded assets for an embedded
// scene), size-checked, read and parsed into ShapeFile.
#include "scene_io/shape_files.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "scene_io/builtin_scenes.h"
#include "scene_io/error_text.h"
#include "scene_io/mesh_file.h"
#include "scene_io/svg_outline.h"

namespace invfree::scene_io {

// Generated into the build directory by core/scene_io/CMakeLists.txt.
extern const EmbeddedShapeFile kEmbeddedShapeFiles[];
extern const std::size_t kEmbeddedShapeFileCount;

std::span<const EmbeddedShapeFile> embedded_shape_files() {
  return {kEmbeddedShapeFiles, kEmbeddedShapeFileCount};
}

namespace {

namespace fs = std::filesystem;

bool is_embedded_scene(const std::string& source) {
  for (auto scenes : {builtin_scenes(), stress_scene_files()})
    for (const auto& e : scenes)
      if (source == "assets/scenes/" + std::string(e.name) + ".toml") return true;
  return false;
}

std::string quote_path(const std::string& path) {
  std::string q(1, '\'');  // appended, not "'" + ...: GCC 12's -Wrestrict misfires on that
  q += printable(path, 200);
  q += '\'';
  return q;
}

// The text of `file` (as the scene gives it) into text, and the absolute path it was read
// from into *resolved (unchanged for an embedded asset); "" or the reason.
std::string read_shape_file(const std::string& file, const std::string& source, std::string& text,
                            std::string* resolved) {
  // The embedded asset that `file`, relative to assets/scenes/, names.
  auto embedded = [&]() -> const EmbeddedShapeFile* {
    const std::string key =
        (fs::path("scenes") / fs::path(file)).lexically_normal().generic_string();
    if (!fs::path(file).is_absolute())
      for (const auto& e : embedded_shape_files())
        if (e.path == key) return &e;
    return nullptr;
  };
  // A built-in scene's source is "assets/scenes/NAME.toml", which is also that scene's
  // path on disk from the repository's root: the embedded copy first, then the disk.
  if (is_embedded_scene(source))
    if (const EmbeddedShapeFile* e = embedded()) {
      text = std::string(e->text);
      return "";
    }
  const fs::path dir = fs::path(source).parent_path();
  const fs::path path = fs::path(file).is_absolute() || dir.empty() ? fs::path(file) : dir / file;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    // A built-in scene written out (scene_to_toml) and read from elsewhere still names
    // "../shapes/bunny.svg": the embedded copy serves when the disk has none.
    if (err == ENOENT)
      if (const EmbeddedShapeFile* e = embedded()) {
        text = std::string(e->text);
        return "";
      }
    return "cannot open " + quote_path(file) + " (" + std::strerror(err) + ")";
  }
  if (S_ISDIR(st.st_mode)) return "cannot open " + quote_path(file) + " (it is a directory)";
  if (!S_ISREG(st.st_mode)) return "cannot open " + quote_path(file) + " (not a regular file)";
  const std::string too_large = quote_path(file) + " is too large for a shape file (at most " +
                                std::to_string(kMaxShapeFileBytes) + " bytes)";
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxShapeFileBytes) return too_large;
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open " + quote_path(file) + " (" + std::strerror(errno) + ")";
  // In blocks, to at most one byte past the limit: the file may have grown since stat().
  text.clear();
  char block[1 << 16];
  while (in && text.size() <= kMaxShapeFileBytes) {
    in.read(block, sizeof block);
    text.append(block, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) return "cannot read " + quote_path(file);
  if (text.size() > kMaxShapeFileBytes) return too_large;
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (!ec) *resolved = absolute.lexically_normal().string();
  return "";
}

// Reads and parses `file` into out; on success *resolved becomes the path it was read from
// (so that a later --set, read from the current directory, finds the same file). "" or the
// reason.
std::string load_one(ShapeKind kind, std::string file, const std::string& path_id, double scale,
                     const std::string& source, ShapeFile& out, std::string* resolved) {
  if (file.empty())
    return std::string("missing: shape = \"") + shape_kind_name(kind) + "\" needs a file";
  std::string text, found = file;
  if (auto e = read_shape_file(file, source, text, &found); !e.empty()) return e;
  ShapeFile loaded;
  if (auto e = parse_shape_text(kind, text, printable(file, 200), path_id, scale, loaded);
      !e.empty())
    return e;
  out = std::move(loaded);
  *resolved = found;
  return "";
}

bool from_file(ShapeKind kind) {
  return kind == ShapeKind::Svg || kind == ShapeKind::MeshFile;
}

}  // namespace

std::string parse_shape_text(ShapeKind kind, std::string_view text, const std::string& name,
                             const std::string& path_id, double scale, ShapeFile& out) {
  if (kind == ShapeKind::Svg) return parse_svg_outline(text, name, path_id, scale, out);
  if (kind != ShapeKind::MeshFile)
    return name + ": shape " + shape_kind_name(kind) + " reads no file";
  std::string ext = fs::path(name).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".msh") return parse_msh(text, name, out);
  if (ext == ".obj") return parse_obj(text, name, out);
  return name + ": a mesh file must end in .msh (gmsh, ASCII) or .obj (Wavefront)";
}

std::string load_shape_files(SceneDef& scene, const std::string& source, int* body) {
  if (body) *body = -1;
  const ShapeDef& own = scene.shape;
  bool scene_file_used = scene.bodies.empty();
  for (const BodyDef& b : scene.bodies)
    scene_file_used = scene_file_used || (from_file(b.shape.value_or(own.kind)) && !b.file);
  if (from_file(own.kind) && scene_file_used)
    if (auto e = load_one(own.kind, own.file, own.path_id, own.scale, source, scene.shape.loaded,
                          &scene.shape.file);
        !e.empty())
      return "mesh.file: " + e;
  for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
    BodyDef& b = scene.bodies[k];
    const ShapeKind kind = b.shape.value_or(own.kind);
    if (!from_file(kind)) continue;
    std::string resolved;
    if (auto e = load_one(kind, b.file.value_or(own.file), b.path_id.value_or(own.path_id),
                          b.scale.value_or(own.scale), source, b.loaded, &resolved);
        !e.empty()) {
      if (body) *body = static_cast<int>(k);
      return "body.file: " + e + " (in [[body]] " + std::to_string(k + 1) + ")";
    }
    if (b.file) b.file = resolved;
  }
  return "";
}

}  // namespace invfree::scene_io
