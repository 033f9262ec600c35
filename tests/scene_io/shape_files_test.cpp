// Loading shape files (scene_io/shape_files.h): relative to the scene file on disk, from the
// embedded assets for an embedded scene, for [mesh] and each [[body]]; a missing file, a
// directory, a file past the size cap and an unknown mesh extension are one-line errors
// naming the key.
#include "scene_io/shape_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace invfree::scene_io {
namespace {

namespace fs = std::filesystem;

class ShapeFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("invfree_shape_files_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "shapes");
    write("shapes/sq.svg",
          "<svg xmlns=\"http://www.w3.org/2000/svg\"><path id=\"p\" d=\"M0 0 H100 V100 H0 Z\"/>"
          "<path id=\"q\" d=\"M200 0 H250 V50 H200 Z\"/></svg>");
    write("shapes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& rel, const std::string& text) {
    std::ofstream(dir_ / rel, std::ios::binary) << text;
  }
  std::string scene_path() const { return (dir_ / "scene.toml").string(); }
  fs::path dir_;
};

TEST_F(ShapeFiles, SceneShapeRelativeToTheSceneFile) {
  SceneDef s;
  s.shape.kind = ShapeKind::Svg;
  s.shape.file = "shapes/sq.svg";
  s.shape.scale = 0.01;
  ASSERT_EQ(load_shape_files(s, scene_path()), "");
  ASSERT_EQ(s.shape.loaded.loops.size(), 2u);
  s.shape.path_id = "p";
  ASSERT_EQ(load_shape_files(s, scene_path()), "");
  ASSERT_EQ(s.shape.loaded.loops.size(), 1u);
  EXPECT_NEAR(s.shape.loaded.loops[0][0].x(), -0.5, 1e-15);

  s.shape.kind = ShapeKind::MeshFile;
  s.shape.file = "shapes/tri.obj";
  ASSERT_EQ(load_shape_files(s, scene_path()), "");
  EXPECT_EQ(s.shape.loaded.nodes.size(), 3u);
  EXPECT_EQ(s.shape.loaded.triangles.size(), 1u);
}

TEST_F(ShapeFiles, SquareScenesReadNothing) {
  SceneDef s;
  s.shape.file = "nowhere.svg";  // not read: the shape is a square
  EXPECT_EQ(load_shape_files(s, scene_path()), "");
  EXPECT_EQ(s.shape.loaded, ShapeFile{});
}

TEST_F(ShapeFiles, OneLineErrorsNamingTheKey) {
  SceneDef s;
  s.shape.kind = ShapeKind::Svg;
  s.shape.file = "x.svg";
  EXPECT_EQ(load_shape_files(s, scene_path()),
            "mesh.file: cannot open 'x.svg' (No such file or directory)");
  s.shape.file = "shapes";
  EXPECT_EQ(load_shape_files(s, scene_path()),
            "mesh.file: cannot open 'shapes' (it is a directory)");
  s.shape.file = "";
  EXPECT_EQ(load_shape_files(s, scene_path()), "mesh.file: missing: shape = \"svg\" needs a file");
  s.shape.kind = ShapeKind::MeshFile;
  s.shape.file = "shapes/sq.svg";
  EXPECT_EQ(load_shape_files(s, scene_path()),
            "mesh.file: shapes/sq.svg: a mesh file must end in .msh (gmsh, ASCII) or .obj "
            "(Wavefront)");
  s.shape.kind = ShapeKind::Svg;
  s.shape.path_id = "nope";
  EXPECT_EQ(load_shape_files(s, scene_path()),
            "mesh.file: shapes/sq.svg has no element with id \"nope\"");
  write("shapes/open.svg", "<svg><path d=\"M0 0 L1 0 L1 1\"/></svg>");
  s.shape.file = "shapes/open.svg";
  s.shape.path_id = "";
  EXPECT_EQ(load_shape_files(s, scene_path()), "mesh.file: shapes/open.svg has no closed path");
}

TEST_F(ShapeFiles, FileLargerThanTheCapIsRefusedUnread) {
  { std::ofstream(dir_ / "big.msh") << "$MeshFormat\n"; }
  fs::resize_file(dir_ / "big.msh", kMaxShapeFileBytes + 1);  // sparse: nothing written
  SceneDef s;
  s.shape.kind = ShapeKind::MeshFile;
  s.shape.file = "big.msh";
  EXPECT_EQ(load_shape_files(s, scene_path()),
            "mesh.file: 'big.msh' is too large for a shape file (at most 67108864 bytes)");
}

TEST_F(ShapeFiles, BodiesTakeTheirOwnOrTheScenesKeys) {
  SceneDef s;
  s.shape.kind = ShapeKind::Svg;
  s.shape.file = "shapes/sq.svg";
  s.bodies.resize(3);
  s.bodies[0].path_id = "q";                // the scene's file, its own path
  s.bodies[1].shape = ShapeKind::MeshFile;  // its own kind and file
  s.bodies[1].file = "shapes/tri.obj";
  s.bodies[2].shape = ShapeKind::Square;  // reads nothing
  int body = 7;
  ASSERT_EQ(load_shape_files(s, scene_path(), &body), "");
  EXPECT_EQ(body, -1);
  EXPECT_EQ(s.bodies[0].loaded.loops.size(), 1u);
  EXPECT_EQ(s.bodies[1].loaded.triangles.size(), 1u);
  EXPECT_EQ(s.bodies[2].loaded, ShapeFile{});
  EXPECT_EQ(s.shape.loaded.loops.size(), 2u);  // body 1 takes the scene's file

  s.bodies[1].file = "shapes/none.obj";
  EXPECT_EQ(load_shape_files(s, scene_path(), &body),
            "body.file: cannot open 'shapes/none.obj' (No such file or directory) (in [[body]] 2)");
  EXPECT_EQ(body, 1);
  // The scene's own file is not needed when every body names its own.
  s.shape.file = "missing.svg";
  s.bodies[0].file = "shapes/sq.svg";
  s.bodies[1].file = "shapes/tri.obj";
  EXPECT_EQ(load_shape_files(s, scene_path(), &body), "");
}

TEST(ShapeFilesEmbedded, EmbeddedScenesReadTheEmbeddedAssets) {
  bool found = false;
  for (const auto& f : embedded_shape_files()) found = found || f.path == "shapes/square-hole.svg";
  ASSERT_TRUE(found);
  SceneDef s;
  s.shape.kind = ShapeKind::Svg;
  s.shape.file = "../shapes/square-hole.svg";
  s.shape.scale = 0.01;
  // "compress" is embedded: its source name finds the asset without any folder.
  ASSERT_EQ(load_shape_files(s, "assets/scenes/compress.toml"), "");
  ASSERT_EQ(s.shape.loaded.loops.size(), 2u);
  EXPECT_EQ(s.shape.loaded.fill_rule, FillRule::EvenOdd);
  s.shape.file = "../shapes/./../shapes/square-hole.svg";  // normalised
  EXPECT_EQ(load_shape_files(s, "assets/scenes/compress.toml"), "");
  // A scene on disk that names an embedded asset not on its disk gets the embedded copy.
  s.shape.file = "../shapes/square-hole.svg";
  s.shape.loaded = {};
  EXPECT_EQ(load_shape_files(s, "/nonexistent-folder/scenes/x.toml"), "");
  EXPECT_EQ(s.shape.loaded.loops.size(), 2u);
  s.shape.file = "../shapes/none.svg";
  EXPECT_EQ(load_shape_files(s, "/nonexistent-folder/scenes/x.toml"),
            "mesh.file: cannot open '../shapes/none.svg' (No such file or directory)");
  // A built-in scene's source is also its path on disk from the repository's root: a file
  // not embedded is looked for there.
  EXPECT_EQ(load_shape_files(s, "assets/scenes/compress.toml"),
            "mesh.file: cannot open '../shapes/none.svg' (No such file or directory)");
}

}  // namespace
}  // namespace invfree::scene_io
