// The wide kernels of the variational equations: the 8 x 8 product (src/flow/matrix_product.hpp)
// and one Magnus step's exponential (src/flow/magnus.hpp), for AVX2 and AVX-512. This file is
// compiled without floating-point contraction (src/CMakeLists.txt): a multiply and an add must
// stay two roundings, as in the baseline build, or the wide kernels would give other results than
// Eigen's and magnus.hpp's.
#include "flow/magnus.hpp"
#include "flow/matrix_product.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define OSCIDRUM_X86_KERNELS 1
#endif

namespace oscidrum::detail {
namespace {

#ifdef OSCIDRUM_X86_KERNELS
// Column j of C: sum over k of column k of A times B(k, j), k in order.
__attribute__((target("avx2"))) void avx2(const double* A, const double* B, double* C) noexcept {
  __m256d lo[8], hi[8];
  for (int k = 0; k < 8; ++k) {
    lo[k] = _mm256_loadu_pd(A + 8 * k);
    hi[k] = _mm256_loadu_pd(A + 8 * k + 4);
  }
  for (int j = 0; j < 8; ++j) {
    const double* b = B + 8 * j;
    __m256d s = _mm256_broadcast_sd(b);
    __m256d c0 = _mm256_mul_pd(lo[0], s), c1 = _mm256_mul_pd(hi[0], s);
    for (int k = 1; k < 8; ++k) {
      s = _mm256_broadcast_sd(b + k);
      c0 = _mm256_add_pd(c0, _mm256_mul_pd(lo[k], s));
      c1 = _mm256_add_pd(c1, _mm256_mul_pd(hi[k], s));
    }
    _mm256_storeu_pd(C + 8 * j, c0);
    _mm256_storeu_pd(C + 8 * j + 4, c1);
  }
}

__attribute__((target("avx512f"))) void avx512(const double* A, const double* B,
                                               double* C) noexcept {
  __m512d a[8];
  for (int k = 0; k < 8; ++k) a[k] = _mm512_loadu_pd(A + 8 * k);
  for (int j = 0; j < 8; ++j) {
    const double* b = B + 8 * j;
    __m512d c = _mm512_mul_pd(a[0], _mm512_set1_pd(b[0]));
    for (int k = 1; k < 8; ++k) c = _mm512_add_pd(c, _mm512_mul_pd(a[k], _mm512_set1_pd(b[k])));
    _mm512_storeu_pd(C + 8 * j, c);
  }
}
#endif

using Kernel = void (*)(const double*, const double*, double*) noexcept;

// The widest kernel this processor (and its operating system: the libgcc check includes the
// saved vector state) runs, or nullptr.
Kernel widest() noexcept {
#ifdef OSCIDRUM_X86_KERNELS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return avx512;
  if (__builtin_cpu_supports("avx2")) return avx2;
#endif
  return nullptr;
}

using Matrix8 = Eigen::Matrix<double, 8, 8>;
using Vector8 = Eigen::Matrix<double, 8, 1>;

#ifdef OSCIDRUM_X86_KERNELS
// magnus.hpp's always-inlined code compiled for the wider vectors (its products call
// wide_product8, which takes the widest kernel).
__attribute__((target("avx2"))) Matrix8 magnus_avx2(double h, const Matrix8& J1, const Matrix8& J2,
                                                    const Matrix8& J3, Vector8& d, int sweeps) {
  return balanced_exponential(magnus6_exponent(h, J1, J2, J3), d, sweeps);
}
__attribute__((target("avx512f"))) Matrix8 magnus_avx512(double h, const Matrix8& J1,
                                                         const Matrix8& J2, const Matrix8& J3,
                                                         Vector8& d, int sweeps) {
  return balanced_exponential(magnus6_exponent(h, J1, J2, J3), d, sweeps);
}
#endif

using MagnusFunction = Matrix8 (*)(double, const Matrix8&, const Matrix8&, const Matrix8&, Vector8&,
                                   int);

MagnusFunction widest_magnus() noexcept {
#ifdef OSCIDRUM_X86_KERNELS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return magnus_avx512;
  if (__builtin_cpu_supports("avx2")) return magnus_avx2;
#endif
  return nullptr;
}

}  // namespace

std::vector<MagnusKernel> wide_magnus_kernels() {
  std::vector<MagnusKernel> kernels;
#ifdef OSCIDRUM_X86_KERNELS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) kernels.push_back({"avx512", magnus_avx512});
  if (__builtin_cpu_supports("avx2")) kernels.push_back({"avx2", magnus_avx2});
#endif
  return kernels;
}

bool wide_magnus_exponential8(double h, const Matrix8& J1, const Matrix8& J2, const Matrix8& J3,
                              Vector8& d, int sweeps, Matrix8& E) noexcept {
  static const MagnusFunction kernel = widest_magnus();
  if (kernel == nullptr) return false;
  E = kernel(h, J1, J2, J3, d, sweeps);
  return true;
}

std::vector<ProductKernel> wide_product8_kernels() {
  std::vector<ProductKernel> kernels;
#ifdef OSCIDRUM_X86_KERNELS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) kernels.push_back({"avx512", avx512});
  if (__builtin_cpu_supports("avx2")) kernels.push_back({"avx2", avx2});
#endif
  return kernels;
}

bool wide_product8(const double* A, const double* B, double* C) noexcept {
  // Chosen once (thread-safe initialisation of a constant; the processor does not change).
  static const Kernel kernel = widest();
  if (kernel == nullptr) return false;
  kernel(A, B, C);
  return true;
}

}  // namespace oscidrum::detail
