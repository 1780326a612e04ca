// fold_rows: Householder reflections (Golub & Van Loan alg. 5.1.1, LAPACK dlarfg convention)
// that zero B's columns one by one against R's diagonal. Per column k the reflector is
// v = [e_k; u] with u in B's rows, so it changes row k of R and the columns of B only:
// 2 m w^2 flops for m new rows, none spent on R's zeros (a dense QR of the stack spends
// 2 (m + w) w^2). The work is level-2 (a dot product and an update per column pair), so it is
// done on row chunks small enough that B's chunk and R stay in L1 between the two passes.

#include "runtime/src/estimation/row_reduction.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

// With GCC on x86-64 Linux the kernel is also compiled for AVX2+FMA and chosen at load time
// (ifunc): the rest of the library stays built for the baseline ISA.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define MODELGEN_KERNEL_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define MODELGEN_KERNEL_CLONES
#endif

namespace modelgen::detail {

namespace {

// Rows of B folded per pass: a 32 x w chunk (<= 16 KB for w <= 64) and the w x w triangle
// of R stay in a 32 KB L1 data cache.
constexpr std::ptrdiff_t kChunkRows = 64;

// Four doubles: GCC's vector extension, lowered to one AVX or two SSE2 operations per clone.
typedef double Lanes __attribute__((vector_size(32)));

// Vectors by value in helpers that are always inlined: no call, so no ABI to differ between
// the clones (GCC warns about one anyway).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
__attribute__((always_inline)) inline Lanes load(const double* p) {
  Lanes a;
  std::memcpy(&a, p, sizeof a);
  return a;
}
__attribute__((always_inline)) inline double sum(Lanes a) { return (a[0] + a[1]) + (a[2] + a[3]); }

// One chunk (m <= kChunkRows rows of B). Inlined into each clone with m a constant for full
// chunks, so that the loops over rows unroll; dot products run on two independent sums each.
__attribute__((always_inline)) inline void fold_chunk_body(double* R, std::ptrdiff_t ldr,
                                                           double* B, std::ptrdiff_t ldb,
                                                           std::ptrdiff_t m, std::ptrdiff_t w) {
  const std::ptrdiff_t m8 = m - m % 8, m4 = m - m % 4;
  for (std::ptrdiff_t k = 0; k < w; ++k) {
    double* u = B + k * ldb;
    Lanes s0 = {0, 0, 0, 0}, s1 = s0;
    for (std::ptrdiff_t i = 0; i < m8; i += 8) {
      const Lanes a = load(u + i), b = load(u + i + 4);
      s0 += a * a;
      s1 += b * b;
    }
    for (std::ptrdiff_t i = m8; i < m4; i += 4) {
      const Lanes a = load(u + i);
      s0 += a * a;
    }
    double sigma = sum(s0 + s1);
    for (std::ptrdiff_t i = m4; i < m; ++i) sigma += u[i] * u[i];
    // Column k of the chunk is already zero (or too small to matter, as in Eigen's
    // makeHouseholder): no reflection. NaN fails the test and travels on into R.
    if (sigma <= std::numeric_limits<double>::min()) continue;
    double& diagonal = R[k + k * ldr];
    const double alpha = diagonal;
    const double norm = std::sqrt(alpha * alpha + sigma);
    const double beta = alpha >= 0 ? -norm : norm;
    const double tau = (beta - alpha) / beta;
    const double scale = 1.0 / (alpha - beta);
    for (std::ptrdiff_t i = 0; i < m; ++i) u[i] *= scale;
    diagonal = beta;
    // H = I - tau v v^T on the later columns [R(k, j); y_j], two at a time (u read once for
    // both): s_j = tau (R(k, j) + u . y_j), then R(k, j) -= s_j, y_j -= s_j u.
    std::ptrdiff_t j = k + 1;
    for (; j + 1 < w; j += 2) {
      double* y0 = B + j * ldb;
      double* y1 = y0 + ldb;
      Lanes d00 = {0, 0, 0, 0}, d01 = d00, d10 = d00, d11 = d00;
      for (std::ptrdiff_t i = 0; i < m8; i += 8) {
        const Lanes a = load(u + i), b = load(u + i + 4);
        d00 += a * load(y0 + i);
        d01 += b * load(y0 + i + 4);
        d10 += a * load(y1 + i);
        d11 += b * load(y1 + i + 4);
      }
      for (std::ptrdiff_t i = m8; i < m4; i += 4) {
        const Lanes a = load(u + i);
        d00 += a * load(y0 + i);
        d10 += a * load(y1 + i);
      }
      double t0 = sum(d00 + d01), t1 = sum(d10 + d11);
      for (std::ptrdiff_t i = m4; i < m; ++i) {
        t0 += u[i] * y0[i];
        t1 += u[i] * y1[i];
      }
      double& top0 = R[k + j * ldr];
      double& top1 = R[k + (j + 1) * ldr];
      t0 = tau * (top0 + t0);
      t1 = tau * (top1 + t1);
      top0 -= t0;
      top1 -= t1;
      const Lanes step0 = {t0, t0, t0, t0}, step1 = {t1, t1, t1, t1};
      for (std::ptrdiff_t i = 0; i < m4; i += 4) {
        const Lanes a = load(u + i);
        const Lanes b0 = load(y0 + i) - step0 * a, b1 = load(y1 + i) - step1 * a;
        std::memcpy(y0 + i, &b0, sizeof b0);
        std::memcpy(y1 + i, &b1, sizeof b1);
      }
      for (std::ptrdiff_t i = m4; i < m; ++i) {
        y0[i] -= t0 * u[i];
        y1[i] -= t1 * u[i];
      }
    }
    if (j < w) {  // the last column when an odd number remain
      double* y = B + j * ldb;
      double t = 0;
      for (std::ptrdiff_t i = 0; i < m; ++i) t += u[i] * y[i];
      double& top = R[k + j * ldr];
      t = tau * (top + t);
      top -= t;
      for (std::ptrdiff_t i = 0; i < m; ++i) y[i] -= t * u[i];
    }
  }
}

MODELGEN_KERNEL_CLONES
void fold_chunk(double* R, std::ptrdiff_t ldr, double* B, std::ptrdiff_t ldb, std::ptrdiff_t m,
                std::ptrdiff_t w) {
  if (m == kChunkRows) {
    fold_chunk_body(R, ldr, B, ldb, kChunkRows, w);
  } else {
    fold_chunk_body(R, ldr, B, ldb, m, w);
  }
}

}  // namespace
#pragma GCC diagnostic pop

void fold_rows(double* R, std::ptrdiff_t ldr, double* B, std::ptrdiff_t ldb, std::ptrdiff_t m,
               std::ptrdiff_t w) {
  for (std::ptrdiff_t r = 0; r < m; r += kChunkRows) {
    fold_chunk(R, ldr, B + r, ldb, std::min(kChunkRows, m - r), w);
  }
}

}  // namespace modelgen::detail
