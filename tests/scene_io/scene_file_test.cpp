#include "scene_io/scene_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

#include "scene/initial_state.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/section_notes.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

// Every file of assets/scenes/ is embedded with its text, under its stem, and loads; the
// embedded list holds nothing else.
TEST(BuiltinScenes, EveryAssetFileIsEmbeddedAndLoads) {
  std::map<std::string, std::string> embedded;
  for (const auto& e : builtin_scenes()) embedded[std::string(e.name)] = std::string(e.text);
  for (const auto& e : stress_scene_files()) embedded[std::string(e.name)] = std::string(e.text);
  size_t files = 0;
  for (const auto& f : std::filesystem::directory_iterator(
           std::string(::invfree::test::source_dir()) + "/assets/scenes")) {
    if (f.path().extension() != ".toml") continue;
    ++files;
    const std::string stem = f.path().stem().string();
    std::ifstream in(f.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_TRUE(embedded.count(stem)) << stem << " is not embedded";
    EXPECT_EQ(embedded[stem], text) << stem;
    const SceneLoad load = load_scene(f.path().string());
    ASSERT_TRUE(load.scene) << load.error;
    EXPECT_EQ(load.scene->name, stem) << "a scene's name is its file's stem";
    EXPECT_EQ(stem.rfind("stress-", 0) == 0,
              std::none_of(builtin_scenes().begin(), builtin_scenes().end(),
                           [&](const EmbeddedScene& e) { return e.name == stem; }))
        << stem << ": stress-*.toml are the stress scenes, the others the built-in ones";
  }
  EXPECT_EQ(files, embedded.size());
  EXPECT_EQ(builtin_scene_names(),
            "bunny, c-shape, compress, course-0-free-fall, course-0-mass-spring, course-0-spring, "
            "course-1-mass-spring, course-2-dirichlet, course-3-contact, "
            "course-4-friction, course-5-moving-dirichlet, "
      "course-9-affine, course-9-cubic, course-9-modal, course-9-quadratic, drop, modes-cantilever, plate-hole, ring, stack, "
            "stack-friction");
}

// SceneDef's defaults are the reference demo (scene/scene.h): `compress` is the struct as
// it comes, and `drop` differs from it in exactly what its file says.
TEST(BuiltinScenes, CompressIsTheDefaultSceneAndDropItsVariant) {
  const SceneLoad compress = load_builtin_scene("compress");
  ASSERT_TRUE(compress.scene) << compress.error;
  EXPECT_TRUE(*compress.scene == SceneDef{});
  EXPECT_TRUE(*load_scene("compress").scene == SceneDef{});
  const SceneLoad drop = load_builtin_scene("drop");
  ASSERT_TRUE(drop.scene) << drop.error;
  SceneDef expected;
  expected.name = "drop";
  expected.has_ceiling = false;
  expected.friction = 0.0;
  EXPECT_TRUE(*drop.scene == expected);
  EXPECT_EQ(load_builtin_scene("stress-h0.1").error,
            "stress-h0.1: not a built-in scene (bunny, c-shape, compress, course-0-free-fall, "
            "course-0-mass-spring, course-0-spring, course-1-mass-spring, "
            "course-2-dirichlet, "
            "course-3-contact, course-4-friction, course-5-moving-dirichlet, "
      "course-9-affine, course-9-cubic, course-9-modal, course-9-quadratic, drop, modes-cantilever, plate-hole, "
            "ring, stack, "
            "stack-friction)");
}

TEST(SceneFiles, SerialisationRoundTrips) {
  for (const auto& entry : builtin_scenes()) {
    SceneDef s = *load_builtin_scene(entry.name).scene;
    s.jitter = 0.1;
    s.seed = 42;
    s.initial_velocity = Vec2(1.0, -20.0);
    s.projection = HessianProjection::Full;
    const SceneLoad back = parse_scene_toml(scene_to_toml(s), "roundtrip.toml");
    ASSERT_TRUE(back.scene) << back.error;
    EXPECT_TRUE(*back.scene == s) << scene_to_toml(s);
  }
}

TEST(SceneFiles, DisabledTermsKeepTheirValuesAndRoundTrip) {
  // `enabled = false` wins whatever the key order (toml++ iterates keys alphabetically).
  for (const char* text :
       {"[ceiling]\nenabled = false\ny = 0.7\n", "[ceiling]\ny = 0.7\nenabled = false\n"}) {
    const SceneLoad load = parse_scene_toml(text, "off.toml");
    ASSERT_TRUE(load.scene) << load.error;
    EXPECT_FALSE(load.scene->has_ceiling) << text;
    EXPECT_EQ(load.scene->ceiling_y, 0.7);
    const SceneLoad back = parse_scene_toml(scene_to_toml(*load.scene), "back.toml");
    ASSERT_TRUE(back.scene) << back.error;
    EXPECT_TRUE(*back.scene == *load.scene) << scene_to_toml(*load.scene);
  }
  SceneDef odd = *load_builtin_scene("drop").scene;
  odd.name = "quote \" and \\ backslash";
  odd.seed = 99;  // kept even while jitter is 0
  odd.has_gravity = false;
  odd.gravity = Vec2(1.5, -2.0);
  odd.dhat = 0.02;
  const SceneLoad back = parse_scene_toml(scene_to_toml(odd), "odd.toml");
  ASSERT_TRUE(back.scene) << back.error << "\n" << scene_to_toml(odd);
  EXPECT_TRUE(*back.scene == odd) << scene_to_toml(odd);
}

TEST(SceneFiles, MissingSectionsSwitchTermsOff) {
  const SceneLoad load = parse_scene_toml("[mesh]\nn_seg = 2\n", "bare.toml");
  ASSERT_TRUE(load.scene) << load.error;
  EXPECT_FALSE(load.scene->has_gravity);
  EXPECT_FALSE(load.scene->has_ground);
  EXPECT_FALSE(load.scene->has_ceiling);
  EXPECT_EQ(load.scene->name, "bare");
}

TEST(SceneFiles, YoungPoissonOrLame) {
  auto a = parse_scene_toml("[material]\nE = 1e4\nnu = 0.3\n", "a.toml");
  ASSERT_TRUE(a.scene);
  EXPECT_DOUBLE_EQ(a.scene->lame.mu, 1e4 / 2.6);
  auto b = parse_scene_toml("[material]\nmu = 10\nlambda = 20\n", "b.toml");
  ASSERT_TRUE(b.scene);
  EXPECT_EQ(b.scene->lame, (Lame{10, 20}));
}

struct BadCase {
  const char* text;
  const char* expected;  // substring of the one-line error
};

TEST(SceneFiles, BadInputGivesOneLineErrorsNamingFileLineAndKey) {
  const BadCase cases[] = {
      {"[material]\nnu = 0.5\n", "bad.toml:2: material.nu: must be in [0, 0.5)"},
      {"[material]\nnu = -0.1\n", "material.nu: must be in [0, 0.5)"},
      {"[material]\nE = 0\n", "bad.toml:2: material.E: must be a finite number > 0"},
      {"[material]\nE = -5\n", "material.E: must be a finite number > 0"},
      {"[material]\nE = 1e5\nmu = 3\n", "give either E and nu or mu and lambda"},
      {"[material]\nmodel = \"neohookean\"\n", "material.model: unknown value \"neohookean\""},
      {"[time]\nh = 0\n", "bad.toml:2: time.h: must be a finite number > 0"},
      {"[time]\nh = -0.01\n", "time.h: must be a finite number > 0"},
      {"[time]\nh = nan\n", "time.h: must be a finite number"},
      {"[time]\nh = \"fast\"\n", "time.h: expected a number, got a string"},
      {"[mesh]\nn_seg = 0\n", "bad.toml:2: mesh.n_seg: must be between 1 and 4096"},
      {"[mesh]\nn_seg = 2.5\n", "mesh.n_seg: expected an integer"},
      {"[mesh]\nnseg = 4\n", "bad.toml:2: mesh.nseg: unknown key (did you mean \"n_seg\"?)"},
      {"[mesh]\ndensity = 0\n", "mesh.density: must be a finite number > 0"},
      {"[meshh]\nn_seg = 4\n", "meshh: unknown section (did you mean \"mesh\"?)"},
      {"[ground]\ny = 0.0\n", "ground.y: the square starts on or through the ground"},
      {"[ceiling]\ny = 0.2\n", "ceiling.y: the square starts on or through the ceiling"},
      {"[ground]\ny = -1\n[ceiling]\ny = -2\n", "ceiling.y: must be above ground.y"},
      {"[ground]\ny = -1\nfriction = -0.1\n", "ground.friction: must be a finite number >= 0"},
      {"[ground]\ny = -1\n[barrier]\ndhat = 0\n", "barrier.dhat: must be a finite number > 0"},
      {"[ground]\ny = -1\n[barrier]\nkappa = -1\n", "barrier.kappa: must be a finite number > 0"},
      {"[gravity]\ng = [0, 1, 2]\n", "gravity.g: expected an array of two numbers"},
      {"[mesh]\njitter = 0.45\nn_seg = 8\n",
       "mesh.jitter: the initial mesh has an inverted triangle"},
      {"[mesh\nn_seg = 4\n", "bad.toml:1: malformed TOML"},
      {"n_seg = 4\n", "n_seg: unknown top-level key"},
      {"mesh = 3\n", "mesh: expected a [mesh] section"},
  };
  for (const auto& c : cases) {
    const SceneLoad load = parse_scene_toml(c.text, "bad.toml");
    ASSERT_FALSE(load.scene) << c.text;
    EXPECT_NE(load.error.find(c.expected), std::string::npos) << "got: " << load.error;
    EXPECT_EQ(load.error.find('\n'), std::string::npos) << load.error;
  }
  EXPECT_NE(parse_scene_toml(std::string("[mesh]\0\x01\x02", 9), "bin.toml")
                .error.find("not a text file"),
            std::string::npos);
}

TEST(SceneFiles, MissingFileAndUnknownName) {
  const SceneLoad load = load_scene("/nonexistent/scene.toml");
  ASSERT_FALSE(load.scene);
  EXPECT_EQ(
      load.error,
      "/nonexistent/scene.toml: no such file, and not a built-in scene (bunny, c-shape, compress, "
      "course-0-free-fall, course-0-mass-spring, course-0-spring, "
      "course-1-mass-spring, course-2-dirichlet, course-3-contact, course-4-friction, "
      "course-5-moving-dirichlet, "
      "course-9-affine, course-9-cubic, course-9-modal, course-9-quadratic, drop, modes-cantilever, plate-hole, ring, stack, stack-friction)");
}

TEST(Overrides, ApplyAndValidate) {
  SceneDef s = *load_builtin_scene("compress").scene;
  EXPECT_EQ(apply_override(s, "material.E=1e4"), "");
  double E, nu;
  young_poisson_from_lame(s.lame, &E, &nu);
  EXPECT_NEAR(E, 1e4, 1e-8);
  EXPECT_NEAR(nu, 0.4, 1e-12);
  EXPECT_EQ(apply_override(s, "material.model=linear"), "");
  EXPECT_EQ(s.model, Model::Linear);
  EXPECT_EQ(apply_override(s, "ceiling.enabled=false"), "");
  EXPECT_FALSE(s.has_ceiling);
  EXPECT_EQ(apply_override(s, "ceiling.y=0.8"), "");
  EXPECT_TRUE(s.has_ceiling);
  EXPECT_EQ(apply_override(s, "gravity.g=[0, -1.62]"), "");
  EXPECT_DOUBLE_EQ(s.gravity.y(), -1.62);

  const SceneDef before = s;
  EXPECT_NE(apply_override(s, "material.nu=0.5").find("material.nu: must be in [0, 0.5)"),
            std::string::npos);
  EXPECT_NE(apply_override(s, "time.h=0").find("time.h"), std::string::npos);
  EXPECT_NE(apply_override(s, "time.hh=0.1").find("did you mean \"h\""), std::string::npos);
  EXPECT_NE(apply_override(s, "timing.h=0.1").find("unknown section"), std::string::npos);
  // The array tables are the scene file's: --set says so instead of "unknown section".
  EXPECT_EQ(apply_override(s, "traction.force=[1, 0]"),
            "--set traction.force=[1, 0]: traction: [[traction]] tables are set in the scene "
            "file; --set reaches the sections' keys only");
  EXPECT_NE(apply_override(s, "body.side=2").find("[[body]] tables are set in the scene file"),
            std::string::npos);
  EXPECT_NE(apply_override(s, "time.h").find("expected section.key=value"), std::string::npos);
  EXPECT_NE(apply_override(s, "ground.y=0").find("ground.y"), std::string::npos);
  EXPECT_TRUE(s == before) << "a rejected override must leave the scene unchanged";
  SceneDef drop = *load_builtin_scene("drop").scene;
  EXPECT_NE(apply_override(drop, "ground.y=0").find("through the ground"), std::string::npos);
}

// ---- exhaustive bad input -------------------------------------------------------------
// Every check below asserts the whole contract: the load fails, the error is one line,
// it starts with "<file>:<line>: <section.key>: " and says what is wrong.

// The kind of value each key takes. The test fails when a key is added to the parser
// without being listed here, so every key's wrong types stay covered.
enum class Kind { Number, Integer, Enum, Bool, Vec2, Text, Points, Loops, Pairs };
const std::map<std::string, Kind>& key_kinds() {
  static const std::map<std::string, Kind> kinds = {
      {"mesh.side", Kind::Number},
      {"mesh.n_seg", Kind::Integer},
      {"mesh.density", Kind::Number},
      {"mesh.mass", Kind::Enum},
      {"mesh.node_mass", Kind::Number},
      {"mesh.points", Kind::Points},
      {"mesh.jitter", Kind::Number},
      {"mesh.seed", Kind::Integer},
      {"mesh.shape", Kind::Enum},
      {"mesh.width", Kind::Number},
      {"mesh.height", Kind::Number},
      {"mesh.radius", Kind::Number},
      {"mesh.inner_radius", Kind::Number},
      {"mesh.outline", Kind::Points},
      {"mesh.holes", Kind::Loops},
      {"mesh.file", Kind::Text},
      {"mesh.path_id", Kind::Text},
      {"mesh.scale", Kind::Number},
      {"mesh.max_edge", Kind::Number},
      {"material.model", Kind::Enum},
      {"material.E", Kind::Number},
      {"material.nu", Kind::Number},
      {"material.mu", Kind::Number},
      {"material.lambda", Kind::Number},
      {"time.h", Kind::Number},
      {"time.tol", Kind::Number},
      {"time.max_newton", Kind::Integer},
      {"time.ramp_steps", Kind::Integer},
      {"solver.projection", Kind::Enum},
      {"solver.inversion_filter", Kind::Bool},
      {"solver.step_expansion", Kind::Bool},
      {"solver.friction_crossing_stop", Kind::Bool},
      {"solver.integrator", Kind::Enum},
      {"initial.velocity", Kind::Vec2},
      {"solver.linear_solver", Kind::Enum},
      {"gravity.enabled", Kind::Bool},
      {"gravity.g", Kind::Vec2},
      {"gravity.per_spring", Kind::Bool},
      {"ground.enabled", Kind::Bool},
      {"ground.y", Kind::Number},
      {"ground.friction", Kind::Number},
      {"ceiling.enabled", Kind::Bool},
      {"ceiling.y", Kind::Number},
      {"ceiling.velocity", Kind::Number},
      {"ceiling.stop", Kind::Number},
      {"barrier.dhat", Kind::Number},
      {"barrier.kappa", Kind::Number},
      {"initial.stretch", Kind::Vec2},
      {"ground.normal", Kind::Vec2},
      {"mass_spring.enabled", Kind::Bool},
      {"mass_spring.stiffness", Kind::Number},
      {"mass_spring.law", Kind::Enum},
      {"mass_spring.springs", Kind::Pairs},
      {"fixed.enabled", Kind::Bool},
      {"fixed.corners", Kind::Enum},
      {"fixed.box_min", Kind::Vec2},
      {"fixed.box_max", Kind::Vec2},
      {"fixed.boxes", Kind::Loops},
      {"fixed.components", Kind::Enum},
      {"fixed.x_boxes", Kind::Loops},
      {"fixed.y_boxes", Kind::Loops},
      {"self_contact.enabled", Kind::Bool},
      {"self_contact.friction", Kind::Number},
      {"self_contact.ccd", Kind::Bool},
      {"modes.element", Kind::Enum},
      {"reduced.basis", Kind::Enum},
      {"reduced.order", Kind::Integer},
      {"reduced.modes", Kind::Integer},
  };
  return kinds;
}

struct WrongValue {
  const char* toml;    // the value as written in a file (and after --set =)
  const char* reason;  // substring of the error
};

std::vector<WrongValue> wrong_values(Kind kind) {
  switch (kind) {
    case Kind::Number:
      return {{"\"1.0\"", "expected a number, got a string"},
              {"true", "expected a number, got a boolean"},
              {"[1.0]", "expected a number, got an array"},
              {"{ a = 1 }", "expected a number, got a table"},
              {"1979-05-27", "expected a number, got a date"},
              {"nan", "must be a finite number"},
              {"inf", "must be a finite number"},
              {"-inf", "must be a finite number"}};
    case Kind::Integer:
      return {{"\"4\"", "expected an integer, got a string"},
              {"true", "expected an integer, got a boolean"},
              {"2.5", "expected an integer, got a number"},
              {"[4]", "expected an integer, got an array"},
              {"{ a = 1 }", "expected an integer, got a table"},
              {"nan", "expected an integer"},
              {"1e300", "expected an integer"},
              {"07:32:00", "expected an integer, got a date"}};
    case Kind::Enum:
      return {{"1", "expected a string, got an integer"},
              {"true", "expected a string, got a boolean"},
              {"[\"a\"]", "expected a string, got an array"},
              {"\"nonsense\"", "unknown value \"nonsense\" (expected one of"},
              {"\"\"", "unknown value \"\""},
              {"\"a\\nb\"", "unknown value \"a\\nb\""}};
    case Kind::Bool:
      return {{"1", "expected true or false, got an integer"},
              {"\"true\"", "expected true or false, got a string"},
              {"0.0", "expected true or false, got a number"},
              {"[true]", "expected true or false, got an array"}};
    case Kind::Vec2:
      return {{"1.0", "expected an array of two numbers"},
              {"\"x\"", "expected an array of two numbers"},
              {"[1.0]", "expected an array of two numbers"},
              {"[1.0, 2.0, 3.0]", "expected an array of two numbers"},
              {"[\"a\", 1.0]", "element 0: expected a number, got a string"},
              {"[1.0, nan]", "element 1: must be a finite number"},
              {"[[1.0], [2.0]]", "element 0: expected a number, got an array"},
              {"{ x = 1 }", "expected an array of two numbers"}};
    case Kind::Text:
      return {{"1", "expected a string, got an integer"},
              {"true", "expected a string, got a boolean"},
              {"[\"a\"]", "expected a string, got an array"}};
    case Kind::Points:
      return {{"1.0", "expected an array of points"},
              {"\"x\"", "expected an array of points"},
              {"[1.0, 2.0]", "point 0: expected [x, y]"},
              {"[[1.0, 2.0], [1.0]]", "point 1: expected [x, y]"},
              {"[[\"a\", 1.0]]", "point 0: element 0: expected a number, got a string"},
              {"[[1.0, nan]]", "point 0: element 1: must be a finite number"}};
    case Kind::Loops:
      return {{"1.0", "expected an array of polygons"},
              {"[1.0]", "polygon 0: expected an array of points"},
              {"[[1.0, 2.0]]", "polygon 0: point 0: expected [x, y]"},
              {"[[[0.0, 0.0]], [[1.0, inf]]]",
               "polygon 1: point 0: element 1: must be a finite number"}};
    case Kind::Pairs:
      return {{"1", "expected an array of node pairs"},
              {"\"x\"", "expected an array of node pairs"},
              {"[0, 1]", "pair 0: expected [i, j]"},
              {"[[0, 1], [2]]", "pair 1: expected [i, j]"},
              {"[[0, 1.5]]", "pair 0: element 1: expected an integer, got a number"},
              {"[[\"a\", 1]]", "pair 0: element 0: expected an integer, got a string"},
              {"[[-1, 0]]", "pair 0: element 0: must be a node index >= 0"},
              {"[[0, 4294967296]]", "pair 0: element 1: must be a node index >= 0"}};
  }
  return {};
}

// Asserts a clean one-line error containing `expected`; counts the inputs tried.
int g_bad_inputs = 0;
void expect_clean_error(const std::string& error, const std::string& expected,
                        const std::string& input) {
  ++g_bad_inputs;
  EXPECT_FALSE(error.empty()) << "accepted: " << input;
  EXPECT_NE(error.find(expected), std::string::npos)
      << "input: " << input << "\nexpected: " << expected << "\ngot: " << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << "not one line: " << error;
  EXPECT_EQ(error.find('\r'), std::string::npos) << "not one line: " << error;
}
// An error naming a "section.key" gives its line, and that line of the input holds the
// key: errors blame the key the user wrote, never one the file does not set.
void expect_blames_a_written_key(const std::string& error, const std::string& text) {
  // "bad.toml[:LINE]: section.key: ..."
  const std::string source = "bad.toml";
  if (error.rfind(source, 0) != 0) return;
  size_t p = source.size();
  int line = 0;
  if (p < error.size() && error[p] == ':' && std::isdigit(static_cast<unsigned char>(error[p + 1])))
    for (++p; p < error.size() && std::isdigit(static_cast<unsigned char>(error[p])); ++p)
      line = 10 * line + (error[p] - '0');
  if (error.compare(p, 2, ": ") != 0) return;
  size_t dot = p + 2;
  while (dot < error.size() && std::islower(static_cast<unsigned char>(error[dot]))) ++dot;
  size_t end = dot + 1;
  while (end < error.size() &&
         (std::isalpha(static_cast<unsigned char>(error[end])) || error[end] == '_'))
    ++end;
  if (dot == p + 2 || error[dot] != '.' || end == dot + 1 || error.compare(end, 2, ": ") != 0)
    return;
  const std::string key = error.substr(dot + 1, end - dot - 1);
  ASSERT_GT(line, 0) << "names a key without its line: " << error;
  std::istringstream in(text);
  std::string written;
  for (int k = line; k > 0; --k) std::getline(in, written);
  EXPECT_NE(written.find(key), std::string::npos)
      << "line " << line << " (" << written << ") does not hold the key of: " << error;
}
void expect_bad_file(const std::string& text, const std::string& expected) {
  const SceneLoad load = parse_scene_toml(text, "bad.toml");
  EXPECT_FALSE(load.scene) << text;
  expect_clean_error(load.error, expected, text);
  expect_blames_a_written_key(load.error, text);
}
void report_count(const char* what) {
  std::printf("bad inputs tried (%s): %d, all clean one-line errors\n", what, g_bad_inputs);
  g_bad_inputs = 0;
}

TEST(BadInput, EveryKeyIsCovered) {
  std::vector<std::string> listed;
  for (const auto& [key, kind] : key_kinds()) listed.push_back(key);
  std::vector<std::string> parser = scene_keys();
  std::sort(parser.begin(), parser.end());
  EXPECT_EQ(parser, listed);
}

TEST(BadInput, WrongTypeForEveryKeyInAFile) {
  for (const auto& [key, kind] : key_kinds()) {
    const std::string section = key.substr(0, key.find('.')), name = key.substr(key.find('.') + 1);
    for (const auto& w : wrong_values(kind)) {
      const std::string text = "[" + section + "]\n" + name + " = " + w.toml + "\n";
      expect_bad_file(text, "bad.toml:2: " + key + ": " + w.reason);
    }
  }
  expect_bad_file("name = 3\n", "bad.toml:1: name: expected a string, got an integer");
  expect_bad_file("name = [\"a\"]\n", "bad.toml:1: name: expected a string, got an array");
  expect_bad_file("name = \"a\\u0007b\"\n",
                  "bad.toml:1: name: must not contain control characters");
  report_count("wrong types in files");
}

TEST(BadInput, WrongTypeForEveryKeyInAnOverride) {
  const SceneDef base = *load_builtin_scene("compress").scene;
  for (const auto& [key, kind] : key_kinds()) {
    for (const auto& w : wrong_values(kind)) {
      // Bare words become strings on the command line, so "--set time.h=fast" reads as
      // the string "fast"; quoted TOML strings are the same value.
      SceneDef s = base;
      const std::string assignment = key + "=" + w.toml;
      const std::string error = apply_override(s, assignment);
      expect_clean_error(error, key + ": " + w.reason, assignment);
      EXPECT_EQ(error.rfind("--set ", 0), 0u) << error;
      EXPECT_TRUE(s == base) << "a rejected override changed the scene: " << assignment;
    }
  }
  report_count("wrong types in --set");
}

TEST(BadInput, OutOfRangeValuesInAFile) {
  const BadCase cases[] = {
      {"[mesh]\nside = 0\n", "bad.toml:2: mesh.side: must be a finite number > 0"},
      {"[mesh]\nside = -1\n", "bad.toml:2: mesh.side: must be a finite number > 0"},
      {"[mesh]\nn_seg = -3\n", "bad.toml:2: mesh.n_seg: must be between 1 and 4096"},
      {"[mesh]\nn_seg = 4097\n", "bad.toml:2: mesh.n_seg: must be between 1 and 4096"},
      {"[mesh]\nn_seg = 9223372036854775807\n",
       "bad.toml:2: mesh.n_seg: must be between 1 and 4096"},
      {"[mesh]\ndensity = -1000\n", "bad.toml:2: mesh.density: must be a finite number > 0"},
      {"[mesh]\njitter = -0.1\n", "bad.toml:2: mesh.jitter: must be in [0, 0.5)"},
      {"[mesh]\njitter = 0.5\n", "bad.toml:2: mesh.jitter: must be in [0, 0.5)"},
      {"[mesh]\nseed = -1\n", "bad.toml:2: mesh.seed: must be >= 0"},
      {"[material]\nnu = 0.7\n", "bad.toml:2: material.nu: must be in [0, 0.5)"},
      {"[material]\nmu = 0\n", "bad.toml:2: material.mu: must be a finite number > 0"},
      {"[material]\nmu = -1\n", "bad.toml:2: material.mu: must be a finite number > 0"},
      {"[material]\nlambda = -1\n", "bad.toml:2: material.lambda: must be a finite number >= 0"},
      {"[material]\nnu = 0.3\nlambda = 5\n",
       "bad.toml:2: material.nu: give either E and nu or mu and lambda, not both"},
      {"[material]\nmu = 5\nE = 1e5\n",
       "bad.toml:3: material.E: give either E and nu or mu and lambda, not both"},
      {"[material]\nE = 1e308\nnu = 0.49\n",
       "material.E: too large (mu and lambda must be finite)"},
      {"[time]\ntol = 0\n", "bad.toml:2: time.tol: must be a finite number > 0"},
      {"[time]\ntol = -1e-3\n", "bad.toml:2: time.tol: must be a finite number > 0"},
      {"[time]\nmax_newton = 0\n", "bad.toml:2: time.max_newton: must be between 1 and 100000"},
      {"[time]\nmax_newton = 1000000\n",
       "bad.toml:2: time.max_newton: must be between 1 and 100000"},
      {"[time]\nh = inf\n", "bad.toml:2: time.h: must be a finite number"},
      {"[solver]\nprojection = \"partial\"\n",
       "bad.toml:2: solver.projection: unknown value \"partial\""},
      {"[solver]\nintegrator = \"rk4\"\n", "bad.toml:2: solver.integrator: unknown value \"rk4\""},
      {"[mesh]\nmass = \"heavy\"\n", "bad.toml:2: mesh.mass: unknown value \"heavy\""},
      // dhat, kappa and friction are checked even when no term uses them yet.
      {"[barrier]\ndhat = 0\n", "bad.toml:2: barrier.dhat: must be a finite number > 0"},
      {"[barrier]\ndhat = -0.01\n", "bad.toml:2: barrier.dhat: must be a finite number > 0"},
      {"[barrier]\nkappa = 0\n", "bad.toml:2: barrier.kappa: must be a finite number > 0"},
      {"[ground]\nenabled = false\nfriction = -1\n",
       "bad.toml:3: ground.friction: must be a finite number >= 0"},
      // Planes: ceiling at or below the ground, square through a plane.
      {"[ground]\ny = -1\n[ceiling]\ny = -1\n", "bad.toml:4: ceiling.y: must be above ground.y"},
      {"[ground]\ny = -1\n[ceiling]\ny = -3\nstop = -4\n",
       "bad.toml:4: ceiling.y: must be above ground.y"},
      {"[ground]\ny = -1\n[ceiling]\nstop = -1.5\n",
       "bad.toml:4: ceiling.stop: must be above ground.y"},
      {"[ground]\ny = -0.5\n", "bad.toml:2: ground.y: the square starts on or through the ground"},
      {"[ground]\ny = 3\n", "bad.toml:2: ground.y: the square starts on or through the ground"},
      {"[ceiling]\ny = 0.5\n",
       "bad.toml:2: ceiling.y: the square starts on or through the ceiling"},
      {"[ceiling]\ny = -3\n", "bad.toml:2: ceiling.y: the square starts on or through the ceiling"},
      {"[mesh]\nside = 3\n[ground]\ny = -1\n",
       "ground.y: the square starts on or through the ground"},
      // The course's additions: springs, fixed nodes, a sloped ground, a stretched start.
      {"[mass_spring]\nstiffness = -1e3\n",
       "bad.toml:2: mass_spring.stiffness: must be a finite number > 0"},
      {"[mass_spring]\nstiffness = 0\n",
       "bad.toml:2: mass_spring.stiffness: must be a finite number > 0"},
      {"[ground]\nnormal = [0.0, 0.0]\n",
       "bad.toml:2: ground.normal: must not be zero (it is the plane's normal)"},
      {"[ground]\nnormal = [0.0, -1.0]\n",
       "bad.toml:2: ground.normal: the square starts on or through the ground"},
      {"[fixed]\ncorners = \"middle\"\n", "bad.toml:2: fixed.corners: unknown value \"middle\""},
      {"[fixed]\ncorners = \"none\"\n",
       "bad.toml:2: fixed.corners: the [fixed] rules select no node"},
      {"[fixed]\nbox_min = [2.0, 2.0]\nbox_max = [3.0, 3.0]\n",
       "bad.toml:2: fixed.box_min: the box [2, 3] x [2, 3] holds no node of the rest mesh"},
      {"[fixed]\nbox_min = [0.1, 0.1]\nbox_max = [0.2, 0.2]\n",
       "fixed.box_min: the box [0.1, 0.2] x [0.1, 0.2] holds no node of the rest mesh"},
      {"[initial]\nstretch = [0.0, 1.0]\n",
       "bad.toml:2: initial.stretch: both factors must be finite and > 0"},
      {"[initial]\nstretch = [1.0, -1.0]\n",
       "bad.toml:2: initial.stretch: both factors must be finite and > 0"},
      {"[initial]\nstretch = [1.0, -1.0]\n[mass_spring]\n",
       "initial.stretch: both factors must be finite and > 0"},
      {"[initial]\nstretch = [1.6, 1.0]\n[ground]\nnormal = [1.0, 0.2]\ny = 0.0\n",
       "the square starts on or through the ground"},
      // A start that neo-Hookean cannot step from.
      {"[mesh]\njitter = 0.49\nn_seg = 16\n",
       "mesh.jitter: the initial mesh has an inverted triangle"},
  };
  for (const auto& c : cases) expect_bad_file(c.text, c.expected);
  report_count("out-of-range values in files");
}

TEST(BadInput, BoundaryValuesAreAccepted) {
  // The checks are exactly as wide as documented: these must all load.
  const char* good[] = {
      "[material]\nnu = 0\n",
      "[material]\nnu = 0.4999\n",
      "[material]\nmu = 1\nlambda = 0\n",
      "[ground]\ny = -1\nfriction = 0\n",
      "[mesh]\nn_seg = 1\n",
      "[mesh]\njitter = 0\n",
      "[ground]\ny = -0.5000001\n",
      "[ceiling]\ny = 0.5000001\n",
      "[mesh]\nn_seg = 4.0\n",
      "[material]\nmodel = \"linear\"\n[mesh]\njitter = 0.49\nn_seg = 16\n",  // invertible model
      "[mass_spring]\n[mesh]\njitter = 0.49\nn_seg = 16\n",                   // springs may invert
      "[fixed]\nbox_min = [-0.5, -0.5]\nbox_max = [-0.5, 0.5]\n",             // the left edge
      "[fixed]\ncorners = \"bottom-right\"\n",
      "[ground]\nnormal = [0.1, 1.0]\ny = -1\n",
  };
  for (const char* text : good) {
    const SceneLoad load = parse_scene_toml(text, "good.toml");
    EXPECT_TRUE(load.scene) << text << "\n" << load.error;
  }
}

TEST(BadInput, MeshTooLargeForMemory) {
  // 4096 passes the hard cap but needs ~100 GiB; skipped only on a machine that has that.
  if (check_mesh_fits_in_memory(kMaxSegments).empty())
    GTEST_SKIP() << "this machine could hold n_seg 4096";
  expect_bad_file("[mesh]\nn_seg = 4096\n", "bad.toml:2: mesh.n_seg: 4096 would need about");
  SceneDef s = *load_builtin_scene("compress").scene;
  expect_clean_error(apply_override(s, "mesh.n_seg=4096"), "mesh.n_seg: 4096 would need about",
                     "--set");
  EXPECT_GT(estimated_memory_bytes(256), 2.0 * 66049 * 1000) << "below the measured 2.8 kB/node";
  report_count("memory");
}

TEST(BadInput, UnknownSectionsAndKeys) {
  const BadCase cases[] = {
      {"[Mesh]\nside = 1\n", "bad.toml:1: Mesh: unknown section (did you mean \"mesh\"?)"},
      {"[materials]\nE = 1\n",
       "bad.toml:1: materials: unknown section (did you mean \"material\"?)"},
      {"[celing]\ny = 1\n", "bad.toml:1: celing: unknown section (did you mean \"ceiling\"?)"},
      {"[xyzzy]\n", "bad.toml:1: xyzzy: unknown section (sections: mesh, material"},
      {"[material]\nyoung = 1e5\n", "bad.toml:2: material.young: unknown key"},
      {"[material]\nlamda = 1\n",
       "bad.toml:2: material.lamda: unknown key (did you mean \"lambda\"?)"},
      {"[material]\ne = 1e5\n", "bad.toml:2: material.e: unknown key (did you mean \"E\"?)"},
      {"[time]\ndt = 0.01\n", "bad.toml:2: time.dt: unknown key"},
      {"[ground]\nfricton = 0.1\n",
       "bad.toml:2: ground.fricton: unknown key (did you mean \"friction\"?)"},
      {"[barrier]\nd_hat = 0.1\n",
       "bad.toml:2: barrier.d_hat: unknown key (did you mean \"dhat\"?)"},
      {"[mesh.sub]\nx = 1\n", "bad.toml:1: mesh.sub: unknown key"},
      {"[mesh]\n\"a\\nb\" = 1\n", "bad.toml:2: mesh.a\\nb: unknown key"},
      {"nme = \"x\"\n",
       "bad.toml:1: nme: unknown top-level key (only \"name\" and sections are allowed)"},
      {"time = 0.01\n", "bad.toml:1: time: expected a [time] section, got a number"},
      {"[[mesh]]\nside = 1\n", "bad.toml:1: mesh: expected a [mesh] section, got an array"},
  };
  for (const auto& c : cases) expect_bad_file(c.text, c.expected);
  report_count("unknown sections and keys");
}

TEST(BadInput, MalformedToml) {
  std::string deep(100000, '[');  // a parser that recurses per bracket would blow the stack
  const BadCase cases[] = {
      {"[mesh\n", "bad.toml:1: malformed TOML"},
      {"[mesh]\nside = \n", "bad.toml:2: malformed TOML"},
      {"[mesh]\nside = 1.2.3\n", "bad.toml:2: malformed TOML"},
      {"[mesh]\nside = 1\nside = 2\n", "bad.toml:3: malformed TOML"},
      {"[mesh]\n[mesh]\n", "bad.toml:2: malformed TOML"},
      {"name = \"unterminated\n", "bad.toml:1: malformed TOML"},
      {"name = \"bad \\q escape\"\n", "bad.toml:1: malformed TOML"},
      {"[gravity]\ng = [0, -9.81\n", "bad.toml:2: malformed TOML"},
      {"[mesh]\nn_seg = 99999999999999999999\n", "bad.toml:2: malformed TOML"},
      {"[mesh]\nside 1\n", "bad.toml:2: malformed TOML"},
      {"= 1\n", "bad.toml:1: malformed TOML"},
      {"name = \"\xff\xfe\"\n", "bad.toml:1: malformed TOML"},  // invalid UTF-8
      {"\xc3\x28 = 1\n", "bad.toml:1: malformed TOML"},
  };
  for (const auto& c : cases) expect_bad_file(c.text, c.expected);
  expect_bad_file("v = " + deep, "bad.toml:1: malformed TOML");
  expect_bad_file("v = " + std::string(100000, '{'), "bad.toml:1: malformed TOML");
  report_count("malformed TOML");
}

// toml++ 3.3 reaches __builtin_unreachable() on some non-ASCII characters (found by
// tests/fuzz; see core/scene_io/toml_guard.h): they must be refused cleanly
// before toml++ sees them, while non-ASCII text inside strings and comments stays fine.
TEST(BadInput, NonAsciiWhereTomlppMisbehaves) {
  expect_bad_file("mes\xcc\xa0se#",
                  "bad.toml:1: malformed TOML: non-ASCII character outside a string or comment");
  expect_bad_file("[mesh]\nside\xc2\xa7= 1\n",
                  "bad.toml:2: malformed TOML: non-ASCII character outside a string");
  expect_bad_file("name = \"\"\"\\\n\xc2\xa7\"\"\"\n",
                  "bad.toml:2: malformed TOML: non-ASCII character after a backslash");
  expect_bad_file("name = \"a\\\xc2\xa7\"\n",
                  "bad.toml:1: malformed TOML: non-ASCII character after a backslash");
  SceneDef s = *load_builtin_scene("compress").scene;
  expect_clean_error(apply_override(s,
                                    "material.model=lin\xcc\xa0"
                                    "ear"),
                     "unknown value \"lin\xcc\xa0"
                     "ear\"",
                     "--set");
  const char* fine[] = {
      "\xef\xbb\xbfname = \"bom\"\n",                     // a byte-order mark
      "name = \"\xc3\xa9mile \xc2\xa7 \xe2\x80\x83\"\n",  // non-ASCII inside a string
      "# \xc2\xa7 commentaire \xc3\xa9\n[mesh]\nn_seg = 2 # \xcc\xa0\n",
      "name = '\xc2\xa7'\n",
      "name = \"\"\"\n\xc2\xa7 \"\" \xc2\xa7\"\"\"\n",
      "name = '''\xc2\xa7\\\xc2\xa7'''\n",  // no escapes in literal strings
  };
  for (const char* text : fine) {
    const SceneLoad load = parse_scene_toml(text, "fine.toml");
    EXPECT_TRUE(load.scene) << text << "\n" << load.error;
  }
  // The fuzzer's second finding: toml++ classifies characters while reporting an error.
  expect_bad_file("s =0\"\"\"\\n\xc2\xa7\"\"\"\n[ground]", "bad.toml:1: malformed TOML");
  // Unsafe code points keep their meaning: names (basic, literal, multi-line) and comments.
  const std::string greek =
      "\xce\xbc \xce\xbb \xc3\xa9 \xe3\x80\x80 \xef\xbc\x81";  // mu lambda e-acute U+3000 U+FF01
  const std::vector<std::string> texts = {
      "name = \"" + greek + "\"\n", "name = '" + greek + "'\n", "name = '''" + greek + "'''\n",
      "name = \"\"\"" + greek + "\"\"\"\n",
      "# \xce\xbc = 1e4, \xce\xbb = 4e4\nname = '" + greek + "' # \xce\xbd\n"};
  for (const std::string& text : texts) {
    const SceneLoad load = parse_scene_toml(text, "greek.toml");
    ASSERT_TRUE(load.scene) << text << "\n" << load.error;
    EXPECT_EQ(load.scene->name, greek) << text;
  }
  const SceneLoad quoted =
      parse_scene_toml("name = '\"\\\xce\xbc'\n", "q.toml");  // quote and backslash too
  ASSERT_TRUE(quoted.scene) << quoted.error;
  EXPECT_EQ(quoted.scene->name, "\"\\\xce\xbc");
  report_count("non-ASCII");
}

TEST(BadInput, BinaryData) {
  expect_bad_file(std::string("[mesh]\0\x01\x02", 9),
                  "bad.toml: not a text file (it contains NUL bytes)");
  expect_bad_file(std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), "bad.toml: not a text file");
  // Random bytes without NULs: toml++ must reject them without crashing.
  std::uint64_t state = 12345;
  for (int trial = 0; trial < 50; ++trial) {
    std::string bytes(200, ' ');
    for (char& c : bytes) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      c = static_cast<char>(1 + (state >> 33) % 255);
    }
    const SceneLoad load = parse_scene_toml(bytes, "bad.toml");
    EXPECT_FALSE(load.scene);
    expect_clean_error(load.error, "bad.toml:", "random bytes");
  }
  report_count("binary data");
}

TEST(BadInput, FilesThatAreNotScenes) {
  const std::string dir = ::testing::TempDir() + "/scene_files_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir + "/binary.toml", std::ios::binary) << std::string(
        "\x7f"
        "ELF\x02\x01\x01\0\0\0",
        10);
  }
  { std::ofstream(dir + "/big.toml") << std::string((1 << 20) + 10, '#'); }
  { std::ofstream(dir + "/empty.toml"); }
  const std::string fifo = dir + "/fifo.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);  // opening it for reading would block forever
  auto expect_bad = [](const std::string& path, const std::string& expected) {
    const SceneLoad load = load_scene(path);
    EXPECT_FALSE(load.scene) << path;
    expect_clean_error(load.error, expected, path);
  };
  expect_bad(dir + "/missing.toml",
             dir +
                 "/missing.toml: no such file, and not a built-in scene (bunny, c-shape, compress, "
                 "course-0-free-fall, course-0-mass-spring, course-0-spring, "
                 "course-1-mass-spring, course-2-dirichlet, course-3-contact, course-4-friction, "
                 "course-5-moving-dirichlet, "
      "course-9-affine, course-9-cubic, course-9-modal, course-9-quadratic, drop, modes-cantilever, plate-hole, ring, stack, stack-friction)");
  expect_bad(dir + "/missing/deeper.toml", "no such file");
  expect_bad(dir, dir + ": is a directory, not a scene file");
  expect_bad(dir + "/binary.toml", dir + "/binary.toml: not a text file");
  expect_bad(dir + "/big.toml", dir + "/big.toml: too large for a scene file");
  expect_bad(fifo, fifo + ": not a regular file");
  expect_bad("/dev/zero", "/dev/zero: not a regular file");
  expect_bad("/dev/urandom", "/dev/urandom: not a regular file");
  expect_bad("", ": no such file");
  expect_bad(
      "comprss",
      "comprss: no such file, and not a built-in scene (did you mean \"compress\"?) "
      "(bunny, c-shape, compress, course-0-free-fall, course-0-mass-spring, course-0-spring, "
      "course-1-mass-spring, course-2-dirichlet, course-3-contact, "
      "course-4-friction, course-5-moving-dirichlet, "
      "course-9-affine, course-9-cubic, course-9-modal, course-9-quadratic, drop, modes-cantilever, plate-hole, ring, stack, "
      "stack-friction)");
  expect_bad(dir + "/empty.toml/x", "no such file");  // a file used as a directory
  // Unreadable: /proc/self/mem is a regular file that fails every read at offset 0.
  expect_bad("/proc/self/mem", "/proc/self/mem: could not read the file");
  // An empty file is a valid (empty) scene: every term off, defaults elsewhere.
  EXPECT_TRUE(load_scene(dir + "/empty.toml").scene);
  std::filesystem::remove_all(dir);
  report_count("files");
}

TEST(BadInput, OverridesOutOfRangeAndMalformed) {
  const SceneDef base = *load_builtin_scene("compress").scene;
  const std::vector<std::string> keys = scene_keys();
  const std::string very_long(5000, 'a');  // outlives the table that points into it
  const BadCase cases[] = {
      {"material.nu=0.5", "--set material.nu=0.5: material.nu: must be in [0, 0.5)"},
      {"material.E=0", "material.E: must be a finite number > 0"},
      {"material.mu=5", "material.mu"},  // compress gives E and nu: mu alone keeps lambda, fine
      {"material.lambda=-2", "material.lambda: must be a finite number >= 0"},
      {"mesh.n_seg=0", "mesh.n_seg: must be between 1 and 4096"},
      {"mesh.side=-1", "mesh.side: must be a finite number > 0"},
      {"time.h=-1", "time.h: must be a finite number > 0"},
      {"time.h=1e400", "time.h"},
      {"ground.friction=-0.5", "ground.friction: must be a finite number >= 0"},
      {"barrier.dhat=0", "barrier.dhat: must be a finite number > 0"},
      {"barrier.kappa=-1", "barrier.kappa: must be a finite number > 0"},
      {"ceiling.y=-1", "ceiling.y: must be above ground.y"},
      {"ceiling.y=0.4", "ceiling.y: the square starts on or through the ceiling"},
      // compress stops its ceiling at -0.7: the error names the key set, and the relation.
      {"ground.y=-0.2", "--set ground.y=-0.2: ground.y: ceiling.stop must be above ground.y"},
      {"ceiling.stop=-2", "ceiling.stop: must be above ground.y"},
      {"mesh.jitter=0.7", "mesh.jitter: must be in [0, 0.5)"},
      {"time.h", "--set time.h: expected section.key=value"},
      {"=1", "expected section.key=value"},
      {"h=0.1", "--set h=0.1: expected section.key=value"},
      {".h=0.1", "unknown section"},
      {"time.=0.1", "time.: unknown key"},
      {"tim.h=0.1", "tim: unknown section (did you mean \"time\"?)"},
      {"time.hh=0.1", "time.hh: unknown key (did you mean \"h\"?)"},
      {"time.h=0.01\n[mesh]\nside = 2", "time.h: expected a single value"},
      {"time.h=0.01\nx = 2", "time.h: expected a single value"},
      {"time.h=[0.01", "time.h: expected a number, got a string"},
      {"material.model=neo hookean", "unknown value \"neo hookean\""},
      {"material.model=\"linear", "unknown value \"\\\"linear\""},
      {"name=x", "--set name=x: expected section.key=value"},
      {very_long.c_str(), "expected section.key=value"},
  };
  for (const auto& c : cases) {
    SceneDef s = base;
    const std::string error = apply_override(s, c.text);
    if (std::string(c.text) == "material.mu=5") {  // a valid override, kept as a control
      EXPECT_EQ(error, "");
      continue;
    }
    expect_clean_error(error, c.expected, c.text);
    const std::string text = c.text;
    const std::string key = text.substr(0, text.find('='));
    if (text.find('=') != std::string::npos &&
        std::find(keys.begin(), keys.end(), key) != keys.end()) {
      EXPECT_NE(error.find(": " + key + ": "), std::string::npos)
          << "blames another key: " << error;
    }
    EXPECT_LT(error.size(), 400u) << "errors quote at most a bounded part of the input";
    EXPECT_TRUE(s == base) << c.text;
  }
  // E/nu over a scene that gave mu/lambda is fine (the pair replaces the pair), but one
  // override may not carry both kinds: each --set is one key, so this is by construction.
  SceneDef lame = *parse_scene_toml("[material]\nmu = 10\nlambda = 20\n", "l.toml").scene;
  EXPECT_EQ(apply_override(lame, "material.E=30"), "");
  report_count("--set");
}

// toml++ recurses once per part of a dotted key or table header and overflowed the stack
// (SIGSEGV) at about 40,000 parts: more than two parts are refused before toml++ sees them.
// A dot inside a quoted key, a string or a comment is no part.
TEST(BadInput, DeepDottedKeys) {
  std::string chain;
  for (int k = 0; k < 50000; ++k) chain += "a.";
  const std::string deep = "malformed TOML: a dotted key with more than two parts";
  expect_bad_file(chain + "b = 1\n", "bad.toml:1: " + deep);
  expect_bad_file("[" + chain + "b]\n", "bad.toml:1: " + deep);
  expect_bad_file("[[" + chain + "b]]\n", "bad.toml:1: " + deep);
  expect_bad_file("[mesh]\nside = { " + chain + "b = 1 }\n", "bad.toml:2: " + deep);
  expect_bad_file("name = \"x\"\n[mesh]\nside = 1\n[a.b.c]\n", "bad.toml:4: " + deep);
  expect_bad_file("a . \"b\" . 'c' = 1\n", "bad.toml:1: " + deep);
  expect_bad_file("[mesh]\nside = 1.2.3\n", "bad.toml:2: malformed TOML");
  expect_bad_file("\"a.b.c.d\" = 1\n", "bad.toml:1: a.b.c.d: unknown top-level key");
  expect_bad_file("[mesh.side.x]\n", "bad.toml:1: " + deep);
  expect_bad_file("[mesh.sub]\nx = 1\n", "bad.toml:1: mesh.sub: unknown key");
  const char* fine[] = {
      "name = \"a.b.c.d.e\" # f.g.h.i\n",
      "name = 'a.b.c.d'\n",
      "name = \"\"\"a.b.\\\nc.d\"\"\"\n",
      "# [a.b.c.d]\nmesh.side = 2.5\n",
      "'mesh'.\"n_seg\" = 3\nmaterial . E = 1e5\n",
      "[mesh]\nside = 1.5 # x.y.z\n",
      "[gravity]\ng = [0.5, -9.81]\n",
  };
  for (const char* text : fine) {
    const SceneLoad load = parse_scene_toml(text, "fine.toml");
    EXPECT_TRUE(load.scene) << text << "\n" << load.error;
  }
  EXPECT_EQ(parse_scene_toml("# [a.b.c.d]\nmesh.side = 2.5\n", "f.toml").scene->side, 2.5);
  SceneDef s = *load_builtin_scene("compress").scene;
  expect_clean_error(apply_override(s, "mesh.side={ " + chain + "b = 1 }"),
                     "mesh.side: expected a number, got a string", "--set");
  expect_clean_error(apply_override(s, "mesh." + chain + "b=1"), "unknown key", "--set");
  report_count("deep dotted keys");
}

// Errors name the key the user wrote, with its line: a relation or a derived value names
// the key that was set, not the one whose check failed.
TEST(BadInput, ErrorsBlameTheKeyTheUserWrote) {
  const BadCase files[] = {
      {"[mesh]\nside = 1e-200\n",
       "bad.toml:2: mesh.side: side / n_seg gives triangles whose area underflows in double "
       "precision"},
      {"[mesh]\nn_seg = 8\nside = 1e-155\n", "bad.toml:3: mesh.side: side / n_seg gives"},
      {"[mesh]\nside = 1e200\n",
       "bad.toml:2: mesh.side: side / n_seg gives triangles whose area "
       "overflows in double precision"},
      {"[material]\nmodel = \"linear\"\n\n[mesh]\nside = 1e-200\n",
       "bad.toml:5: mesh.side: side / n_seg gives"},  // any model
      {"[material]\nnu = 0.3\nE = 5e-324\n",
       "bad.toml:3: material.E: too small (mu = E / (2 (1 + nu)) underflows to 0)"},
      {"[mesh]\nside = 3\n[ground]\n",
       "bad.toml:2: mesh.side: the square starts on or through the ground"},
      {"[ground]\ny = -0.2\n[ceiling]\n",
       "bad.toml:2: ground.y: ceiling.stop must be above ground.y"},
      {"[ground]\ny = 1\n[ceiling]\n", "bad.toml:2: ground.y: ceiling.y must be above ground.y"},
  };
  for (const auto& c : files) expect_bad_file(c.text, c.expected);
  const SceneDef compress = *load_builtin_scene("compress").scene;
  const BadCase overrides[] = {
      {"mesh.side=1e-200", "--set mesh.side=1e-200: mesh.side: side / n_seg gives triangles"},
      {"material.E=5e-324", "--set material.E=5e-324: material.E: too small"},
      {"mesh.side=3", "--set mesh.side=3: mesh.side: the square starts on or through the ground"},
      {"ground.y=1", "--set ground.y=1: ground.y: ceiling.y must be above ground.y"},
  };
  for (const auto& c : overrides) {
    SceneDef s = compress;
    expect_clean_error(apply_override(s, c.text), c.expected, c.text);
  }
  // A start only an invertible model can take, then the lecture's model.
  SceneDef jittered =
      *parse_scene_toml("[mesh]\nn_seg = 16\njitter = 0.49\n[material]\nmodel = \"arap\"\n",
                        "j.toml")
           .scene;
  expect_clean_error(apply_override(jittered, "material.model=neo-hookean"),
                     "--set material.model=neo-hookean: material.model: the initial mesh has an "
                     "inverted triangle, which the neo-hookean model cannot start from",
                     "--set");
  report_count("blame");
}

// Issue 32 item 11: a student's file with several independent mistakes gets all of them
// at once, one line each, in the file's order (only the first was reported).
TEST(SceneFiles, EveryIndependentErrorOfAFileIsReportedAtOnce) {
  const std::string text =
      "name = \"mine\"\n"      // 1
      "[mesh]\n"                // 2
      "n_segs = 8\n"            // 3: unknown key
      "side = \"big\"\n"        // 4: wrong type
      "[material]\n"            // 5
      "E = -5\n"                // 6: out of range
      "[gravty]\n"              // 7: unknown section
      "g = [0.0, -9.81]\n";     // 8
  const SceneLoad load = parse_scene_toml(text, "mine.toml");
  ASSERT_FALSE(load.scene);
  std::vector<std::string> lines;
  std::istringstream in(load.error);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << load.error;
  EXPECT_EQ(lines[0].rfind("mine.toml:3: mesh.n_segs: unknown key", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("mine.toml:4: mesh.side:", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("mine.toml:6: material.E:", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("mine.toml:7: gravty: unknown section", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find("gravity"), std::string::npos) << lines[3];  // did you mean
  // One mistake: one line, as before.
  const SceneLoad one = parse_scene_toml("[mesh]\nn_segs = 8\n", "one.toml");
  EXPECT_EQ(one.error.find('\n'), std::string::npos) << one.error;
}

// Issue 32 item 11: a file without [gravity] (or [ground], [ceiling]) runs with that term
// off, which the note says; a file with all three gets no note.
TEST(SceneFiles, LeftOutTermSectionsAreNamed) {
  const std::string note =
      left_out_sections_note("[mesh]\nn_seg = 2\n[ground]\ny = -1.0\n", "mine.toml");
  EXPECT_EQ(note.rfind("mine.toml: no [gravity] section, so gravity is off", 0), 0u) << note;
  EXPECT_NE(note.find("no [ceiling] section, so there is no ceiling"), std::string::npos) << note;
  EXPECT_EQ(note.find("[ground]"), std::string::npos) << note;
  EXPECT_EQ(note.find('\n'), std::string::npos) << note;
  EXPECT_EQ(left_out_sections_note(
                "[gravity]\ng = [0.0, -9.81]\n[ground]\ny = -1.0\n[ceiling]\nenabled = false\n",
                "all.toml"),
            "");
  // The scene itself is as the file says: gravity off.
  const SceneLoad load = parse_scene_toml("[mesh]\nn_seg = 2\n[ground]\ny = -1.0\n", "m.toml");
  ASSERT_TRUE(load.scene) << load.error;
  EXPECT_FALSE(load.scene->has_gravity);
}

}  // namespace
}  // namespace invfree
