// Internal: the 8x8 matrix product of the variational equations (src/flow/monodromy.hpp), where a
// Magnus step spends most of its time. Debian builds for the x86-64 baseline (SSE2), on which
// Eigen multiplies two 8x8 matrices with 2-wide vectors; the kernels (src/flow/wide_kernels.cpp)
// run the same product with 4-wide (AVX2) or 8-wide (AVX-512) vectors where the processor has
// them, chosen once at run time, and leave it to Eigen's inlined product elsewhere. Every kernel
// computes each element as Eigen's lazyProduct does (the k = 0 product, then the k = 1, ..., 7
// products added in order, each rounded: no fused multiply-add), so the results are the same to the
// bit on every machine (tests/flow/test_matrix_product.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace oscidrum::detail {

/// C = A B for column-major 8x8 matrices by the widest kernel this processor has (C must not alias
/// A or B). False, with C untouched, where it has none (then Eigen's inlined product is the
/// fastest).
bool wide_product8(const double* A, const double* B, double* C) noexcept;

/// The wide kernels this processor can run, the widest first (none on a processor without AVX2):
/// for tests and benchmarks.
struct ProductKernel {
  const char* name;  ///< "avx512" or "avx2"
  void (*multiply)(const double* A, const double* B, double* C) noexcept;
};
std::vector<ProductKernel> wide_product8_kernels();

/// A B: wide_product8 for 8x8 matrices where the processor has a wide kernel, Eigen's lazyProduct
/// otherwise and for any other size.
template <class Matrix>
Matrix product(const Matrix& A, const Matrix& B) {
  if constexpr (Matrix::RowsAtCompileTime == 8 && Matrix::ColsAtCompileTime == 8 &&
                !Matrix::IsRowMajor) {
    Matrix C;
    if (wide_product8(A.data(), B.data(), C.data())) return C;
  }
  return A.lazyProduct(B);
}

}  // namespace oscidrum::detail
