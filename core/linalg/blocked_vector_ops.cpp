// The symmetric sparse product of blocked_vector_ops.h.
#include "linalg/blocked_vector_ops.h"

namespace invfree {

double multiply_symmetric(const Eigen::SparseMatrix<double>& h,
                          std::span<const NodeCoupling> couplings, const VecX& v, VecX& y) {
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  const double* values = h.valuePtr();
  y.resize(h.rows());
  double dot = sum_over_blocks(h.rows(), [&](int begin, int length) {
    double block_dot = 0.0;
    for (int i = begin, end = begin + length; i < end; ++i) {
      double s = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) s += values[k] * v[inner[k]];
      y[i] = s;
      block_dot += s * v[i];
    }
    return block_dot;
  });
  if (!couplings.empty()) dot += add_couplings_product(couplings, v, y);
  return dot;
}

}  // namespace invfree
