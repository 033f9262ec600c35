// CGAL's constrained Delaunay mesher behind triangulate_region (triangulate.h): the loops
// become constraints, the domain is marked by nesting parity, the mesher refines step by
// step under a step budget, and the in-domain faces come out renumbered in Morton order.
#include "shape/triangulate.h"

#ifdef INVFREE_NO_CGAL
// A build without CGAL (INVFREE_NO_CGAL) reports meshing unavailable; the web page compiles
// CGAL too (app/web/CMakeLists.txt).
namespace invfree {
Triangulation triangulate_region(const std::vector<RegionLoop>&, double, long) {
  Triangulation out;
  out.error = "meshing is not available in this build (no CGAL)";
  return out;
}
std::optional<bool> loop_is_simple(const Loop&) {
  return std::nullopt;
}
}  // namespace invfree
#else

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <exception>
#include <numeric>
#include <utility>

namespace invfree {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
// Vertex info: the output index (-1 until used). Face info: the nesting level.
using Vb =
    CGAL::Delaunay_mesh_vertex_base_2<K, CGAL::Triangulation_vertex_base_with_info_2<int, K> >;
using Fb = CGAL::Delaunay_mesh_face_base_2<
    K, CGAL::Constrained_Delaunay_triangulation_face_base_2<
           K, CGAL::Constrained_triangulation_face_base_2<
                  K, CGAL::Triangulation_face_base_with_info_2<int, K> > > >;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_2<Cdt, Criteria>;

// Faces reachable from the infinite face without crossing a constraint are level 0; one
// constraint further, level 1; and so on. The region is the odd levels: the outer loops
// and holes of a valid region alternate with nesting depth.
void mark_domain(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<std::pair<Cdt::Face_handle, int> > border{{cdt.infinite_face(), 0}};
  while (!border.empty()) {
    const auto [start, level] = border.front();
    border.pop_front();
    if (start->info() != -1) continue;
    start->info() = level;
    std::deque<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          border.emplace_back(n, level + 1);
        } else {
          n->info() = level;
          queue.push_back(n);
        }
      }
    }
  }
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    f->set_in_domain(f->info() % 2 == 1);
}

// Interleaves the low 21 bits of x and y.
std::uint64_t morton(std::uint32_t x, std::uint32_t y) {
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  return spread(x) | spread(y) << 1;
}

// The in-domain faces as nodes and counter-clockwise triangles, nodes in Morton order of
// their positions (ties by x then y), each triangle starting at its smallest node, the
// list sorted.
void extract(Cdt& cdt, Triangulation& out) {
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) v->info() = -1;
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3> > tris;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    std::array<int, 3> t;
    for (int i = 0; i < 3; ++i) {
      const Cdt::Vertex_handle v = f->vertex(i);
      if (v->info() < 0) {
        v->info() = static_cast<int>(nodes.size());
        nodes.emplace_back(v->point().x(), v->point().y());
      }
      t[i] = v->info();
    }
    tris.push_back(t);
  }
  Eigen::AlignedBox2d box;
  for (const Vec2& p : nodes) box.extend(p);
  const double size = nodes.empty() ? 1.0 : std::max(box.sizes().maxCoeff(), 1e-300);
  const double scale = static_cast<double>((1u << 21) - 1) / size;
  std::vector<std::uint64_t> key(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Vec2 q = (nodes[i] - box.min()) * scale;
    key[i] = morton(static_cast<std::uint32_t>(q.x()), static_cast<std::uint32_t>(q.y()));
  }
  std::vector<int> order(nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (key[a] != key[b]) return key[a] < key[b];
    if (nodes[a].x() != nodes[b].x()) return nodes[a].x() < nodes[b].x();
    return nodes[a].y() < nodes[b].y();
  });
  std::vector<int> new_index(nodes.size());
  out.nodes.resize(nodes.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    new_index[order[k]] = static_cast<int>(k);
    out.nodes[k] = nodes[order[k]];
  }
  for (std::array<int, 3>& t : tris) {
    for (int& v : t) v = new_index[v];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(tris.begin(), tris.end());
  out.triangles = std::move(tris);
}

}  // namespace

std::optional<bool> loop_is_simple(const Loop& loop) {
  try {
    std::vector<K::Point_2> points;
    points.reserve(loop.size());
    for (const Vec2& p : loop) points.emplace_back(p.x(), p.y());
    return CGAL::is_simple_2(points.begin(), points.end(), K());
  } catch (...) {
    return std::nullopt;  // the caller then searches every pair itself
  }
}

Triangulation triangulate_region(const std::vector<RegionLoop>& loops, double max_edge,
                                 long max_steps) {
  Triangulation out;
  try {
    Cdt cdt;
    // One point at a time in loop order, each located from the previous one: no spatial
    // sort (CGAL's shuffles with a time-seeded generator) and short walks along a loop.
    for (const RegionLoop& loop : loops) {
      std::vector<Cdt::Vertex_handle> v;
      v.reserve(loop.points.size());
      Cdt::Face_handle hint;
      for (const Vec2& p : loop.points) {
        v.push_back(cdt.insert(K::Point_2(p.x(), p.y()), hint));
        hint = v.back()->face();
      }
      for (std::size_t i = 0; i < v.size(); ++i) cdt.insert_constraint(v[i], v[(i + 1) % v.size()]);
    }
    mark_domain(cdt);
    Mesher mesher(cdt, Criteria(kShapeBound, max_edge));
    mesher.init(true);
    while (mesher.try_one_step_refine_mesh()) {
      if (++out.refinement_steps > max_steps) {
        out.error = "meshing stopped after " + std::to_string(max_steps) +
                    " refinement steps (features much smaller than max_edge?)";
        return out;
      }
    }
    extract(cdt, out);
    if (out.triangles.empty()) out.error = "meshing gave no triangle";
  } catch (const std::exception& e) {
    out = Triangulation{};
    out.error = std::string("meshing failed: ") + e.what();
  } catch (...) {
    out = Triangulation{};
    out.error = "meshing failed (unknown exception)";
  }
  return out;
}

}  // namespace invfree

#endif  // INVFREE_NO_CGAL
