#include "scene/initial_state.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "scene/fixed_nodes.h"

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
    const double amplitude = scene.jitter * scene.side / scene.n_seg;
    for (int k = 0; k < x.size(); ++k) x[k] += amplitude * next_uniform(state);
  }
  return x;
}

std::optional<SceneProblem> check_initial_state(const SceneDef& s) {
  const Mesh mesh = square_mesh(s.side, s.n_seg);
  const VecX x = initial_positions(s, mesh);
  if (auto problem = fixed_rule_problem(s, mesh)) return problem;
  const bool needs_det_f_positive = s.has_triangle_elasticity() && !model_allows_inversion(s.model);
  for (const auto& tri : mesh.triangles) {
    // The rest triangle's area must be a normal double: the rest shape's inverse and the
    // node masses divide by it or scale with it.
    Mat2 dm;
    dm.col(0) = mesh.rest[tri[1]] - mesh.rest[tri[0]];
    dm.col(1) = mesh.rest[tri[2]] - mesh.rest[tri[0]];
    if (const double det = dm.determinant(); !std::isnormal(det))
      return SceneProblem{"mesh.side",
                          std::string("side / n_seg gives triangles whose area ") +
                              (std::isfinite(det) ? "underflows" : "overflows") +
                              " in double precision",
                          {"mesh.n_seg"}};
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
  const double nodes = (double(n_seg) + 1.0) * (double(n_seg) + 1.0);
  return nodes * 1024.0 * (1.0 + 0.25 * std::log2(nodes));
}

std::string check_mesh_fits_in_memory(int n_seg) {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return "";  // unknown: let the allocator decide
  const double physical = double(pages) * double(page_size);
  const double needed = estimated_memory_bytes(n_seg);
  if (needed <= 0.8 * physical) return "";
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "%d would need about %.1f GiB, more than this machine's %.1f GiB of memory allows",
                n_seg, needed / double(1 << 30), physical / double(1 << 30));
  return buf;
}

}  // namespace invfree
