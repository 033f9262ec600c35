#include "scene/initial_state.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "scene/fixed_nodes.h"
#include "scene/reduced_basis.h"
#include "scene/scene_mesh.h"
#include "scene/tractions.h"

namespace invfree {

namespace {
// SplitMix64 (Steele, Lea, Flood 2014): tiny, fast and identical everywhere, unlike the
// standard library's distributions.
double next_uniform(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53 * 2.0 - 1.0;  // [-1, 1)
}
}  // namespace

VecX initial_positions(const SceneDef& scene, const Mesh& mesh) {
  VecX x(2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i) x.segment<2>(2 * i) = mesh.rest[i];
  if (scene.initial_stretch != Vec2(1.0, 1.0))
    for (int i = 0; i < mesh.node_count(); ++i)
      x.segment<2>(2 * i) = x.segment<2>(2 * i).cwiseProduct(scene.initial_stretch);
  if (scene.jitter > 0.0) {
    std::uint64_t state = scene.seed;
    // Held coordinates stay where the stretch put them (a patch test's boundary); their
    // draws are still made, so the free nodes' offsets do not depend on the [fixed] rule.
    std::vector<char> held(x.size(), 0);
    for (int dof : select_fixed_dofs(scene, mesh)) held[dof] = 1;
    // Each body's own edge length; the draws in node order, x then y, as for one body.
    for (size_t body = 0; body < mesh.body_begin.size(); ++body) {
      const double amplitude = scene.jitter * body_edge_length(scene, static_cast<int>(body));
      const int end =
          body + 1 < mesh.body_begin.size() ? mesh.body_begin[body + 1] : mesh.node_count();
      for (int k = 2 * mesh.body_begin[body]; k < 2 * end; ++k) {
        const double offset = amplitude * next_uniform(state);
        if (!held[k]) x[k] += offset;
      }
    }
  }
  return x;
}

VecX initial_velocities(const SceneDef& scene, const Mesh& mesh) {
  // Each node takes its body's velocity (placed_body: the [[body]]'s own, else
  // initial.velocity), a scene of one [[body]] table too.
  VecX v(2 * mesh.node_count());
  for (int i = 0; i < mesh.node_count(); ++i)
    v.segment<2>(2 * i) = placed_body(scene, body_of_node(mesh, i)).velocity;
  return v;
}

namespace {
// With self-contact on (the default), bodies must start apart: each pair's bounding boxes at t = 0
// may not touch (the squares are axis-aligned at rest, so this is their overlap test, made a little
// stricter by jitter), since contact needs a positive distance from the start.
std::optional<SceneProblem> overlapping_bodies(const SceneDef& s, const Mesh& mesh, const VecX& x) {
  const int bodies = static_cast<int>(mesh.body_begin.size());
  if (!s.self_contact_on() || bodies < 2) return std::nullopt;
  std::vector<Eigen::AlignedBox2d> box(bodies);
  for (int i = 0; i < mesh.node_count(); ++i)
    box[body_of_node(mesh, i)].extend(Vec2(x.segment<2>(2 * i)));
  for (int a = 0; a < bodies; ++a)
    for (int b = a + 1; b < bodies; ++b)
      if (box[a].intersects(box[b]))
        return SceneProblem{"body.offset",
                            "[[body]] " + std::to_string(b + 1) + " touches or overlaps [[body]] " +
                                std::to_string(a + 1) +
                                " at t = 0 (self-contact, on by default, needs them apart; "
                                "self_contact.enabled = false lets them overlap)",
                            {"self_contact.enabled", "mesh.side", "mesh.n_seg"}};
  return std::nullopt;
}

// [mass_spring] springs: node pairs of this mesh, two different nodes each, apart at rest
// for the green law (it divides by the rest length; Hooke's allows a zero rest length).
std::optional<SceneProblem> spring_problem(const SceneDef& s, const Mesh& mesh) {
  const int n = mesh.node_count();
  const std::vector<std::string> causes = {"mesh.n_seg", "mesh.shape", "mesh.points"};
  for (size_t k = 0; k < s.springs.size(); ++k) {
    const auto [i, j] = s.springs[k];
    const std::string spring = "spring " + std::to_string(k) + ": ";
    for (int node : {i, j})
      if (node < 0 || node >= n)
        return SceneProblem{"mass_spring.springs",
                            spring + "node " + std::to_string(node) +
                                " is out of range (the mesh has " + std::to_string(n) + " nodes)",
                            causes};
    if (i == j)
      return SceneProblem{
          "mass_spring.springs", spring + "both ends are node " + std::to_string(i), {}};
    if (s.spring_law == SpringLaw::Green && mesh.rest[i] == mesh.rest[j])
      return SceneProblem{"mass_spring.springs",
                          spring + "nodes " + std::to_string(i) + " and " + std::to_string(j) +
                              " share a rest position (the green law divides by the rest length)",
                          {"mass_spring.law", "mesh.points"}};
  }
  return std::nullopt;
}
// A body whose rest triangles lost their area only because its offset is so far from the
// origin that double precision cannot tell its nodes apart (an offset of 1.7e308 for a 1 m
// square): its edge, squared, is a normal double, so its size is not the cause.
std::optional<SceneProblem> far_body_problem(const SceneDef& s, int body) {
  if (s.bodies.empty()) return std::nullopt;
  const PlacedBody b = placed_body(s, body);
  const double edge = body_edge_length(s, body);
  if (b.offset == Vec2::Zero() || !std::isnormal(0.5 * edge * edge)) return std::nullopt;
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "[[body]] %d at [%g, %g] is too far from the origin for its %g m edges: double "
                "precision cannot hold its triangles there",
                body + 1, b.offset.x(), b.offset.y(), edge);
  return SceneProblem{"body.offset", buf, {}};
}

}  // namespace

std::optional<SceneProblem> check_initial_state(const SceneDef& s) {
  const Mesh mesh = scene_mesh(s);
  if (auto problem = spring_problem(s, mesh)) return problem;
  const VecX x = initial_positions(s, mesh);
  if (auto problem = overlapping_bodies(s, mesh, x)) return problem;
  if (auto problem = fixed_rule_problem(s, mesh)) return problem;
  if (auto problem = traction_problem(s, mesh)) return problem;
  if (auto problem = static_support_problem(s, mesh)) return problem;
  if (auto problem = reduced_basis_problem(s, mesh)) return problem;
  const bool needs_det_f_positive = s.has_triangle_elasticity() && !model_allows_inversion(s.model);
  for (const auto& tri : mesh.triangles) {
    // The rest triangle's area must be a normal double: the rest shape's inverse and the
    // node masses divide by it or scale with it.
    Mat2 dm;
    dm.col(0) = mesh.rest[tri[1]] - mesh.rest[tri[0]];
    dm.col(1) = mesh.rest[tri[2]] - mesh.rest[tri[0]];
    if (const double det = dm.determinant(); !std::isnormal(det)) {
      if (auto problem = far_body_problem(s, body_of_node(mesh, tri[0]))) return problem;
      return SceneProblem{"mesh.side",
                          std::string("side / n_seg gives triangles whose area ") +
                              (std::isfinite(det) ? "underflows" : "overflows") +
                              " in double precision",
                          {"mesh.n_seg"}};
    }
    if (!needs_det_f_positive) continue;
    Mat2 ds;
    ds.col(0) = x.segment<2>(2 * tri[1]) - x.segment<2>(2 * tri[0]);
    ds.col(1) = x.segment<2>(2 * tri[2]) - x.segment<2>(2 * tri[0]);
    if (!(ds.determinant() > 0.0))
      return SceneProblem{"mesh.jitter",
                          "the initial mesh has an inverted triangle, which the " +
                              std::string(model_name(s.model)) + " model cannot start from",
                          {"mesh.seed", "material.model", "mesh.side", "mesh.n_seg"}};
  }
  const std::vector<std::string> placement = {"mesh.side", "mesh.jitter", "mesh.seed",
                                              "mesh.n_seg"};
  for (int i = 0; i < mesh.node_count(); ++i) {
    const double y = x[2 * i + 1];
    if (s.has_ground && !(ground_gap(s, x[2 * i], y) > 0.0)) {
      auto causes = placement;
      causes.push_back("ground.enabled");
      causes.push_back("ground.normal");
      causes.push_back("initial.stretch");
      return SceneProblem{"ground.y", "the square starts on or through the ground", causes};
    }
    if (s.has_ceiling && !(y < s.ceiling_y)) {
      auto causes = placement;
      causes.push_back("ceiling.enabled");
      return SceneProblem{"ceiling.y", "the square starts on or through the ceiling", causes};
    }
  }
  return std::nullopt;
}

double estimated_memory_bytes(int n_seg) {
  return estimated_memory_bytes_of_nodes((double(n_seg) + 1.0) * (double(n_seg) + 1.0));
}

double estimated_memory_bytes_of_nodes(double nodes) {
  return nodes * 1024.0 * (1.0 + 0.25 * std::log2(std::max(nodes, 1.0)));
}

namespace {
std::string memory_verdict(const char* what, double needed) {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return "";  // unknown: let the allocator decide
  const double physical = double(pages) * double(page_size);
  if (needed <= 0.8 * physical) return "";
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "%s would need about %.1f GiB, more than this machine's %.1f GiB of memory allows",
                what, needed / double(1 << 30), physical / double(1 << 30));
  return buf;
}
}  // namespace

std::string check_mesh_fits_in_memory(int n_seg) {
  return memory_verdict(std::to_string(n_seg).c_str(), estimated_memory_bytes(n_seg));
}

std::string check_mesh_fits_in_memory(const SceneDef& scene) {
  if (scene.bodies.empty() && scene.shape.kind == ShapeKind::Square)
    return check_mesh_fits_in_memory(scene.n_seg);
  // A meshed shape's nodes are known once it is meshed: find_scene_problem checks them
  // (check_nodes_fit_in_memory) after the mesher, whose own cap comes first.
  double needed = 0.0;
  for (int b = 0; b < body_count(scene); ++b)
    if (const PlacedBody body = placed_body(scene, b); body.shape.kind == ShapeKind::Square)
      needed += estimated_memory_bytes(body.n_seg);
  return memory_verdict("these bodies", needed);
}

std::string check_nodes_fit_in_memory(double nodes) {
  return memory_verdict("this mesh", estimated_memory_bytes_of_nodes(nodes));
}

}  // namespace invfree
