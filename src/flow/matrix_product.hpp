// Internal: the 8x8 matrix product of the variational equations (src/flow/monodromy.hpp), where a
// Magnus step spends most of its time. Debian builds for the x86-64 baseline (SSE2), on which
// Eigen multiplies two 8x8 matrices with 2-wide vectors; this file runs the same product with
// 4-wide (AVX2) or 8-wide (AVX-512) vectors where the processor has them, chosen once at run time.
// Every kernel computes each element as Eigen's lazyProduct does (the k = 0 product, then the
// k = 1, ..., 7 products added in order, each rounded: no fused multiply-add), so the results are
// the same to the bit on every machine (tests/flow/test_matrix_product.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace oscidrum::detail {

/// C = A B for column-major 8x8 matrices (C must not alias A or B).
void product8(const double* A, const double* B, double* C) noexcept;

/// The kernels this processor can run, the one product8 uses first: for tests and benchmarks.
struct ProductKernel {
  const char* name;  ///< "avx512", "avx2" or "baseline"
  void (*multiply)(const double* A, const double* B, double* C) noexcept;
};
std::vector<ProductKernel> product8_kernels();

/// A B: product8 for 8x8 matrices, Eigen's lazyProduct for any other size.
template <class Matrix>
Matrix product(const Matrix& A, const Matrix& B) {
  if constexpr (Matrix::RowsAtCompileTime == 8 && Matrix::ColsAtCompileTime == 8 &&
                !Matrix::IsRowMajor) {
    Matrix C;
    product8(A.data(), B.data(), C.data());
    return C;
  } else {
    return A.lazyProduct(B);
  }
}

}  // namespace oscidrum::detail
