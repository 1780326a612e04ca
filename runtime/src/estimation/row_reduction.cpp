// fold_rows: Householder reflections (Golub & Van Loan alg. 5.1.1, LAPACK dlarfg convention)
// that zero B's columns one by one against R's diagonal. Per column k the reflector is
// v = [e_k; u] with u in B's rows, so it changes row k of R and the columns of B only:
// 2 m w^2 flops for m new rows, none spent on R's zeros (a dense QR of the stack spends
// 2 (m + w) w^2). Reflectors are made four at a time (a panel, level-2 within it) and then
// applied together to later columns, three at a time: one pass for the dot products,
// one for the update (compact WY, Schreiber & Van Loan, with the small triangular factor
// written out as the Gram matrix of the panel's u), so that each load and store of B serves
// four reflections (three columns: u loaded once for three).

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

// Rows of B folded per pass. Within a pass the panel's four u columns and the columns being
// updated (256 rows: 2 KB each) stay in L1 while B streams from L2; 64, 128, 256 and 512
// measured within noise of each other, 256 (one full block of the Reducer) slightly fastest.
constexpr std::ptrdiff_t kChunkRows = 256;
// Reflectors applied together.
constexpr int kPanel = 4;

// Four doubles: GCC's vector extension, lowered to one AVX or two SSE2 operations per clone.
typedef double Lanes __attribute__((vector_size(32)));

// Vectors by value in helpers that are always inlined: no call, so no ABI to differ between
// the clones (GCC warns about one anyway, also at the end of the file).
#pragma GCC diagnostic ignored "-Wpsabi"

__attribute__((always_inline)) inline Lanes load(const double* p) {
  Lanes a;
  std::memcpy(&a, p, sizeof a);
  return a;
}
__attribute__((always_inline)) inline void store(double* p, const Lanes& a) {
  std::memcpy(p, &a, sizeof a);
}
__attribute__((always_inline)) inline double sum(const Lanes& a) {
  return (a[0] + a[1]) + (a[2] + a[3]);
}
__attribute__((always_inline)) inline Lanes splat(double x) { return Lanes{x, x, x, x}; }

// u . y over m entries (m4 = m rounded down to a multiple of 4).
__attribute__((always_inline)) inline double dot(const double* u, const double* y, std::ptrdiff_t m,
                                                 std::ptrdiff_t m4) {
  Lanes s0 = {0, 0, 0, 0}, s1 = s0;
  std::ptrdiff_t i = 0;
  for (; i + 8 <= m4; i += 8) {
    s0 += load(u + i) * load(y + i);
    s1 += load(u + i + 4) * load(y + i + 4);
  }
  if (i < m4) s0 += load(u + i) * load(y + i);
  double s = sum(s0 + s1);
  for (i = m4; i < m; ++i) s += u[i] * y[i];
  return s;
}

// The reflector of column k: [R(k, k); u] -> [beta; 0], u (B's column k) overwritten by the
// reflector's lower part, R(k, k) by beta. Returns tau, 0 when the column of B is already zero
// (or too small to matter, as in Eigen's makeHouseholder); NaN fails that test and travels on
// into R.
__attribute__((always_inline)) inline double make_reflector(double& diagonal, double* u,
                                                            std::ptrdiff_t m, std::ptrdiff_t m4) {
  const double sigma = dot(u, u, m, m4);
  if (sigma <= std::numeric_limits<double>::min()) return 0;
  const double alpha = diagonal;
  const double norm = std::sqrt(alpha * alpha + sigma);
  const double beta = alpha >= 0 ? -norm : norm;
  const double scale = 1.0 / (alpha - beta);
  for (std::ptrdiff_t i = 0; i < m; ++i) u[i] *= scale;
  diagonal = beta;
  return (beta - alpha) / beta;
}

// H = I - tau v v^T on one column [top; y]: s = tau (top + u . y), top -= s, y -= s u.
__attribute__((always_inline)) inline void reflect(const double* u, double tau, double& top,
                                                   double* y, std::ptrdiff_t m, std::ptrdiff_t m4) {
  if (tau == 0) return;
  const double s = tau * (top + dot(u, y, m, m4));
  top -= s;
  const Lanes step = splat(s);
  for (std::ptrdiff_t i = 0; i < m4; i += 4) store(y + i, load(y + i) - step * load(u + i));
  for (std::ptrdiff_t i = m4; i < m; ++i) y[i] -= s * u[i];
}

// The panel's four reflections H_3 H_2 H_1 H_0 on `Cols` later columns [R(k..k+3, j); y_j].
// With d_c = u_c . y (the original y) and g(a, b) = u_a . u_b, reflection c sees
// u_c . y - sum_{b<c} s_b g(c, b), so s_c = tau_c (R(k+c, j) + d_c - sum_{b<c} s_b g(c, b));
// then y -= sum_c s_c u_c in one pass.
template <int Cols>
__attribute__((always_inline)) inline void reflect_panel(const double* const* u, const double* tau,
                                                         const double (*g)[kPanel], double* R,
                                                         std::ptrdiff_t ldr, std::ptrdiff_t k,
                                                         double* const* y, std::ptrdiff_t j,
                                                         std::ptrdiff_t m, std::ptrdiff_t m4) {
  Lanes acc[Cols][kPanel];
  for (int c = 0; c < Cols; ++c) {
    for (int p = 0; p < kPanel; ++p) acc[c][p] = Lanes{0, 0, 0, 0};
  }
  for (std::ptrdiff_t i = 0; i < m4; i += 4) {
    const Lanes u0 = load(u[0] + i), u1 = load(u[1] + i), u2 = load(u[2] + i), u3 = load(u[3] + i);
    for (int c = 0; c < Cols; ++c) {
      const Lanes x = load(y[c] + i);
      acc[c][0] += u0 * x;
      acc[c][1] += u1 * x;
      acc[c][2] += u2 * x;
      acc[c][3] += u3 * x;
    }
  }
  double s[Cols][kPanel];
  for (int c = 0; c < Cols; ++c) {
    for (int p = 0; p < kPanel; ++p) {
      double d = sum(acc[c][p]);
      for (std::ptrdiff_t i = m4; i < m; ++i) d += u[p][i] * y[c][i];
      double& top = R[k + p + (j + c) * ldr];
      for (int b = 0; b < p; ++b) d -= s[c][b] * g[p][b];
      s[c][p] = tau[p] * (top + d);
      top -= s[c][p];
    }
  }
  for (int c = 0; c < Cols; ++c) {
    const Lanes s0 = splat(s[c][0]), s1 = splat(s[c][1]), s2 = splat(s[c][2]), s3 = splat(s[c][3]);
    double* x = y[c];
    for (std::ptrdiff_t i = 0; i < m4; i += 4) {
      store(x + i, load(x + i) - s0 * load(u[0] + i) - s1 * load(u[1] + i) - s2 * load(u[2] + i) -
                       s3 * load(u[3] + i));
    }
    for (std::ptrdiff_t i = m4; i < m; ++i) {
      x[i] -= s[c][0] * u[0][i] + s[c][1] * u[1][i] + s[c][2] * u[2][i] + s[c][3] * u[3][i];
    }
  }
}

// One chunk (m <= kChunkRows rows of B). Inlined into each clone with m a constant for full
// chunks (the compiler's choice of unrolling then sees the trip count).
__attribute__((always_inline)) inline void fold_chunk_body(double* R, std::ptrdiff_t ldr, double* B,
                                                           std::ptrdiff_t ldb, std::ptrdiff_t m,
                                                           std::ptrdiff_t w) {
  const std::ptrdiff_t m4 = m - m % 4;
  for (std::ptrdiff_t k = 0; k < w; k += kPanel) {
    const std::ptrdiff_t width = std::min<std::ptrdiff_t>(kPanel, w - k);
    const double* u[kPanel];
    double tau[kPanel];
    for (std::ptrdiff_t c = 0; c < width; ++c) {
      double* column = B + (k + c) * ldb;
      tau[c] = make_reflector(R[(k + c) + (k + c) * ldr], column, m, m4);
      u[c] = column;
      for (std::ptrdiff_t j = k + c + 1; j < k + width; ++j) {
        reflect(column, tau[c], R[(k + c) + j * ldr], B + j * ldb, m, m4);
      }
    }
    if (k + kPanel >= w) break;  // no later columns
    double g[kPanel][kPanel] = {};
    for (int a = 1; a < kPanel; ++a) {
      for (int b = 0; b < a; ++b) g[a][b] = dot(u[a], u[b], m, m4);
    }
    std::ptrdiff_t j = k + kPanel;
    for (; j + 2 < w; j += 3) {
      double* y[3] = {B + j * ldb, B + (j + 1) * ldb, B + (j + 2) * ldb};
      reflect_panel<3>(u, tau, g, R, ldr, k, y, j, m, m4);
    }
    if (j + 1 < w) {
      double* y[2] = {B + j * ldb, B + (j + 1) * ldb};
      reflect_panel<2>(u, tau, g, R, ldr, k, y, j, m, m4);
    } else if (j < w) {
      double* y[1] = {B + j * ldb};
      reflect_panel<1>(u, tau, g, R, ldr, k, y, j, m, m4);
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

void fold_rows(double* R, std::ptrdiff_t ldr, double* B, std::ptrdiff_t ldb, std::ptrdiff_t m,
               std::ptrdiff_t w) {
  for (std::ptrdiff_t r = 0; r < m; r += kChunkRows) {
    fold_chunk(R, ldr, B + r, ldb, std::min(kChunkRows, m - r), w);
  }
}

}  // namespace modelgen::detail
