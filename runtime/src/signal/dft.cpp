// Power-of-two FFTs from Eigen's FFT module; other lengths by Bluestein's chirp.

#include "runtime/src/signal/dft.hpp"

#include <cstdint>
#include <numbers>

#include <unsupported/Eigen/FFT>

namespace modelgen::detail {

using Complex = std::complex<double>;

Eigen::Index next_power_of_two(Eigen::Index n) {
  Eigen::Index m = 1;
  while (m < n) m *= 2;
  return m;
}

// Bluestein: l k = (l^2 + k^2 - (l - k)^2) / 2 turns the DFT into a convolution, done with
// power-of-two FFTs, so the cost is O(n log n) even for prime n.
std::vector<Complex> dft(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Eigen::Index n = x.size();
  Eigen::FFT<double> fft;
  std::vector<Complex> in(x.data(), x.data() + n), out;
  if (n == next_power_of_two(n)) {
    fft.fwd(out, in);
    return out;
  }
  const Eigen::Index m = next_power_of_two(2 * n - 1);
  // w_k = exp(-i pi k^2 / n); k^2 mod 2n in integers keeps the angle exact for large k.
  std::vector<Complex> w(n);
  const std::uint64_t two_n = 2 * static_cast<std::uint64_t>(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::uint64_t kk = static_cast<std::uint64_t>(k) * static_cast<std::uint64_t>(k);
    w[k] = std::polar(1.0,
                      -std::numbers::pi * static_cast<double>(kk % two_n) / static_cast<double>(n));
  }
  std::vector<Complex> a(m, 0.0), b(m, 0.0), fa, fb;
  for (Eigen::Index k = 0; k < n; ++k) a[k] = in[k] * w[k];
  b[0] = std::conj(w[0]);
  for (Eigen::Index k = 1; k < n; ++k) b[k] = b[m - k] = std::conj(w[k]);
  fft.fwd(fa, a);
  fft.fwd(fb, b);
  for (Eigen::Index k = 0; k < m; ++k) fa[k] *= fb[k];
  fft.inv(a, fa);
  out.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) out[k] = w[k] * a[k];
  return out;
}

}  // namespace modelgen::detail
