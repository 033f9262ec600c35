// material/stress_analysis.* and triangle_fields.*: what `invfree inspect` and the live
// inspector show, checked against an independent fourth-order finite-difference evaluation
// of Psi written here (not the library's finite_difference_errors), for every model over
// a sweep of F: near sigma1 = sigma2, near J -> 0+, large stretch, pure rotations, rotation
// times stretch, and inverted F for the invertible models. The eigenvalues are compared with
// the eigenvalues of the finite-difference Hessian as multisets, `clamped` with its number
// of negative eigenvalues. Then the library's own finite-difference check is shown able to
// fail, and triangle_at / analyze_triangle are checked on simulations.
#include "material/stress_analysis.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "material/models.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/scene_file.h"
#include "simulation.h"
#include "triangle_fields.h"

namespace invfree {
namespace {

const Model kAllModels[] = {Model::NeoHookean, Model::Linear, Model::Arap, Model::StableNeoHookean};

Mat2 rot(double angle) {
  Mat2 r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return r;
}

// F = R(a) diag(s1, s2) R(b)^T.
Mat2 make_F(double a, double s1, double s2, double b) {
  return rot(a) * Vec2(s1, s2).asDiagonal() * rot(b).transpose();
}

struct Sample {
  std::string what;
  Mat2 F;
};

// The sweep. Every F is a rotation times a stretch times a rotation (the pure ones with
// zero angles or unit stretches), in the groups the lecture's derivation cares about.
std::vector<Sample> sweep(bool inverted) {
  std::vector<Sample> out;
  const double angles[][2] = {{0.0, 0.0}, {0.3, -1.1}, {2.5, 0.7}, {-2.9, 3.0}};
  const auto add = [&](const std::string& what, double s1, double s2) {
    for (const auto& ab : angles) {
      std::ostringstream name;
      name << what << " sigma = (" << s1 << ", " << s2 << "), angles (" << ab[0] << ", " << ab[1]
           << ")";
      out.push_back({name.str(), make_F(ab[0], s1, s2, ab[1])});
    }
  };
  if (!inverted) {
    // Near sigma1 = sigma2: the flip's (Psi_1 - Psi_2)/(s1 - s2) is 0/0 there.
    add("equal", 1.3, 1.3);
    add("near-equal", 0.7, 0.7 * (1.0 - 1e-9));
    add("near-equal", 1.6, 1.6 * (1.0 - 1e-6));
    // Near J -> 0+: neo-Hookean's barrier.
    add("thin", 1.0, 1e-2);
    add("thin", 1.5, 1e-3);
    add("thin", 0.5, 1e-2);
    // Large stretch.
    add("large", 3.0, 1.0);
    add("large", 5.0, 4.0);
    add("large", 4.5, 0.5);
    // Moderate stretch and compression.
    add("moderate", 1.2, 0.9);
    add("moderate", 0.8, 0.6);
    add("moderate", 1.1, 1.05);
    // Pure rotations (sigma = 1, 1).
    for (double a : {0.0, 0.4, 1.9, -2.6, 3.1}) {
      std::ostringstream name;
      name << "rotation by " << a;
      out.push_back({name.str(), rot(a)});
    }
  } else {
    // Inverted: sigma2 < 0 (the polar SVD's sign convention); away from s1 + s2 = 0,
    // where ARAP's polar rotation is undefined.
    add("inverted", 1.0, -0.5);
    add("inverted", 1.2, -0.3);
    add("inverted", 2.0, -1.0);
    add("inverted", 0.8, -0.1);
    add("inverted", 3.0, -2.5);
    add("inverted", 1.0, -1e-3);
  }
  return out;
}

// Two Lame pairs: lambda > mu (compressible rubber) and lambda < mu.
const Lame kLames[] = {{1.0, 4.0}, {3.0, 0.5}};

// ---------------------------------------------------------------------------------------
// The independent check: fourth-order central differences of Psi alone.

struct Differences {
  Mat2 P;  // dPsi/dF
  Mat4 H;  // d2Psi/dF2, flattened [F11, F21, F12, F22]
};

Differences differences(Model model, const Mat2& F, const Lame& lame) {
  const Eigen::JacobiSVD<Mat2> svd(F);
  const double s_max = svd.singularValues()(0), s_min = svd.singularValues()(1);
  // Steps small against F and against the distance to where the energy is singular: for
  // the barrier model the smallest singular value (J changes by about h s_max, J itself is
  // s_max s_min), for the others s1 + s2 (signed), where ARAP's polar rotation is undefined.
  double h = 1e-3 * s_max;
  if (!model_allows_inversion(model))
    h = std::min(h, 3e-3 * s_min);
  else
    h = std::min(h, 3e-3 * (s_max + (F.determinant() < 0.0 ? -s_min : s_min)));
  const auto psi = [&](const Vec4& f) {
    return energy_density(model, Eigen::Map<const Mat2>(f.data()), lame);
  };
  const Vec4 f0 = Eigen::Map<const Vec4>(F.data());
  const Mat4 I = Mat4::Identity();
  // First derivative, 4th order: (-f(2h) + 8 f(h) - 8 f(-h) + f(-2h)) / 12h.
  const double c[4] = {-1.0, 8.0, -8.0, 1.0};
  const double o[4] = {2.0, 1.0, -1.0, -2.0};
  Differences d;
  Vec4 g;
  for (int i = 0; i < 4; ++i) {
    double s = 0.0;
    for (int k = 0; k < 4; ++k) s += c[k] * psi(f0 + o[k] * h * I.col(i));
    g(i) = s / (12.0 * h);
  }
  d.P = Eigen::Map<const Mat2>(g.data());
  for (int i = 0; i < 4; ++i) {
    // Second derivative, 4th order: (-f(2h) + 16 f(h) - 30 f(0) + 16 f(-h) - f(-2h)) / 12h^2.
    d.H(i, i) = (-psi(f0 + 2 * h * I.col(i)) + 16 * psi(f0 + h * I.col(i)) - 30 * psi(f0) +
                 16 * psi(f0 - h * I.col(i)) - psi(f0 - 2 * h * I.col(i))) /
                (12.0 * h * h);
    // Mixed: the 4th-order first difference applied in i and then in j.
    for (int j = i + 1; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          s += c[k] * c[l] * psi(f0 + o[k] * h * I.col(i) + o[l] * h * I.col(j));
      d.H(i, j) = d.H(j, i) = s / (144.0 * h * h);
    }
  }
  return d;
}

Vec4 sorted(Vec4 v) {
  std::sort(v.data(), v.data() + 4);
  return v;
}

// How far the analysis may be from the finite differences: dP/dF relative to the Hessian's
// norm (the differences' own error, measured over the sweep: up to 4.4e-9, linear
// elasticity at large stretch, where rounding dominates; the test prints the worst), P
// relative with an absolute part for rounding (measured up to 1.6e-10).
constexpr double kHessianTolerance = 1e-8;
constexpr double kStressTolerance = 1e-9;
constexpr double kStressNoise = 1e-10;  // of mu + |lambda| times |F|

struct SweepCounts {
  int samples = 0, with_clamped = 0, clamped_checked = 0;
  double worst_P = 0.0, worst_H = 0.0;
};

void check_sample(Model model, const Lame& lame, const Sample& sample, SweepCounts* counts) {
  const Mat2& F = sample.F;
  SCOPED_TRACE(std::string(model_name(model)) + ", mu " + std::to_string(lame.mu) + ", lambda " +
               std::to_string(lame.lambda) + ": " + sample.what);
  const StressAnalysis a = analyze_stress(model, F, lame);
  ASSERT_TRUE(a.finite);
  const Differences d = differences(model, F, lame);
  ++counts->samples;

  // F, its polar SVD, J, psi.
  EXPECT_EQ(a.model, model);
  EXPECT_EQ(a.lame, lame);
  EXPECT_EQ(a.F, F);
  const double scale_F = F.norm();
  EXPECT_LT((a.svd.U * a.svd.sigma.asDiagonal() * a.svd.V.transpose() - F).norm(), 1e-14 * scale_F);
  for (const Mat2* R : {&a.svd.U, &a.svd.V}) {
    EXPECT_LT((R->transpose() * *R - Mat2::Identity()).norm(), 1e-14);
    EXPECT_NEAR(R->determinant(), 1.0, 1e-14);  // rotations, not reflections
  }
  const Eigen::JacobiSVD<Mat2> svd(F);
  EXPECT_NEAR(a.svd.sigma(0), svd.singularValues()(0), 1e-14 * scale_F);
  EXPECT_NEAR(std::abs(a.svd.sigma(1)), svd.singularValues()(1), 1e-14 * scale_F);
  EXPECT_GE(a.svd.sigma(0), std::abs(a.svd.sigma(1)));
  EXPECT_EQ(a.svd.sigma(1) < 0.0, F.determinant() < 0.0);  // the lecture's Algorithm 6
  EXPECT_NEAR(a.J, F.determinant(), 1e-15 * scale_F * scale_F);
  EXPECT_EQ(a.psi, energy_density(model, F, lame));

  // P against the differences of Psi.
  // Relative, with an absolute part for the differences' own rounding (measured about
  // 2e-12 of the stiffness mu + |lambda| here; P = 0 exactly at a rotation).
  const double stiffness = lame.mu + std::abs(lame.lambda);
  const double floor = 1e-4 * stiffness;
  const double err_P =
      (a.P - d.P).norm() / (d.P.norm() + kStressNoise / kStressTolerance * stiffness * F.norm());
  EXPECT_LT(err_P, kStressTolerance) << "P\n" << a.P << "\nfinite differences\n" << d.P;
  counts->worst_P = std::max(counts->worst_P, err_P);

  // dP/dF (the unprojected 4x4 the solver builds) against the second differences.
  const Mat4 C = exact_stress_derivative(model, F, lame);
  const double norm_H = d.H.norm();
  const double err_H = (C - d.H).norm() / norm_H;
  EXPECT_LT(err_H, kHessianTolerance) << "dP/dF\n" << C << "\nfinite differences\n" << d.H;
  counts->worst_H = std::max(counts->worst_H, err_H);

  // The four eigenvalues against the finite-difference Hessian's, as multisets.
  const Eigen::SelfAdjointEigenSolver<Mat4> eig(d.H);
  const Vec4 fd_values = eig.eigenvalues();  // ascending
  const double noise = kHessianTolerance * norm_H;
  EXPECT_LT((sorted(a.eigenvalues) - fd_values).cwiseAbs().maxCoeff(), noise)
      << "analysis " << a.eigenvalues.transpose() << "\nfinite differences "
      << fd_values.transpose();
  // The scaling pair comes larger first.
  EXPECT_GE(a.eigenvalues(0), a.eigenvalues(1));

  // Each eigenvalue with its mode (material/stress_analysis.h): the flip
  // (u1 v2^T + u2 v1^T)/sqrt2 and the twist (u2 v1^T - u1 v2^T)/sqrt2 are eigenvectors of the
  // finite-difference Hessian with eigenvalues 2 and 3; span{u1 v1^T, u2 v2^T} is invariant
  // and holds eigenvalues 0 and 1. Linear elasticity is reported in the basis at U = V = I.
  {
    const Mat2 U = model == Model::Linear ? Mat2::Identity() : a.svd.U;
    const Mat2 V = model == Model::Linear ? Mat2::Identity() : a.svd.V;
    const Vec2 u1 = U.col(0), u2 = U.col(1), v1 = V.col(0), v2 = V.col(1);
    const Vec4 a12 = flatten(u1 * v2.transpose()), a21 = flatten(u2 * v1.transpose());
    const Vec4 flip = (a12 + a21) / std::sqrt(2.0), twist = (a21 - a12) / std::sqrt(2.0);
    EXPECT_LT((d.H * flip - a.eigenvalues(2) * flip).norm(), noise) << "flip";
    EXPECT_LT((d.H * twist - a.eigenvalues(3) * twist).norm(), noise) << "twist";
    Eigen::Matrix<double, 4, 2> B;
    B << flatten(u1 * v1.transpose()), flatten(u2 * v2.transpose());
    const Mat2 M = B.transpose() * d.H * B;
    EXPECT_LT((d.H * B - B * M).norm(), 2 * noise) << "the scaling modes' plane";
    const Eigen::SelfAdjointEigenSolver<Mat2> scaling(M);
    EXPECT_NEAR(a.eigenvalues(0), scaling.eigenvalues()(1), noise);
    EXPECT_NEAR(a.eigenvalues(1), scaling.eigenvalues()(0), noise);
  }

  // The projection: the negative ones set to zero, the others kept; as the finite-
  // difference Hessian's clamped eigenvalues, and as the projected dP/dF the solver uses.
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(a.projected_eigenvalues(k), std::max(a.eigenvalues(k), 0.0)) << k;
  EXPECT_LT((sorted(a.projected_eigenvalues) - fd_values.cwiseMax(0.0)).cwiseAbs().maxCoeff(),
            noise);
  const Eigen::SelfAdjointEigenSolver<Mat4> projected(stress_derivative(model, F, lame, true));
  EXPECT_LT((sorted(a.projected_eigenvalues) - projected.eigenvalues()).cwiseAbs().maxCoeff(),
            1e-12 * norm_H);

  // `clamped`: the number of negative eigenvalues of the finite-difference Hessian, where
  // no eigenvalue is within the differences' noise of zero (exact zeros, as linear
  // elasticity's twist, count as not negative). Pure rotations put the twist of every
  // rotation-invariant model at zero up to rounding: their sign is not checked.
  bool determinate = true;
  for (int k = 0; k < 4; ++k)
    if (a.eigenvalues(k) != 0.0 && std::abs(a.eigenvalues(k)) < noise) determinate = false;
  const int fd_negative = static_cast<int>((fd_values.array() < -noise).count());
  if (determinate) {
    EXPECT_EQ(a.clamped, fd_negative) << "eigenvalues " << a.eigenvalues.transpose();
    ++counts->clamped_checked;
  }
  EXPECT_EQ(a.clamped, static_cast<int>((a.eigenvalues.array() < 0.0).count()));
  EXPECT_EQ(clamped_eigenvalue_count(model, F, lame), a.clamped);
  if (a.clamped > 0) ++counts->with_clamped;

  // The Cauchy stress: P F^T / J; symmetric for the rotation-invariant models.
  const Mat2 cauchy = a.P * F.transpose() / a.J;
  // (Symmetrising removes a skew part of the product's rounding, eps |P| |F| / |J|.)
  EXPECT_LT((a.cauchy - cauchy).norm(), 1e-14 * a.P.norm() * F.norm() / std::abs(a.J) + 1e-300);
  if (model != Model::Linear) {
    EXPECT_EQ(a.cauchy, a.cauchy.transpose());
  }
  // Principal stresses: eigenpairs of the (symmetric part of the) Cauchy stress, larger
  // first, unit orthogonal directions.
  const Mat2 sym = 0.5 * (a.cauchy + a.cauchy.transpose());
  const double scale_c = std::max(sym.norm(), floor);
  EXPECT_GE(a.principal_stress(0), a.principal_stress(1));
  for (int k = 0; k < 2; ++k) {
    const Vec2 dir = a.principal_directions.col(k);
    EXPECT_NEAR(dir.norm(), 1.0, 1e-14);
    EXPECT_LT((sym * dir - a.principal_stress(k) * dir).norm(), 1e-13 * scale_c) << k;
  }
  EXPECT_NEAR(a.principal_directions.col(0).dot(a.principal_directions.col(1)), 0.0, 1e-14);
  const Eigen::SelfAdjointEigenSolver<Mat2> ceig(sym);
  EXPECT_NEAR(a.principal_stress(0), ceig.eigenvalues()(1), 1e-13 * scale_c);
  EXPECT_NEAR(a.principal_stress(1), ceig.eigenvalues()(0), 1e-13 * scale_c);
  const double largest = std::abs(a.principal_stress(0)) >= std::abs(a.principal_stress(1))
                             ? a.principal_stress(0)
                             : a.principal_stress(1);
  EXPECT_EQ(signed_max_principal_stress(model, F, lame), largest);
  EXPECT_EQ(energy_density_of(model, F, lame), a.psi);

  // The library's own finite-difference check agrees that the derivatives are right.
  const FiniteDifferenceErrors fd = finite_difference_errors(model, F, lame);
  EXPECT_LT(fd.P, 1e-6);
  EXPECT_LT(fd.dPdF, 1e-4);
}

TEST(StressAnalysis, EveryModelMatchesFiniteDifferencesOverTheSweep) {
  for (Model model : kAllModels) {
    SweepCounts counts;
    for (const Lame& lame : kLames) {
      for (const Sample& s : sweep(false)) check_sample(model, lame, s, &counts);
      if (model_allows_inversion(model))
        for (const Sample& s : sweep(true)) check_sample(model, lame, s, &counts);
    }
    std::printf(
        "%-20s %3d F: clamped checked at %d (%d with clamped > 0); worst |P - fd| %.2g, "
        "|dP/dF - fd| %.2g (relative)\n",
        model_name(model), counts.samples, counts.clamped_checked, counts.with_clamped,
        counts.worst_P, counts.worst_H);
    // The sweep must exercise the clamping (every model but linear elasticity has negative
    // eigenvalues somewhere in it) and its check must not be skipped wholesale.
    EXPECT_GE(counts.clamped_checked, counts.samples - 2 * 5) << model_name(model);
    if (model != Model::Linear) {
      EXPECT_GE(counts.with_clamped, 10) << model_name(model);
    }
  }
}

// The library's finite-difference check must be able to fail: fed a wrong P or a wrong
// dP/dF (the classic slips: a Lame parameter off, the flip and twist eigenvalues swapped,
// the projected derivative for the exact one) it reports a large error; fed the right ones
// a small one. Its own P_fd agrees with the independent differences above.
TEST(StressAnalysis, FiniteDifferenceCheckCatchesWrongDerivatives) {
  const Lame lame{1.0, 4.0};
  const Lame off{1.0, 4.0 * 1.01};
  int checked = 0;
  for (const Sample& s : sweep(false)) {
    if (s.what.rfind("rotation", 0) == 0) continue;  // P = 0 there: nothing to get wrong
    SCOPED_TRACE(s.what);
    const Mat2& F = s.F;
    const auto psi = [&](const Mat2& G) { return energy_density(Model::NeoHookean, G, lame); };
    const Mat2 P = first_piola(Model::NeoHookean, F, lame);
    const Mat4 C = exact_stress_derivative(Model::NeoHookean, F, lame);
    const double floor = 1e-4 * (lame.mu + lame.lambda);
    const FiniteDifferenceErrors right = finite_difference_errors(psi, P, C, F, true, floor);
    EXPECT_LT(right.P, 1e-6);
    EXPECT_LT(right.dPdF, 1e-4);
    // The model version is this one.
    const FiniteDifferenceErrors model = finite_difference_errors(Model::NeoHookean, F, lame);
    EXPECT_EQ(model.P, right.P);
    EXPECT_EQ(model.dPdF, right.dPdF);
    const Differences d = differences(Model::NeoHookean, F, lame);
    EXPECT_LT((model.P_fd - d.P).norm(), 1e-6 * d.P.norm());
    EXPECT_LT((model.dPdF_fd - d.H).norm(), 1e-4 * d.H.norm());

    // Each wrong one reports an error at least 100 times the right one's, and above 1e-4.
    // (Relative to |dP/dF|: near J -> 0 the huge scaling block dominates that norm, so a
    // wrong flip or twist shows as about 1e-3 there, against 1e-6 when right.)
    const auto wrong = [&](double error, double right_error) {
      return error > std::max(100.0 * right_error, 1e-4);
    };
    // lambda 1% off in P.
    const Mat2 P_off = first_piola(Model::NeoHookean, F, off);
    EXPECT_TRUE(wrong(finite_difference_errors(psi, P_off, C, F, true, floor).P, right.P));
    // Flip and twist swapped in dP/dF.
    const PolarSvd svd = polar_svd(F);
    DiagonalHessian swapped = NeoHookean::diagonal_hessian(svd.sigma, lame);
    std::swap(swapped.flip, swapped.twist);
    const Mat4 C_swapped = compose_stress_derivative(svd, swapped, false);
    EXPECT_TRUE(
        wrong(finite_difference_errors(psi, P, C_swapped, F, true, floor).dPdF, right.dPdF));
    // The projected derivative where the projection clamps something.
    if (clamped_eigenvalue_count(Model::NeoHookean, F, lame) > 0) {
      const Mat4 C_projected = stress_derivative(Model::NeoHookean, F, lame, true);
      EXPECT_TRUE(
          wrong(finite_difference_errors(psi, P, C_projected, F, true, floor).dPdF, right.dPdF));
    }
    ++checked;
  }
  EXPECT_GE(checked, 40);
}

// Where neo-Hookean's energy is +inf (J <= 0) the analysis says so and reports no stress.
TEST(StressAnalysis, InvertedNeoHookeanIsNotFinite) {
  const Lame lame{1.0, 4.0};
  for (const Mat2& F :
       {make_F(0.3, 1.0, -0.5, 0.2), Mat2(Mat2::Zero()), make_F(0.0, 1.0, 0.0, 0.0)}) {
    const StressAnalysis a = analyze_stress(Model::NeoHookean, F, lame);
    EXPECT_FALSE(a.finite);
    EXPECT_EQ(a.psi, std::numeric_limits<double>::infinity());
    EXPECT_EQ(a.P, Mat2::Zero());
    EXPECT_EQ(a.clamped, 0);
    EXPECT_EQ(clamped_eigenvalue_count(Model::NeoHookean, F, lame), 0);
    EXPECT_EQ(signed_max_principal_stress(Model::NeoHookean, F, lame), 0.0);
    const FiniteDifferenceErrors fd = finite_difference_errors(Model::NeoHookean, F, lame);
    EXPECT_EQ(fd.P, 0.0);
    EXPECT_EQ(fd.dPdF, 0.0);
  }
  // The invertible models are finite there (where defined: not at F = 0 for ARAP's rotation).
  for (Model m : {Model::Linear, Model::Arap, Model::StableNeoHookean})
    EXPECT_TRUE(analyze_stress(m, make_F(0.3, 1.0, -0.5, 0.2), lame).finite) << model_name(m);
}

// Linear elasticity is not rotation invariant: its P F^T / J keeps a skew part, which the
// analysis reports as it is (stress_analysis.h), while the principal stresses are those of
// its symmetric part.
TEST(StressAnalysis, LinearCauchyStressKeepsItsSkewPart) {
  const Lame lame{1.0, 4.0};
  const Mat2 F = make_F(0.7, 1.3, 0.8, -0.2);
  const StressAnalysis a = analyze_stress(Model::Linear, F, lame);
  const Mat2 expected = a.P * F.transpose() / a.J;
  EXPECT_LT((a.cauchy - expected).norm(), 1e-14 * expected.norm());
  EXPECT_GT((a.cauchy - a.cauchy.transpose()).norm(), 1e-2 * a.cauchy.norm());
}

// --- On a simulation: triangle_at, analyze_triangle, triangle_field ------------------------

Simulation stepped(const SceneDef& scene, int steps) {
  Simulation sim = make_simulation(scene);
  for (int k = 0; k < steps; ++k) {
    const StepReport r = step(sim);
    EXPECT_EQ(r.status, StepStatus::Ok) << r.message;
  }
  return sim;
}

Vec2 node(const Simulation& sim, int i) {
  return Vec2(sim.x[2 * i], sim.x[2 * i + 1]);
}

Vec2 centroid(const Simulation& sim, int t) {
  const auto& tri = sim.mesh.triangles[static_cast<size_t>(t)];
  return (node(sim, tri[0]) + node(sim, tri[1]) + node(sim, tri[2])) / 3.0;
}

double signed_area(const Simulation& sim, int t) {
  const auto& tri = sim.mesh.triangles[static_cast<size_t>(t)];
  const Vec2 e1 = node(sim, tri[1]) - node(sim, tri[0]), e2 = node(sim, tri[2]) - node(sim, tri[0]);
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}

// Each triangle's centroid (in the deformed body, after 40 steps of compress) is in that
// triangle and no other; points well outside the body are in none.
TEST(TriangleAt, FindsTheTriangleUnderAPoint) {
  const Simulation sim = stepped(*load_builtin_scene("compress").scene, 40);
  const int n = sim.mesh.triangle_count();
  ASSERT_EQ(n, 32);
  for (int t = 0; t < n; ++t) {
    ASSERT_GT(signed_area(sim, t), 0.0);
    EXPECT_EQ(triangle_at(sim, centroid(sim, t)), std::optional<int>(t)) << t;
  }
  // The body's bounding box, and points beyond it.
  Vec2 lo = node(sim, 0), hi = lo;
  for (int i = 0; i < sim.mesh.node_count(); ++i) {
    lo = lo.cwiseMin(node(sim, i));
    hi = hi.cwiseMax(node(sim, i));
  }
  for (const Vec2& p :
       {Vec2(hi.x() + 0.01, 0.5 * (lo.y() + hi.y())), Vec2(lo.x() - 1.0, lo.y()),
        Vec2(0.5 * (lo.x() + hi.x()), hi.y() + 1e-3), Vec2(100.0, -100.0), Vec2(std::nan(""), 0.0),
        Vec2(0.0, std::numeric_limits<double>::infinity())})
    EXPECT_EQ(triangle_at(sim, p), std::nullopt) << p.transpose();
  // A shared node is in every triangle around it: the smallest index is reported.
  const int shared = sim.mesh.triangles[5][1];
  int first = n;
  for (int t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
      if (sim.mesh.triangles[static_cast<size_t>(t)][k] == shared) first = std::min(first, t);
  EXPECT_EQ(triangle_at(sim, node(sim, shared)), std::optional<int>(first));
}

// Inverted (clockwise) triangles are found as well: the whole body mirrored, so that every
// triangle is clockwise; and one triangle folded over its neighbour; and a triangle
// collapsed to a segment contains nothing.
TEST(TriangleAt, FindsInvertedTriangles) {
  Simulation sim = make_simulation(*load_builtin_scene("compress").scene);
  const int n = sim.mesh.triangle_count();
  for (int i = 0; i < sim.mesh.node_count(); ++i) sim.x[2 * i] = -sim.x[2 * i];
  for (int t = 0; t < n; ++t) {
    ASSERT_LT(signed_area(sim, t), 0.0);
    EXPECT_EQ(triangle_at(sim, centroid(sim, t)), std::optional<int>(t)) << t;
  }

  // Fold: move one node of triangle t across its opposite edge, so that t turns clockwise,
  // beyond the body's boundary where no other triangle is.
  Simulation folded = make_simulation(*load_builtin_scene("compress").scene);
  // A corner node of the square belongs to one or two triangles; take the bottom-left one.
  int corner = 0;
  for (int i = 0; i < folded.mesh.node_count(); ++i)
    if (node(folded, i).sum() < node(folded, corner).sum()) corner = i;
  int t_fold = -1;
  for (int t = 0; t < n && t_fold < 0; ++t)
    for (int k = 0; k < 3; ++k)
      if (folded.mesh.triangles[static_cast<size_t>(t)][k] == corner) t_fold = t;
  ASSERT_GE(t_fold, 0);
  const auto& tri = folded.mesh.triangles[static_cast<size_t>(t_fold)];
  // Reflect the corner through the line of the other two nodes.
  Vec2 p, q;
  for (int k = 0, m = 0; k < 3; ++k)
    if (tri[k] != corner) (m++ == 0 ? p : q) = node(folded, tri[k]);
  const Vec2 c = node(folded, corner), e = (q - p).normalized();
  const Vec2 mirrored = p + 2.0 * (c - p).dot(e) * e - (c - p);
  folded.x[2 * corner] = mirrored.x();
  folded.x[2 * corner + 1] = mirrored.y();
  ASSERT_LT(signed_area(folded, t_fold), 0.0);
  // Its centroid now lies inside the body, over other triangles: the smallest index wins;
  // a point near the mirrored corner is in the folded triangle only if no other has it.
  const std::optional<int> at_c = triangle_at(folded, centroid(folded, t_fold));
  ASSERT_TRUE(at_c.has_value());
  EXPECT_LE(*at_c, t_fold);
  const Vec2 near_corner = mirrored + 0.05 * ((p + q) / 2.0 - mirrored);
  const std::optional<int> at_n = triangle_at(folded, near_corner);
  ASSERT_TRUE(at_n.has_value());
  // Every triangle that triangle_at passes over really does not contain the point.
  for (int t = 0; t < *at_n; ++t) {
    const auto& u = folded.mesh.triangles[static_cast<size_t>(t)];
    const Vec2 a = node(folded, u[0]), b = node(folded, u[1]), cc = node(folded, u[2]);
    const auto cross = [](const Vec2& x, const Vec2& y) { return x.x() * y.y() - x.y() * y.x(); };
    const double s0 = cross(b - a, near_corner - a), s1 = cross(cc - b, near_corner - b),
                 s2 = cross(a - cc, near_corner - cc);
    EXPECT_TRUE((s0 < 0 || s1 < 0 || s2 < 0) && (s0 > 0 || s1 > 0 || s2 > 0)) << t;
  }

  // Collapse triangle 0 onto a segment: its former centroid is then in none of it.
  Simulation flat = make_simulation(*load_builtin_scene("compress").scene);
  const auto& t0 = flat.mesh.triangles[0];
  const Vec2 mid = (node(flat, t0[0]) + node(flat, t0[1])) / 2.0;
  flat.x[2 * t0[2]] = mid.x();
  flat.x[2 * t0[2] + 1] = mid.y();
  const std::optional<int> at_flat = triangle_at(flat, mid + Vec2(1e-9, 1e-9));
  EXPECT_NE(at_flat, std::optional<int>(0));
}

// analyze_triangle uses the triangle's own F, the scene's model and the triangle's own
// material (a body may have its own); triangle_field agrees with it triangle by triangle.
TEST(StressAnalysisOnSimulation, AnalyzeTriangleAndFieldsAgree) {
  SceneLoad load = parse_scene_toml(R"(
name = "two-materials"
[mesh]
side = 0.5
n_seg = 2
[[body]]
offset = [0.0, 0.0]
[[body]]
offset = [1.0, 0.0]
mu = 2e4
lambda = 3e4
[material]
model = "stable-neo-hookean"
E = 1e5
nu = 0.3
[time]
h = 0.01
[gravity]
g = [0.0, -9.81]
[ground]
y = -0.3
)",
                                    "two-materials");
  ASSERT_TRUE(load.scene) << load.error;
  const Simulation sim = stepped(*load.scene, 30);
  const int n = sim.mesh.triangle_count();
  ASSERT_EQ(n, 16);
  std::vector<double> det, psi, stress, clamped;
  triangle_field(sim, TriangleField::DetF, &det);
  triangle_field(sim, TriangleField::Psi, &psi);
  triangle_field(sim, TriangleField::Stress, &stress);
  triangle_field(sim, TriangleField::Clamped, &clamped);
  int clamped_somewhere = 0;
  for (int t = 0; t < n; ++t) {
    const StressAnalysis a = analyze_triangle(sim, t);
    EXPECT_EQ(a.model, Model::StableNeoHookean);
    EXPECT_EQ(a.lame, t < 8 ? load.scene->lame : (Lame{2e4, 3e4})) << t;
    EXPECT_EQ(a.lame, triangle_material(sim, t));
    const auto& tri = sim.mesh.triangles[static_cast<size_t>(t)];
    // F maps the rest edges to the deformed ones.
    const Vec2 x0 = node(sim, tri[0]), x1 = node(sim, tri[1]), x2 = node(sim, tri[2]);
    Mat2 Ds;
    Ds << x1 - x0, x2 - x0;
    EXPECT_LT((a.F - Ds * sim.mesh.rest_shape_inverse[static_cast<size_t>(t)]).norm(), 1e-14);
    EXPECT_NEAR(a.J * std::abs(sim.mesh.rest_area[static_cast<size_t>(t)]), signed_area(sim, t),
                1e-14);
    EXPECT_EQ(det[static_cast<size_t>(t)], a.J);
    EXPECT_EQ(psi[static_cast<size_t>(t)], a.psi);
    const double largest = std::abs(a.principal_stress(0)) >= std::abs(a.principal_stress(1))
                               ? a.principal_stress(0)
                               : a.principal_stress(1);
    EXPECT_EQ(stress[static_cast<size_t>(t)], largest);
    EXPECT_EQ(clamped[static_cast<size_t>(t)], a.clamped);
    clamped_somewhere += a.clamped > 0;
  }
  EXPECT_GT(clamped_somewhere, 0);  // gravity and the ground compress it: twists go negative
}

// A mass-spring scene has no strain energy per triangle: the fields other than det F are 0.
TEST(StressAnalysisOnSimulation, MassSpringFieldsAreGeometryOnly) {
  const Simulation sim = stepped(*load_builtin_scene("course-1-mass-spring").scene, 5);
  ASSERT_FALSE(sim.scene.has_triangle_elasticity());
  std::vector<double> det, psi;
  triangle_field(sim, TriangleField::DetF, &det);
  triangle_field(sim, TriangleField::Psi, &psi);
  for (int t = 0; t < sim.mesh.triangle_count(); ++t) {
    EXPECT_EQ(det[static_cast<size_t>(t)], determinant(triangle_deformation_gradient(sim, t)));
    EXPECT_EQ(psi[static_cast<size_t>(t)], 0.0);
  }
}

}  // namespace
}  // namespace invfree
