// LinearSolver (linear_solver.h): picks the backend for a pattern and times the
// factorisations. The backends: ldlt_backend.h (with SparseLdlt), cholmod_backend.h and
// pcg.h.
#include "linalg/linear_solver.h"

#include <chrono>

#include "linalg/cholmod_backend.h"
#include "linalg/ldlt_backend.h"
#include "linalg/pcg.h"
#include "linalg/sparse_ldlt.h"

namespace invfree {

using SpMat = Eigen::SparseMatrix<double>;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

}  // namespace

struct LinearSolver::Impl {
  enum class Backend { Ldlt, Cholmod, PcgLdlt };
  Backend backend = Backend::Ldlt;
  bool positive_definite = true;
  SparseLdlt ldlt;  // the ldlt backend's factor, and PCG's preconditioner
  CholmodBackend chol;
  ReusedFactorPcg pcg;

  bool factorize(const SpMat& h, LinearSolveStats& stats) {
    const auto t0 = Clock::now();
    const bool ok =
        backend == Backend::Cholmod ? chol.factorize(h) : ldlt.factorize(h, positive_definite);
    stats.factor_ms += ms_since(t0);
    ++stats.factorizations;
    if (backend == Backend::PcgLdlt) pcg.factorized(h, ok);
    return ok;
  }

  bool solve(const SpMat& h, const VecX& b, VecX& x, const SolveRequest& request,
             LinearSolveStats& stats) {
    if (backend != Backend::PcgLdlt && !request.couplings.empty()) return false;
    switch (backend) {
      case Backend::Ldlt:
        if (!factorize(h, stats)) return false;
        ldlt.solve(b, x);
        return true;
      case Backend::Cholmod:
        return factorize(h, stats) && chol.solve(b, x);
      case Backend::PcgLdlt:
        return pcg.solve_with_stored_factor(h, b, x, request, ldlt, stats) ||
               (factorize(h, stats) && pcg.solve_with_new_factor(h, b, x, request, ldlt, stats));
    }
    return false;
  }
};

bool solves_by_pcg(LinearSolverKind kind, bool positive_definite) {
  return kind == LinearSolverKind::Pcg || (kind == LinearSolverKind::Auto && positive_definite);
}

LinearSolver::LinearSolver() = default;
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::setup(const SpMat& pattern, LinearSolverKind kind, bool positive_definite) {
  using Backend = Impl::Backend;
  requested_ = kind;
  positive_definite_ = positive_definite;
  impl_ = std::make_unique<Impl>();
  Impl& s = *impl_;
  s.positive_definite = positive_definite;
  switch (kind) {
    case LinearSolverKind::Ldlt:
      s.backend = Backend::Ldlt;
      break;
    case LinearSolverKind::Cholmod:
      // Without CHOLMOD, or where its analysis fails, the LDL^T serves the request.
      s.backend = s.chol.analyze(pattern) ? Backend::Cholmod : Backend::Ldlt;
      break;
    case LinearSolverKind::Pcg:
    case LinearSolverKind::Auto:
    default:
      s.backend = solves_by_pcg(kind, positive_definite) ? Backend::PcgLdlt : Backend::Ldlt;
      break;
  }
  if (s.backend == Backend::Cholmod) return;
  analyze_like_the_solver(pattern, s.ldlt);
  if (s.backend == Backend::PcgLdlt) s.pcg.setup(pattern, s.ldlt);
}

const char* LinearSolver::backend_name() const {
  if (!impl_) return "none";
  switch (impl_->backend) {
    case Impl::Backend::Ldlt:
      return "ldlt";
    case Impl::Backend::Cholmod:
      return "cholmod";
    case Impl::Backend::PcgLdlt:
      return "pcg+ldlt";
  }
  return "?";
}

void LinearSolver::invalidate() {
  if (impl_) impl_->pcg.invalidate();
}

bool LinearSolver::solve(const SpMat& h, const VecX& b, VecX& x, const SolveRequest& request,
                         LinearSolveStats& stats) {
  const auto start = Clock::now();
  const double factor_ms_before = stats.factor_ms;
  ++stats.solves;
  if (x.size() != b.size()) x.resize(b.size());
  const bool ok = impl_->solve(h, b, x, request, stats) && x.allFinite();
  stats.solve_ms += ms_since(start) - (stats.factor_ms - factor_ms_before);
  return ok;
}

}  // namespace invfree
