#include "potential/elasticity.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "potential/work_blocks.h"

namespace invfree {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}
}  // namespace

double elastic_energy(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                      std::span<const Lame> triangle_lame) {
  return visit_model(model, [&](auto m) {
    return elastic_energy_range<decltype(m)>(
        mesh, lame, x.data(), 0, mesh.triangle_count(),
        triangle_lame.empty() ? nullptr : triangle_lame.data());
  });
}

void add_elastic_gradient(const Mesh& mesh, Model model, const Lame& lame, const VecX& x,
                          double scale, VecX& g, std::span<const Lame> triangle_lame) {
  visit_model(model, [&](auto m) {
    using M = decltype(m);
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Mat46 dFdx = deformation_gradient_jacobian(mesh.rest_shape_inverse[t]);
      const Vec6 gt = TriangleElasticity<M>::gradient(
          triangle_deformation_gradient(mesh, x.data(), t), dFdx, scale * mesh.rest_area[t],
          triangle_lame.empty() ? lame : triangle_lame[t]);
      const auto& tri = mesh.triangles[t];
      for (int a = 0; a < 3; ++a) g.segment<2>(2 * tri[a]) += gt.segment<2>(2 * a);
    }
  });
}

double Elasticity::value(const TermPoint& at, double scale) const {
  const int nt = at.mesh.triangle_count();
  const BlockSplit tri = split_blocks(nt, kTriangleBlock, kMaxBlocks);
  double partial[kMaxBlocks];
  visit_model(model, [&](auto m) {
    run_blocks(tri.blocks, [&](int b) {
      partial[b] = elastic_energy_range<decltype(m)>(at.mesh, lame, at.z.data(), tri.begin(b),
                                                     tri.end(b, nt), triangle_lame);
    });
  });
  double elastic = 0.0;
  for (int b = 0; b < tri.blocks; ++b) elastic += partial[b];
  return scale * elastic;
}

void Elasticity::add_derivatives(const TermPoint& at, double scale, Assembly& out) const {
  SparseHessian& hess = out.hessian;
  const bool parallel = at.mesh.triangle_count() >= kParallelTriangles;
  visit_model(model, [&](auto m) {
    using M = decltype(m);
    for (int colour = 0; colour < hess.colour_count(); ++colour) {
      const int first = hess.colour_begin[colour], count = hess.colour_begin[colour + 1] - first;
      auto chunk = [&](int k) {
        const int begin = hess.chunk_order[first + k] * hess.chunk_size;
        const int end = std::min(at.mesh.triangle_count(), begin + hess.chunk_size);
        add_elastic_derivatives_range<M>(at.mesh, *this, at.z.data(), begin, end, scale,
                                         out.gradient.data(), hess);
      };
      if (parallel) {
        thread_pool().run(count, chunk);
      } else {
        for (int k = 0; k < count; ++k) chunk(k);
      }
    }
  });
}

double Elasticity::max_step(const TermPoint& at, const VecX& dir, double alpha) const {
  if (!filters_inversions()) return alpha;
  return std::min(alpha, inversion_free_step(at.mesh, at.z, dir));
}

void Elasticity::add_explicit_force(const TermPoint& at, VecX& gradient) const {
  const std::span<const Lame> own =
      triangle_lame ? std::span<const Lame>(triangle_lame, at.mesh.triangle_count())
                    : std::span<const Lame>();
  add_elastic_gradient(at.mesh, model, lame, at.z, 1.0, gradient, own);
}

double smallest_positive_root(double a, double b, double c) {
  if (a == 0.0) {
    if (b == 0.0) return kInf;
    const double t = -c / b;
    return t > 0.0 ? t : kInf;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return kInf;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double best = kInf;
  const double r1 = q / a;
  if (r1 > 0.0) best = r1;
  if (q != 0.0) {
    const double r2 = c / q;
    if (r2 > 0.0) best = std::min(best, r2);
  }
  return best;
}

// The smallest step over fixed blocks of triangles: a minimum, so exact in any order.
double inversion_free_step(const Mesh& mesh, const VecX& x, const VecX& p) {
  const int nt = mesh.triangle_count();
  const BlockSplit tri = split_blocks(nt, kTriangleBlock, kMaxBlocks);
  double partial[kMaxBlocks];
  run_blocks(tri.blocks, [&](int b) {
    double alpha = 1.0;
    for (int t = tri.begin(b), end = tri.end(b, nt); t < end; ++t) {
      const auto& v = mesh.triangles[t];
      const Vec2 x1 = x.segment<2>(2 * v[0]);
      const Vec2 x21 = x.segment<2>(2 * v[1]) - x1, x31 = x.segment<2>(2 * v[2]) - x1;
      const Vec2 p1 = p.segment<2>(2 * v[0]);
      const Vec2 p21 = p.segment<2>(2 * v[1]) - p1, p31 = p.segment<2>(2 * v[2]) - p1;
      const double area = cross(x21, x31);
      const double a = cross(p21, p31) / area;
      const double b_coef = (cross(x21, p31) + cross(p21, x31)) / area;
      alpha = std::min(alpha, smallest_positive_root(a, b_coef, 1.0 - kMinAreaFraction));
    }
    partial[b] = alpha;
  });
  double alpha = 1.0;
  for (int b = 0; b < tri.blocks; ++b) alpha = std::min(alpha, partial[b]);
  return alpha;
}

double signed_area(const VecX& x, const std::array<int, 3>& t) {
  return cross(x.segment<2>(2 * t[1]) - x.segment<2>(2 * t[0]),
               x.segment<2>(2 * t[2]) - x.segment<2>(2 * t[0]));
}

}  // namespace invfree
