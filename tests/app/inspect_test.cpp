// `invfree inspect` end to end: its JSON has exactly the documented keys and numbers equal
// to analyze_triangle on a simulation stepped here to the same step (same scene, same
// --set), --at picks the triangle triangle_at picks, the table names every quantity, and
// every bad input is one line on stderr with exit 2 (3 for a failed step).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "material/models.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "tests/run_command.h"
#include "tests/test_paths.h"
#include "triangle_fields.h"

namespace invfree {
namespace {

using test::CommandResult;

CommandResult run(const std::string& args) {
  return test::run_command(::invfree::test::exe_path(), args, false);
}

// --- A small strict JSON reader (the tests need no library for one object) ----------------

struct Json {
  enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
  bool boolean = false;
  double number = 0.0;
  std::string text;
  std::vector<Json> items;
  std::map<std::string, Json> members;
  std::vector<std::string> order;  // the members' keys as written

  const Json& operator[](const std::string& key) const {
    static const Json missing;
    const auto it = members.find(key);
    EXPECT_NE(it, members.end()) << "no key " << key;
    return it == members.end() ? missing : it->second;
  }
  const Json& operator[](size_t i) const {
    static const Json missing;
    EXPECT_LT(i, items.size());
    return i < items.size() ? items[i] : missing;
  }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& s) : s_(s) {}

  // The whole text as one value; an error names where it went wrong.
  bool read(Json* out, std::string* error) {
    if (!value(out) || (skip(), pos_ != s_.size())) {
      *error = "malformed JSON at offset " + std::to_string(pos_);
      return false;
    }
    return true;
  }

 private:
  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool literal(const char* word) {
    const std::string w = word;
    if (s_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }
  bool string(std::string* out) {
    if (pos_ >= s_.size() || s_[pos_] != '"') return false;
    ++pos_;
    out->clear();
    while (pos_ < s_.size() && s_[pos_] != '"') {
      if (s_[pos_] == '\\' || static_cast<unsigned char>(s_[pos_]) < 0x20) return false;
      *out += s_[pos_++];
    }
    if (pos_ >= s_.size()) return false;
    ++pos_;
    return true;
  }
  bool value(Json* v) {
    skip();
    if (pos_ >= s_.size()) return false;
    const char c = s_[pos_];
    if (c == '{') {
      v->kind = Json::Object;
      ++pos_;
      skip();
      if (pos_ < s_.size() && s_[pos_] == '}') return ++pos_, true;
      for (;;) {
        skip();
        std::string key;
        if (!string(&key)) return false;
        skip();
        if (pos_ >= s_.size() || s_[pos_++] != ':') return false;
        Json member;
        if (!value(&member)) return false;
        if (!v->members.emplace(key, member).second) return false;  // duplicate key
        v->order.push_back(key);
        skip();
        if (pos_ < s_.size() && s_[pos_] == ',') {
          ++pos_;
          continue;
        }
        return pos_ < s_.size() && s_[pos_++] == '}';
      }
    }
    if (c == '[') {
      v->kind = Json::Array;
      ++pos_;
      skip();
      if (pos_ < s_.size() && s_[pos_] == ']') return ++pos_, true;
      for (;;) {
        Json item;
        if (!value(&item)) return false;
        v->items.push_back(item);
        skip();
        if (pos_ < s_.size() && s_[pos_] == ',') {
          ++pos_;
          continue;
        }
        return pos_ < s_.size() && s_[pos_++] == ']';
      }
    }
    if (c == '"') return v->kind = Json::String, string(&v->text);
    if (literal("null")) return v->kind = Json::Null, true;
    if (literal("true")) return v->kind = Json::Bool, v->boolean = true, true;
    if (literal("false")) return v->kind = Json::Bool, v->boolean = false, true;
    // A JSON number: -?digits(.digits)?([eE][+-]?digits)? (no NaN, no infinity, no hex).
    const size_t start = pos_;
    if (s_[pos_] == '-') ++pos_;
    const auto digits = [&] {
      const size_t d = pos_;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      return pos_ > d;
    };
    if (!digits()) return false;
    if (pos_ < s_.size() && s_[pos_] == '.' && (++pos_, !digits())) return false;
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      if (!digits()) return false;
    }
    v->kind = Json::Number;
    v->number = std::strtod(s_.substr(start, pos_ - start).c_str(), nullptr);
    return true;
  }

  const std::string& s_;
  size_t pos_ = 0;
};

Json parse(const std::string& text) {
  Json j;
  std::string error;
  EXPECT_TRUE(JsonReader(text).read(&j, &error)) << error << "\n" << text;
  return j;
}

// --- What the numbers must be ------------------------------------------------------------

// The scene as the command resolves it (--scene, then each --set in order), stepped here.
Simulation stepped(const std::string& scene, const std::vector<std::string>& sets, int steps) {
  SceneLoad load = load_scene(scene);
  EXPECT_TRUE(load.scene) << load.error;
  for (const auto& s : sets) EXPECT_EQ(apply_override(*load.scene, s), "") << s;
  Simulation sim = make_simulation(*load.scene);
  for (int k = 0; k < steps; ++k) EXPECT_EQ(step(sim).status, StepStatus::Ok) << "step " << k;
  return sim;
}

std::string args_of(const std::string& scene, const std::vector<std::string>& sets, int steps) {
  std::string a = "inspect --scene " + scene + " --step " + std::to_string(steps);
  for (const auto& s : sets) a += " --set " + s;
  return a;
}

// The keys, in the documented order (docs/cli.md): the issue's, and `triangle` first.
const std::vector<std::string> kKeys = {"triangle",
                                        "model",
                                        "mu",
                                        "lambda",
                                        "F",
                                        "U",
                                        "sigma",
                                        "V",
                                        "J",
                                        "psi",
                                        "P",
                                        "cauchy",
                                        "principal_stress",
                                        "eigenvalues",
                                        "projected_eigenvalues",
                                        "clamped",
                                        "fd_error_P",
                                        "fd_error_dPdF"};

void expect_matrix(const Json& j, const Mat2& m, const std::string& what) {
  ASSERT_EQ(j.kind, Json::Array) << what;
  ASSERT_EQ(j.items.size(), 2u) << what;
  for (size_t r = 0; r < 2; ++r) {
    ASSERT_EQ(j[r].items.size(), 2u) << what;
    for (size_t c = 0; c < 2; ++c)  // row-major
      EXPECT_EQ(j[r][c].number, m(static_cast<int>(r), static_cast<int>(c))) << what << r << c;
  }
}

void expect_vector(const Json& j, const double* v, size_t n, const std::string& what) {
  ASSERT_EQ(j.kind, Json::Array) << what;
  ASSERT_EQ(j.items.size(), n) << what;
  for (size_t i = 0; i < n; ++i) EXPECT_EQ(j[i].number, v[i]) << what << i;
}

// Every number of `j` equals the analysis of triangle t of `sim` (bit for bit: the command
// prints the shortest text that reads back as the same double).
void expect_report(const Json& j, const Simulation& sim, int t) {
  ASSERT_EQ(j.kind, Json::Object);
  EXPECT_EQ(j.order, kKeys);
  EXPECT_EQ(j["triangle"].number, t);
  const StressAnalysis a = analyze_triangle(sim, t);
  ASSERT_TRUE(a.finite);
  const FiniteDifferenceErrors fd = finite_difference_errors(a.model, a.F, a.lame);
  EXPECT_EQ(j["model"].text, model_name(sim.scene.model));
  EXPECT_EQ(j["mu"].number, a.lame.mu);
  EXPECT_EQ(j["lambda"].number, a.lame.lambda);
  expect_matrix(j["F"], a.F, "F");
  expect_matrix(j["U"], a.svd.U, "U");
  expect_vector(j["sigma"], a.svd.sigma.data(), 2, "sigma");
  expect_matrix(j["V"], a.svd.V, "V");
  EXPECT_EQ(j["J"].number, a.J);
  EXPECT_EQ(j["psi"].number, a.psi);
  expect_matrix(j["P"], a.P, "P");
  expect_matrix(j["cauchy"], a.cauchy, "cauchy");
  const Json& ps = j["principal_stress"];
  ASSERT_EQ(ps.kind, Json::Object);
  EXPECT_EQ(ps.order, (std::vector<std::string>{"values", "directions"}));
  expect_vector(ps["values"], a.principal_stress.data(), 2, "principal values");
  for (size_t k = 0; k < 2; ++k) {
    const Vec2 d = a.principal_directions.col(static_cast<int>(k));
    expect_vector(ps["directions"][k], d.data(), 2, "principal direction");
  }
  expect_vector(j["eigenvalues"], a.eigenvalues.data(), 4, "eigenvalues");
  expect_vector(j["projected_eigenvalues"], a.projected_eigenvalues.data(), 4, "projected");
  EXPECT_EQ(j["clamped"].number, a.clamped);
  EXPECT_EQ(j["fd_error_P"].number, fd.P);
  EXPECT_EQ(j["fd_error_dPdF"].number, fd.dPdF);
  // The derivatives are right: the check says so.
  EXPECT_LT(fd.P, 1e-5);
  EXPECT_LT(fd.dPdF, 1e-4);
}

bool has_non_finite_text(const std::string& s) {
  std::string lower = s;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos;
}

// --- The tests ------------------------------------------------------------------------------

TEST(Inspect, JsonEqualsAnalyzeTriangleAfterTheSameSteps) {
  struct Case {
    std::string scene;
    std::vector<std::string> sets;
    int steps, triangle;
  };
  const Case cases[] = {
      {"compress", {}, 60, 7},
      {"compress", {"material.model=stable-neo-hookean", "mesh.n_seg=6"}, 25, 40},
      {"drop", {"material.model=arap"}, 30, 0},
      {"compress", {"material.model=linear"}, 10, 31},
      {"compress", {}, 0, 3},  // the initial state
  };
  int clamped_seen = 0;
  for (const Case& c : cases) {
    const std::string args =
        args_of(c.scene, c.sets, c.steps) + " --triangle " + std::to_string(c.triangle) + " --json";
    SCOPED_TRACE(args);
    const CommandResult r = run(args);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_FALSE(has_non_finite_text(r.out)) << r.out;
    const Json j = parse(r.out);
    const Simulation sim = stepped(c.scene, c.sets, c.steps);
    ASSERT_EQ(sim.step_count, c.steps);
    expect_report(j, sim, c.triangle);
    clamped_seen += static_cast<int>(j["clamped"].number);
  }
  EXPECT_GT(clamped_seen, 0) << "no case shows the projection at work";
}

// --at X,Y reports the triangle triangle_at finds under the deformed point.
TEST(Inspect, AtPicksTheTriangleUnderThePoint) {
  const std::vector<std::string> sets = {"mesh.n_seg=4"};
  const int steps = 40;
  const Simulation sim = stepped("compress", sets, steps);
  // Centroids of a few triangles, a node shared by several, and a point on an edge.
  std::vector<Vec2> points;
  for (int t : {0, 9, 22, 31}) {
    const auto& tri = sim.mesh.triangles[static_cast<size_t>(t)];
    Vec2 c = Vec2::Zero();
    for (int k = 0; k < 3; ++k) c += Vec2(sim.x[2 * tri[k]], sim.x[2 * tri[k] + 1]) / 3.0;
    points.push_back(c);
  }
  const int shared = sim.mesh.triangles[12][0];
  points.emplace_back(sim.x[2 * shared], sim.x[2 * shared + 1]);
  for (const Vec2& p : points) {
    char at[96];
    std::snprintf(at, sizeof at, "--at=%.17g,%.17g", p.x(), p.y());
    const std::string args = args_of("compress", sets, steps) + " " + at + " --json";
    SCOPED_TRACE(args);
    const std::optional<int> expected = triangle_at(sim, p);
    ASSERT_TRUE(expected.has_value());
    const CommandResult r = run(args);
    ASSERT_EQ(r.code, 0) << r.err;
    const Json j = parse(r.out);
    EXPECT_EQ(j["triangle"].number, *expected);
    expect_report(j, sim, *expected);
  }
  // The space-separated form, with a negative first coordinate too (not taken for an option).
  for (const Vec2& p : {points[0], points[3]}) {
    char at[96];
    std::snprintf(at, sizeof at, "--at %.17g,%.17g", p.x(), p.y());
    const CommandResult r = run(args_of("compress", sets, steps) + " " + at + " --json");
    ASSERT_EQ(r.code, 0) << at << "\n" << r.err;
    EXPECT_EQ(parse(r.out)["triangle"].number, *triangle_at(sim, p));
  }
  EXPECT_LT(std::min(points[0].x(), points[3].x()), 0.0);
}

// The table for a person names each quantity, with units and the eigenvalues' names, and
// marks the clamped ones.
TEST(Inspect, TableNamesEveryQuantity) {
  const std::vector<std::string> sets = {};
  const int steps = 60;
  const CommandResult r = run(args_of("compress", sets, steps) + " --triangle 7");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_FALSE(has_non_finite_text(r.out)) << r.out;
  for (const std::string& key : kKeys) {
    if (key == "triangle") continue;
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
  }
  for (const char* name : kEigenvalueNames) EXPECT_NE(r.out.find(name), std::string::npos) << name;
  for (const char* text : {" Pa", "neo-Hookean", "triangle 7 of 32", "step 60"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  const Simulation sim = stepped("compress", sets, steps);
  const StressAnalysis a = analyze_triangle(sim, 7);
  ASSERT_GT(a.clamped, 0) << "pick a compressed triangle: the table must show a clamped value";
  size_t marks = 0;
  for (size_t at = r.out.find("clamped to 0"); at != std::string::npos;
       at = r.out.find("clamped to 0", at + 1))
    ++marks;
  EXPECT_EQ(marks, static_cast<size_t>(a.clamped)) << r.out;
  EXPECT_NE(r.out.find(std::to_string(a.clamped) + " of 4"), std::string::npos) << r.out;
}

// A mass-spring scene: the triangle's geometry, and the stress quantities n/a (null).
TEST(Inspect, MassSpringSceneReportsGeometryOnly) {
  const std::string args = args_of("course-1-mass-spring", {}, 5) + " --triangle 3";
  const CommandResult r = run(args + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(has_non_finite_text(r.out)) << r.out;
  const Json j = parse(r.out);
  EXPECT_EQ(j.order, kKeys);
  EXPECT_EQ(j["model"].text, "mass-spring");
  for (const char* key : {"mu", "lambda", "psi", "P", "cauchy", "principal_stress", "eigenvalues",
                          "projected_eigenvalues", "clamped", "fd_error_P", "fd_error_dPdF"})
    EXPECT_EQ(j[key].kind, Json::Null) << key;
  const Simulation sim = stepped("course-1-mass-spring", {}, 5);
  const Mat2 F = triangle_deformation_gradient(sim, 3);
  expect_matrix(j["F"], F, "F");
  EXPECT_EQ(j["J"].number, determinant(F));
  const PolarSvd svd = polar_svd(F);
  expect_vector(j["sigma"], svd.sigma.data(), 2, "sigma");
  expect_matrix(j["U"], svd.U, "U");
  expect_matrix(j["V"], svd.V, "V");

  const CommandResult table = run(args);
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_NE(table.out.find("mass-spring"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("n/a"), std::string::npos) << table.out;
}

// Every bad input: exit 2, one line on stderr naming the problem, nothing on stdout.
TEST(Inspect, BadInputExitsTwoWithOneLine) {
  struct Case {
    std::string args, expected;
  };
  const std::string base = "inspect --scene compress ";
  const Case cases[] = {
      {base + "--step 1 --triangle 32", "--triangle 32 is out of range: the mesh has 32 triangles"},
      {base + "--step 1 --triangle -1", "--triangle -1 is out of range"},
      {base + "--set mesh.n_seg=2 --step 0 --triangle 8", "the mesh has 8 triangles (0 to 7)"},
      {base + "--step 2 --at 5,5", "no triangle contains the point (5, 5) at step 2"},
      {base + "--step 0 --at=-0.6,0", "no triangle contains the point (-0.6, 0) at step 0"},
      {base + "--step 1 --at 1", "--at 1: expected X,Y"},
      {base + "--step 1 --at 1,2,3", "--at 1,2,3: expected X,Y"},
      {base + "--step 1 --at a,b", "--at a,b: expected X,Y"},
      {base + "--step 1 --at 0.1,", "--at 0.1,: expected X,Y"},
      {base + "--step 1 --at nan,0", "--at nan,0: expected X,Y"},
      {base + "--step 1 --at 0,inf", "--at 0,inf: expected X,Y"},
      {base + "--step 1 --at ' 0.1,0.1'", "expected X,Y"},
      {base + "--step -1 --triangle 0",
       "--step: expected a whole number of steps from 0 to "
       "100000000, got -1"},
      {base + "--step 1.5 --triangle 0", "got 1.5"},
      {base + "--step 100000001 --triangle 0", "got 100000001"},
      {base + "--triangle 0", "--step is required"},
      {base + "--step 1", "inspect needs --triangle T or --at X,Y"},
      {base + "--step 1 --triangle 0 --at 0,0", "excludes"},
      {base + "--step 1 --triangle x", "--triangle"},
      {"inspect --scene nosuchscene --step 1 --triangle 0", "nosuchscene"},
      {base + "--set material.nu=0.7 --step 1 --triangle 0", "material.nu"},
      // Particles only (the course's chapter 0): nothing to inspect, whichever way asked.
      {"inspect --scene course-0-spring --step 1 --triangle 0",
       "scene course-0-spring has no triangles (particles and springs only): nothing to inspect"},
      {"inspect --scene course-0-free-fall --step 0 --at 0,0", "has no triangles"},
  };
  for (const Case& c : cases) {
    const CommandResult r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_TRUE(test::one_line(r.err)) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("invfree: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos)
        << c.args << "\nexpected: " << c.expected << "\ngot: " << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
}

// A step that fails before the requested one: exit 3, one line naming the failed step.
TEST(Inspect, FailedStepExitsThree) {
  // Newton's cap of 1 iteration with an unreachable tolerance: the first step fails.
  for (const char* what : {"--triangle 0", "--at 0,0", "--triangle 0 --json"}) {
    const CommandResult r =
        run(std::string("inspect --scene compress --set time.max_newton=1 --set time.tol=1e-14 "
                        "--step 3 ") +
            what);
    EXPECT_EQ(r.code, 3) << what << "\n" << r.err;
    EXPECT_TRUE(test::one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("invfree: step 1 failed: newton-failed"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("step 3 cannot be inspected"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  // Step 0 needs no step: the same settings inspect the initial state.
  const CommandResult r0 =
      run("inspect --scene compress --set time.max_newton=1 --set time.tol=1e-14 --step 0 "
          "--triangle 0 --json");
  EXPECT_EQ(r0.code, 0) << r0.err;
}

}  // namespace
}  // namespace invfree
