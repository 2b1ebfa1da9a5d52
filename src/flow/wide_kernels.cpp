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

// The widest instruction set this processor and its operating system run (libgcc's check
// includes the saved vector state).
enum class VectorSet { none, avx2, avx512 };
[[maybe_unused]] VectorSet widest_set() noexcept {
#ifdef OSCIDRUM_X86_KERNELS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return VectorSet::avx512;
  if (__builtin_cpu_supports("avx2")) return VectorSet::avx2;
#endif
  return VectorSet::none;
}

// Of a kernel's AVX-512 and AVX2 versions, those this processor runs, the widest first.
template <class Kernel>
std::vector<Kernel> runnable([[maybe_unused]] Kernel avx512_version,
                             [[maybe_unused]] Kernel avx2_version) {
  std::vector<Kernel> kernels;
  const VectorSet set = widest_set();
  if (set == VectorSet::avx512) kernels.push_back(avx512_version);
  if (set != VectorSet::none) kernels.push_back(avx2_version);
  return kernels;
}

// The one to run (chosen once by the callers: thread-safe initialisation of a constant; the
// processor does not change), or nullptr.
template <class F>
F widest(F avx512_version, F avx2_version) noexcept {
  switch (widest_set()) {
    case VectorSet::avx512:
      return avx512_version;
    case VectorSet::avx2:
      return avx2_version;
    case VectorSet::none:
      break;
  }
  return nullptr;
}

using ProductFunction = void (*)(const double*, const double*, double*) noexcept;
using MagnusFunction = Matrix8 (*)(double, const Matrix8&, const Matrix8&, const Matrix8&, Vector8&,
                                   int);

}  // namespace

std::vector<ProductKernel> wide_product8_kernels() {
#ifdef OSCIDRUM_X86_KERNELS
  return runnable<ProductKernel>({"avx512", avx512}, {"avx2", avx2});
#else
  return {};
#endif
}

bool wide_product8([[maybe_unused]] const double* A, [[maybe_unused]] const double* B,
                   [[maybe_unused]] double* C) noexcept {
#ifdef OSCIDRUM_X86_KERNELS
  static const ProductFunction kernel = widest<ProductFunction>(avx512, avx2);
  if (kernel != nullptr) {
    kernel(A, B, C);
    return true;
  }
#endif
  return false;
}

std::vector<MagnusKernel> wide_magnus_kernels() {
#ifdef OSCIDRUM_X86_KERNELS
  return runnable<MagnusKernel>({"avx512", magnus_avx512}, {"avx2", magnus_avx2});
#else
  return {};
#endif
}

bool wide_magnus_exponential8([[maybe_unused]] double h, [[maybe_unused]] const Matrix8& J1,
                              [[maybe_unused]] const Matrix8& J2,
                              [[maybe_unused]] const Matrix8& J3, [[maybe_unused]] Vector8& d,
                              [[maybe_unused]] int sweeps, [[maybe_unused]] Matrix8& E) noexcept {
#ifdef OSCIDRUM_X86_KERNELS
  static const MagnusFunction kernel = widest<MagnusFunction>(magnus_avx512, magnus_avx2);
  if (kernel != nullptr) {
    E = kernel(h, J1, J2, J3, d, sweeps);
    return true;
  }
#endif
  return false;
}

}  // namespace oscidrum::detail
