#include "potential/mass_spring.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace invfree {

namespace {

Vec2 node(const double* x, int i) {
  return {x[2 * i], x[2 * i + 1]};
}

std::pair<int, int> ordered(int a, int b) {
  return {std::min(a, b), std::max(a, b)};
}

double length2(const Mesh& mesh, int a, int b) {
  return (mesh.rest[a] - mesh.rest[b]).squaredNorm();
}

// The triangle's edge (local index k: opposite vertex k) that is strictly its longest.
int longest_edge(const Mesh& mesh, const std::array<int, 3>& t) {
  double l[3];
  for (int k = 0; k < 3; ++k) l[k] = length2(mesh, t[(k + 1) % 3], t[(k + 2) % 3]);
  for (int k = 0; k < 3; ++k)
    if (l[k] > l[(k + 1) % 3] && l[k] > l[(k + 2) % 3]) return k;
  return -1;
}

}  // namespace

std::vector<Spring> mesh_springs(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> edges;  // edge -> the opposite vertex of the first
                                             // triangle whose longest edge it is, or -1
  std::vector<std::pair<int, int>> pairs;
  for (const auto& t : mesh.triangles) {
    const int longest = longest_edge(mesh, t);
    for (int k = 0; k < 3; ++k) {
      const auto e = ordered(t[(k + 1) % 3], t[(k + 2) % 3]);
      auto [it, inserted] = edges.emplace(e, k == longest ? t[k] : -1);
      if (inserted) {
        pairs.push_back(e);
      } else if (k == longest && it->second >= 0) {
        pairs.push_back(ordered(it->second, t[k]));  // the cell's other diagonal
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<Spring> springs;
  springs.reserve(pairs.size());
  for (auto [a, b] : pairs) springs.push_back({a, b, length2(mesh, a, b)});
  return springs;
}

std::vector<Spring> listed_springs(const Mesh& mesh, const std::vector<std::array<int, 2>>& pairs) {
  std::vector<Spring> springs;
  springs.reserve(pairs.size());
  for (const auto& [a, b] : pairs) springs.push_back({a, b, length2(mesh, a, b)});
  return springs;
}

std::vector<double> spring_counts(const std::vector<Spring>& springs, int node_count) {
  std::vector<double> count(node_count, 0.0);
  for (const Spring& s : springs) {
    count[s.i] += 1.0;
    count[s.j] += 1.0;
  }
  return count;
}

std::vector<std::array<int, 2>> spring_node_pairs(const std::vector<Spring>& springs) {
  std::vector<std::array<int, 2>> out;
  out.reserve(springs.size());
  for (const Spring& s : springs) out.push_back({s.i, s.j});
  return out;
}

std::vector<int> spring_slots(const std::vector<Spring>& springs, const SparseHessian& h) {
  std::vector<int> slots;
  slots.reserve(16 * springs.size());
  for (const Spring& s : springs) {
    const int dof[4] = {2 * s.i, 2 * s.i + 1, 2 * s.j, 2 * s.j + 1};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) slots.push_back(sparse_slot(h.matrix, dof[r], dof[c]));
  }
  return slots;
}

double spring_energy(const Spring& s, double k, const Vec2& xi, const Vec2& xj) {
  const double strain = (xi - xj).squaredNorm() / s.rest_length2 - 1.0;
  return 0.5 * k * s.rest_length2 * strain * strain;
}

Vec2 spring_gradient(const Spring& s, double k, const Vec2& xi, const Vec2& xj) {
  const Vec2 d = xi - xj;
  return 2.0 * k * (d.squaredNorm() / s.rest_length2 - 1.0) * d;
}

Mat2 spring_hessian_block(const Spring& s, double k, const Vec2& xi, const Vec2& xj, bool project) {
  const Vec2 d = xi - xj;
  const double d2 = d.squaredNorm(), l2 = s.rest_length2, c = 2.0 * k / l2;
  if (!project) return c * (2.0 * d * d.transpose() + (d2 - l2) * Mat2::Identity());
  const double across = std::max(0.0, c * (d2 - l2));
  if (!(d2 > 0.0)) return across * Mat2::Identity();
  const double along = std::max(0.0, c * (3.0 * d2 - l2));
  const Mat2 dd = d * d.transpose() / d2;
  return along * dd + across * (Mat2::Identity() - dd);
}

double hooke_spring_energy(const Spring& s, double k, const Vec2& xi, const Vec2& xj) {
  const double stretch = (xi - xj).norm() - std::sqrt(s.rest_length2);
  return 0.5 * k * stretch * stretch;
}

Vec2 hooke_spring_gradient(const Spring& s, double k, const Vec2& xi, const Vec2& xj) {
  const Vec2 d = xi - xj;
  const double length = d.norm();
  if (!(length > 0.0)) return Vec2::Zero();
  return k * (length - std::sqrt(s.rest_length2)) * (d / length);
}

Mat2 hooke_spring_hessian_block(const Spring& s, double k, const Vec2& xi, const Vec2& xj,
                                bool project) {
  const Vec2 d = xi - xj;
  const double length = d.norm();
  if (!(length > 0.0)) return Mat2::Zero();
  const Mat2 dd = d * d.transpose() / (length * length);
  double across = k * (1.0 - std::sqrt(s.rest_length2) / length);
  if (project) across = std::max(0.0, across);
  return k * dd + across * (Mat2::Identity() - dd);
}

namespace {

// The sums, one instantiation per law (no branch per spring).
template <bool Hooke>
double energy_sum(const MassSpring& m, const double* x) {
  double e = 0.0;
  for (const Spring& s : *m.springs)
    e += Hooke ? hooke_spring_energy(s, m.stiffness, node(x, s.i), node(x, s.j))
               : spring_energy(s, m.stiffness, node(x, s.i), node(x, s.j));
  return e;
}

template <bool Hooke>
void add_gradient(const MassSpring& m, const double* x, double scale, double* g) {
  for (const Spring& s : *m.springs) {
    const Vec2 gi = scale * (Hooke ? hooke_spring_gradient(s, m.stiffness, node(x, s.i), node(x, s.j))
                                   : spring_gradient(s, m.stiffness, node(x, s.i), node(x, s.j)));
    g[2 * s.i] += gi.x();
    g[2 * s.i + 1] += gi.y();
    g[2 * s.j] -= gi.x();
    g[2 * s.j + 1] -= gi.y();
  }
}

template <bool Hooke>
void add_hessian(const MassSpring& m, const double* x, double scale, double* values) {
  const int* slot = m.slots->data();
  for (const Spring& s : *m.springs) {
    const Vec2 xi = node(x, s.i), xj = node(x, s.j);
    const Mat2 b = scale * (Hooke ? hooke_spring_hessian_block(s, m.stiffness, xi, xj, m.project)
                                  : spring_hessian_block(s, m.stiffness, xi, xj, m.project));
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        const double sign = (r < 2) == (c < 2) ? 1.0 : -1.0;
        values[*slot++] += sign * b(r % 2, c % 2);
      }
  }
}

}  // namespace

double mass_spring_energy(const MassSpring& m, const double* x) {
  return m.hooke ? energy_sum<true>(m, x) : energy_sum<false>(m, x);
}

void add_mass_spring_gradient(const MassSpring& m, const double* x, double scale, double* g) {
  if (m.hooke)
    add_gradient<true>(m, x, scale, g);
  else
    add_gradient<false>(m, x, scale, g);
}

void add_mass_spring_derivatives(const MassSpring& m, const double* x, double scale, double* g,
                                 double* values) {
  add_mass_spring_gradient(m, x, scale, g);
  if (m.hooke)
    add_hessian<true>(m, x, scale, values);
  else
    add_hessian<false>(m, x, scale, values);
}

}  // namespace invfree
