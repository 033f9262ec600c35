// Bodies of any shape in whole scenes (issue 27): the built-in shape scenes' masses and
// areas, a disk coming to rest without self-contact, the ring squashed without ever
// passing through itself, the same shape given as a polygon, an SVG and a mesh file, and
// every bad shape input refused with one line naming its key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "collision/broad_phase.h"
#include "collision/intersection_check.h"
#include "potential/point_edge_distance.h"
#include "scene/boundary.h"
#include "scene/scene_mesh.h"
#include "scene_io/scene_file.h"
#include "shape/shape_mesh.h"
#include "shape/shape_region.h"
#include "simulation.h"

namespace invfree {
namespace {

SceneDef load(const std::string& name_or_path) {
  SceneLoad l = load_scene(name_or_path);
  EXPECT_TRUE(l.scene) << l.error;
  return l.scene ? *l.scene : SceneDef{};
}

double mesh_area(const Mesh& m) {
  double a = 0.0;
  for (double t : m.rest_area) a += t;
  return a;
}

double total_mass(const Simulation& sim) {
  double m = 0.0;
  for (double v : sim.node_mass) m += v;
  return m;
}

double signed_area(const Loop& loop) {
  double a = 0.0;
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec2& p = loop[k];
    const Vec2& q = loop[(k + 1) % loop.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

TEST(ShapeScenes, MassesSumToDensityTimesTheShapesArea) {
  for (const char* name : {"ring", "c-shape", "plate-hole", "bunny"}) {
    const SceneDef s = load(name);
    const Simulation sim = make_simulation(s);
    const double area = mesh_area(sim.mesh);
    ASSERT_GT(sim.mesh.triangle_count(), 50) << name;
    EXPECT_NEAR(total_mass(sim), s.density * area, 1e-12 * s.density * area) << name;
    const PlacedBody b = placed_body(s, 0);
    const double exact = shape_area(b.shape);
    // Polygons (the C, and the SVGs' flattened loops) exactly; the ring's circles to the
    // inscribed polygons' stated bound.
    const double bound = region_area_error_bound(b.shape, shape_max_edge(b.shape, b.n_seg));
    if (b.shape.kind == ShapeKind::Ring) {
      EXPECT_GT(bound, 0.0);
      EXPECT_LE(std::abs(area - exact), bound) << name;
      EXPECT_LT(area, exact) << name;  // inscribed: always short of the circle
    } else {
      EXPECT_NEAR(area, exact, 1e-12 * exact) << name;
    }
    // Lumped masses: every node carries a third of its triangles' mass, none is zero.
    for (double m : sim.node_mass) EXPECT_GT(m, 0.0) << name;
  }
}

TEST(ShapeScenes, TheRingsBoundaryIsTwoLoopsAndTheHoleStaysAHole) {
  const SceneDef s = load("ring");
  const Mesh mesh = scene_mesh(s);
  const Boundary b = find_boundary(mesh);
  // Walk the boundary edges into loops: every node has one edge out and one in.
  std::vector<int> next(mesh.node_count(), -1);
  for (const auto& e : b.edges) {
    ASSERT_EQ(next[e[0]], -1) << "two boundary edges leave node " << e[0];
    next[e[0]] = e[1];
  }
  std::vector<bool> seen(mesh.node_count(), false);
  std::vector<double> loop_areas;
  for (const auto& e : b.edges) {
    if (seen[e[0]]) continue;
    Loop loop;
    for (int v = e[0]; !seen[v]; v = next[v]) {
      ASSERT_NE(next[v], -1) << "the boundary is open at node " << v;
      seen[v] = true;
      loop.push_back(mesh.rest[v]);
    }
    loop_areas.push_back(signed_area(loop));
  }
  ASSERT_EQ(loop_areas.size(), 2u);
  // The outer loop counter-clockwise (body on its left), the hole's clockwise.
  std::sort(loop_areas.begin(), loop_areas.end());
  EXPECT_LT(loop_areas[0], 0.0);
  EXPECT_GT(loop_areas[1], 0.0);
  EXPECT_NEAR(-loop_areas[0], M_PI * 0.3 * 0.3, 0.02);
  // No triangle covers the hole's centre.
  for (const auto& t : mesh.triangles) {
    const Vec2 c = (mesh.rest[t[0]] + mesh.rest[t[1]] + mesh.rest[t[2]]) / 3.0;
    EXPECT_GT(c.norm(), 0.29);
  }
}

// The smallest distance between a boundary node and a boundary edge it is not on.
double min_self_distance(const Boundary& b, const VecX& x) {
  double best = INFINITY;
  for (int k = 0; k < b.node_count(); ++k) {
    const int n = b.nodes[k];
    const Vec2 p = x.segment<2>(2 * n);
    for (const auto& e : b.edges) {
      if (e[0] == n || e[1] == n) continue;
      best = std::min(best, std::sqrt(point_edge_distance_squared(p, x.segment<2>(2 * e[0]),
                                                                  x.segment<2>(2 * e[1]))));
    }
  }
  return best;
}

TEST(ShapeScenes, ADiskOnTheGroundComesToRestWithoutSelfContact) {
  SceneDef s = load("ring");
  s.shape.kind = ShapeKind::Disk;
  s.has_ceiling = false;
  // Stiff, so its bounce dies within the run (implicit Euler damps its modes by about
  // omega h per step), and a Newton tolerance below the rest the test asks for.
  s.lame = lame_from_young_poisson(1e7, 0.4);
  s.tol = 1e-4;
  ASSERT_EQ(validate_scene(s), "");
  Simulation sim = make_simulation(s);
  const Boundary b = find_boundary(sim.mesh);
  double closest = INFINITY;
  double impact_speed = 0.0;
  for (int k = 0; k < 500; ++k) {
    ASSERT_EQ(step(sim).status, StepStatus::Ok) << k;
    closest = std::min(closest, min_self_distance(b, sim.x));
    impact_speed = std::max(impact_speed, sim.v.cwiseAbs().maxCoeff());
  }
  // At rest: every node a thousand times slower than the disk hit the ground (~3 m/s).
  EXPECT_GT(impact_speed, 2.0);
  EXPECT_LT(sim.v.cwiseAbs().maxCoeff(), 1e-3 * impact_speed);
  // Its boundary never came within the barrier's reach of itself: no self-contact force.
  EXPECT_GT(closest, s.dhat);
}

TEST(ShapeScenes, TheRingSquashedToTheCeilingsStopNeverIntersectsOrInverts) {
  SceneDef s = load("ring");
  s.n_seg = 10;  // coarser than the scene's, the same squash
  ASSERT_EQ(validate_scene(s), "");
  Simulation sim = make_simulation(s);
  const Boundary b = find_boundary(sim.mesh);
  const int stop_step =
      static_cast<int>(std::ceil((s.ceiling_y - s.ceiling_stop) / -s.ceiling_velocity / s.h));
  double min_det = INFINITY;
  BroadPhaseGrid grid;
  std::vector<std::array<int, 2>> scratch;
  for (int k = 0; k < stop_step + 20; ++k) {
    ASSERT_EQ(step(sim).status, StepStatus::Ok) << k;
    ASSERT_FALSE(find_self_intersection(b, sim.x, grid, scratch)) << "step " << k + 1;
    for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
      const auto& tri = sim.mesh.triangles[t];
      Mat2 ds;
      ds.col(0) = sim.x.segment<2>(2 * tri[1]) - sim.x.segment<2>(2 * tri[0]);
      ds.col(1) = sim.x.segment<2>(2 * tri[2]) - sim.x.segment<2>(2 * tri[0]);
      min_det = std::min(min_det, (ds * sim.mesh.rest_shape_inverse[t]).determinant());
    }
  }
  EXPECT_GT(min_det, 0.0);
  // Squashed: the hole has closed to within a few barrier distances.
  EXPECT_LT(min_self_distance(b, sim.x), 4 * s.dhat);
}

// ---- the same shape three ways --------------------------------------------------------

class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/invfree_shape_XXXXXX";
    path_ = ::mkdtemp(tmpl);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = path_ + "/" + name;
    std::ofstream(p) << text;
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// An L with a square hole, its bounding box centred at the origin and symmetric under
// y -> -y, so the SVG (y down, centred) gives the same points.
constexpr const char* kPolygonScene = R"(name = "L"
[mesh]
shape = "polygon"
outline = [[-0.5, -0.5], [0.5, -0.5], [0.5, -0.1], [0.0, -0.1], [0.0, 0.1], [0.5, 0.1], [0.5, 0.5], [-0.5, 0.5]]
holes = [[[-0.3, -0.1], [-0.1, -0.1], [-0.1, 0.1], [-0.3, 0.1]]]
max_edge = 0.1
mass = "lumped"
[material]
E = 1e5
nu = 0.4
)";

constexpr const char* kSvg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="-1 -1 2 2">
  <path fill-rule="evenodd" d="M -0.5 0.5 L 0.5 0.5 L 0.5 0.1 L 0 0.1 L 0 -0.1 L 0.5 -0.1 L 0.5 -0.5 L -0.5 -0.5 Z
                               M -0.3 0.1 L -0.1 0.1 L -0.1 -0.1 L -0.3 -0.1 Z"/>
</svg>
)";

std::string with_mesh_keys(const std::string& keys) {
  std::string text = kPolygonScene;
  const size_t begin = text.find("shape = ");
  const size_t end = text.find("max_edge");
  return text.replace(begin, end - begin, keys);
}

struct ShapeSummary {
  double area = 0.0, mass = 0.0, boundary_length = 0.0;
  int boundary_edges = 0;
};

ShapeSummary summary(const SceneDef& s) {
  const Simulation sim = make_simulation(s);
  const Boundary b = find_boundary(sim.mesh);
  ShapeSummary out{mesh_area(sim.mesh), total_mass(sim), 0.0, b.edge_count()};
  for (const auto& e : b.edges)
    out.boundary_length += (sim.mesh.rest[e[1]] - sim.mesh.rest[e[0]]).norm();
  return out;
}

TEST(ShapeScenes, PolygonSvgAndMeshFileGiveTheSameBody) {
  TempDir dir;
  const SceneDef polygon = load(dir.file("polygon.toml", kPolygonScene));
  const ShapeSummary p = summary(polygon);
  EXPECT_NEAR(p.area, 1.0 - 0.5 * 0.2 - 0.2 * 0.2, 1e-12);

  dir.file("l.svg", kSvg);
  const SceneDef svg = load(
      dir.file("svg.toml", with_mesh_keys("shape = \"svg\"\nfile = \"l.svg\"\nscale = 1.0\n")));
  const ShapeSummary v = summary(svg);
  EXPECT_NEAR(v.area, p.area, 1e-12);
  EXPECT_NEAR(v.mass, p.mass, 1e-12 * p.mass);
  EXPECT_NEAR(v.boundary_length, p.boundary_length, 1e-12);
  // The same loops meshed the same way: the very same mesh.
  EXPECT_EQ(scene_mesh(svg).rest, scene_mesh(polygon).rest);

  // The mesh as invfree itself writes it (simulate --obj's text at step 0), read back.
  const Simulation sim = make_simulation(polygon);
  std::string obj;
  for (const Vec2& x : sim.mesh.rest) {
    char line[96];
    std::snprintf(line, sizeof line, "v %.17g %.17g 0\n", x.x(), x.y());
    obj += line;
  }
  for (const auto& t : sim.mesh.triangles)
    obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
           std::to_string(t[2] + 1) + "\n";
  dir.file("l.obj", obj);
  const SceneDef mesh =
      load(dir.file("mesh.toml", with_mesh_keys("shape = \"mesh\"\nfile = \"l.obj\"\n")));
  const ShapeSummary m = summary(mesh);
  EXPECT_NEAR(m.area, p.area, 1e-12);
  EXPECT_NEAR(m.mass, p.mass, 1e-12 * p.mass);
  EXPECT_NEAR(m.boundary_length, p.boundary_length, 1e-12);
  EXPECT_EQ(m.boundary_edges, p.boundary_edges);
}

// ---- bad input: one line naming the key ------------------------------------------------

struct BadShape {
  const char* what;
  std::string mesh_keys;  // replaces the polygon scene's shape keys
  const char* key;        // the key the error must name
  const char* reason;     // a piece of the reason
};

std::string error_of(const TempDir& dir, const std::string& toml) {
  const SceneLoad l = load_scene(dir.file("bad.toml", toml));
  EXPECT_FALSE(l.scene);
  EXPECT_EQ(l.error.find('\n'), std::string::npos) << l.error;
  return l.error;
}

TEST(ShapeScenes, EveryBadShapeIsRefusedInOneLineNamingItsKey) {
  TempDir dir;
  dir.file("open.svg",
           R"(<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10 0 L 10 10"/></svg>)");
  dir.file("inverted.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n");
  dir.file("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n");
  dir.file("duplicate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 2 3 1\n");
  dir.file("unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 0\nf 1 2 3\n");
  const BadShape cases[] = {
      {"self-intersecting outline",
       "shape = \"polygon\"\noutline = [[0, 0], [1, 1], [1, 0], [0, 1]]\n", "mesh.outline",
       "cross"},
      {"hole outside its outline",
       "shape = \"polygon\"\noutline = [[0, 0], [1, 0], [1, 1], [0, 1]]\n"
       "holes = [[[2, 2], [3, 2], [3, 3]]]\n",
       "mesh.holes", "not inside"},
      {"hole touching its outline",
       "shape = \"polygon\"\noutline = [[0, 0], [1, 0], [1, 1], [0, 1]]\n"
       "holes = [[[0, 0.2], [0.5, 0.2], [0.5, 0.6]]]\n",
       "mesh.holes", "touch"},
      {"fewer than three points", "shape = \"polygon\"\noutline = [[0, 0], [1, 0]]\n",
       "mesh.outline", "three"},
      {"zero area", "shape = \"polygon\"\noutline = [[0, 0], [1, 0], [2, 0]]\n", "mesh.outline",
       "area"},
      {"NaN coordinate", "shape = \"polygon\"\noutline = [[0, 0], [1, 0], [nan, 1]]\n",
       "mesh.outline", "finite"},
      {"infinite coordinate", "shape = \"polygon\"\noutline = [[0, 0], [1, 0], [inf, 1]]\n",
       "mesh.outline", "finite"},
      {"SVG without a closed path", "shape = \"svg\"\nfile = \"open.svg\"\n", "mesh.file",
       "closed path"},
      {"missing file", "shape = \"svg\"\nfile = \"nowhere.svg\"\n", "mesh.file", "nowhere.svg"},
      {"inverted triangle", "shape = \"mesh\"\nfile = \"inverted.obj\"\n", "mesh.file", "inverted"},
      {"degenerate triangle", "shape = \"mesh\"\nfile = \"degenerate.obj\"\n", "mesh.file",
       "degenerate"},
      {"duplicate triangle", "shape = \"mesh\"\nfile = \"duplicate.obj\"\n", "mesh.file",
       "duplicate"},
      {"unused node", "shape = \"mesh\"\nfile = \"unused.obj\"\n", "mesh.file",
       "used by no triangle"},
      {"max_edge past the cap", "shape = \"disk\"\nradius = 0.5\nmax_edge = 1e-5\n",
       "mesh.max_edge", "cap"},
  };
  for (const BadShape& c : cases) {
    std::string text = kPolygonScene;
    const size_t begin = text.find("shape = ");
    const size_t end = text.find("mass = ");
    text.replace(begin, end - begin, c.mesh_keys);
    const std::string e = error_of(dir, text);
    EXPECT_NE(e.find(c.key), std::string::npos) << c.what << ": " << e;
    EXPECT_NE(e.find(c.reason), std::string::npos) << c.what << ": " << e;
  }
}

}  // namespace
}  // namespace invfree
