// Which linear solver Newton uses for H p = -g (the scene key `[solver] linear_solver`).
//   auto    - the default: PCG preconditioned by a reused sparse LDL^T factorisation
//             when the Hessian is positive definite by construction (projection "diagonal"
//             or "full"), a fresh direct LDL^T per iteration otherwise (projection "none")
//   ldlt    - the project's sparse LDL^T (core/linalg/sparse_ldlt.h), refactorised every
//             Newton iteration
//   cholmod - CHOLMOD's supernodal LL^T (METIS ordering), refactorised every iteration
//   pcg     - PCG with a reused factorisation as preconditioner, even where auto would not
#pragma once

#include <optional>
#include <string_view>

namespace invfree {

enum class LinearSolverKind { Auto, Ldlt, Cholmod, Pcg };

inline const char* linear_solver_name(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::Auto:
      return "auto";
    case LinearSolverKind::Ldlt:
      return "ldlt";
    case LinearSolverKind::Cholmod:
      return "cholmod";
    case LinearSolverKind::Pcg:
      return "pcg";
  }
  return "?";
}

inline std::optional<LinearSolverKind> linear_solver_from_name(std::string_view name) {
  for (auto k : {LinearSolverKind::Auto, LinearSolverKind::Ldlt, LinearSolverKind::Cholmod,
                 LinearSolverKind::Pcg})
    if (name == linear_solver_name(k)) return k;
  return std::nullopt;
}

}  // namespace invfree
