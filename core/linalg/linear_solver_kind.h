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

#include "enum_names.h"

namespace invfree {

enum class LinearSolverKind { Auto, Ldlt, Cholmod, Pcg };

inline constexpr EnumName<LinearSolverKind> kLinearSolverNames[] = {
    {LinearSolverKind::Auto, "auto"},
    {LinearSolverKind::Ldlt, "ldlt"},
    {LinearSolverKind::Cholmod, "cholmod"},
    {LinearSolverKind::Pcg, "pcg"},
};

inline const char* linear_solver_name(LinearSolverKind k) {
  return enum_name(kLinearSolverNames, k);
}

inline std::optional<LinearSolverKind> linear_solver_from_name(std::string_view name) {
  return enum_from_name(kLinearSolverNames, name);
}

}  // namespace invfree
