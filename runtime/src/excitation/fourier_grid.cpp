// A Fourier excitation on a uniform grid by blocks of inverse FFTs (fourier_grid.hpp).

#include "runtime/src/excitation/fourier_grid.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <unsupported/Eigen/FFT>

namespace modelgen::detail {

using Complex = std::complex<double>;

long grid_block(long n) {
  // n = 2^i 3^j 5^k r with r free of 2, 3 and 5: the best of the divisors 2^a 3^b 5^c.
  int powers[3] = {0, 0, 0};
  const long primes[3] = {2, 3, 5};
  long rest = std::max(n, 1L);
  for (int f = 0; f < 3; ++f) {
    while (rest % primes[f] == 0) rest /= primes[f], ++powers[f];
  }
  long best = 1;
  long p2 = 1;
  for (int a = 0; a <= powers[0] && p2 <= kMaxGridBlock; ++a, p2 *= 2) {
    long p23 = p2;
    for (int b = 0; b <= powers[1] && p23 <= kMaxGridBlock; ++b, p23 *= 3) {
      long m = p23;
      for (int c = 0; c <= powers[2] && m <= kMaxGridBlock; ++c, m *= 5) best = std::max(best, m);
    }
  }
  return best;
}

SeriesBounds series_bounds(const FourierTrajectory& trajectory) {
  const Eigen::Index dof = trajectory.q0.size();
  const double wf = 2.0 * std::numbers::pi / trajectory.period;
  SeriesBounds bounds{Eigen::VectorXd::Zero(dof), Eigen::VectorXd::Zero(dof),
                      Eigen::VectorXd::Zero(dof)};
  for (Eigen::Index l = 0; l < trajectory.a.cols(); ++l) {
    const double w = wf * static_cast<double>(l + 1);
    const Eigen::VectorXd r = trajectory.a.col(l).cwiseAbs() + trajectory.b.col(l).cwiseAbs();
    bounds.q += r / w;
    bounds.dq += r;
    bounds.ddq += r * w;
  }
  return bounds;
}

namespace {

// The complex amplitudes of the three series: a term alpha sin(phi) + beta cos(phi) is
// Re[(beta - i alpha) e^{i phi}]; Swevers eq. 15-17 give, with w = l wf,
// q: alpha = a / w, beta = -b / w; dq: alpha = b, beta = a; ddq: alpha = -a w, beta = b w.
struct Amplitudes {
  Eigen::MatrixXcd q, dq, ddq;  // dof x L
};

Amplitudes amplitudes(const FourierTrajectory& x) {
  const Eigen::Index dof = x.q0.size(), harmonics = x.a.cols();
  const double wf = 2.0 * std::numbers::pi / x.period;
  Amplitudes c{Eigen::MatrixXcd(dof, harmonics), Eigen::MatrixXcd(dof, harmonics),
               Eigen::MatrixXcd(dof, harmonics)};
  for (Eigen::Index l = 0; l < harmonics; ++l) {
    const double w = wf * static_cast<double>(l + 1);
    for (Eigen::Index j = 0; j < dof; ++j) {
      const double a = x.a(j, l), b = x.b(j, l);
      c.q(j, l) = Complex(-b / w, -a / w);
      c.dq(j, l) = Complex(a, -b);
      c.ddq(j, l) = Complex(b * w, a * w);
    }
  }
  return c;
}

}  // namespace

void for_each_grid_block(const FourierTrajectory& trajectory, long n,
                         const std::function<void(const GridBlock&)>& visit) {
  const Eigen::Index dof = trajectory.q0.size(), harmonics = trajectory.a.cols();
  const long m = grid_block(n), blocks = n / m;
  const Amplitudes c = amplitudes(trajectory);
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::Unscaled);
  std::vector<Complex> bins(static_cast<std::size_t>(m)), values(bins.size()),
      phase(static_cast<std::size_t>(harmonics));
  GridBlock block;
  block.stride = blocks;
  for (Eigen::MatrixXd* out : {&block.q, &block.dq, &block.ddq}) out->resize(m, dof);
  for (long r = 0; r < blocks; ++r) {
    block.first = r;
    // At s = r + blocks k, l wf t_s = 2 pi l r / n + 2 pi l k / m: the first part is the
    // block's phase, its angle reduced in integers so that it stays exact for large l r.
    for (Eigen::Index l = 0; l < harmonics; ++l) {
      const long turns = ((l + 1) * r) % n;
      phase[static_cast<std::size_t>(l)] = std::polar(
          1.0, 2.0 * std::numbers::pi * static_cast<double>(turns) / static_cast<double>(n));
    }
    const Eigen::MatrixXcd* sources[3] = {&c.q, &c.dq, &c.ddq};
    Eigen::MatrixXd* targets[3] = {&block.q, &block.dq, &block.ddq};
    for (int key = 0; key < 3; ++key) {
      for (Eigen::Index j = 0; j < dof; ++j) {
        std::fill(bins.begin(), bins.end(), Complex(0.0, 0.0));
        for (Eigen::Index l = 0; l < harmonics; ++l) {
          bins[static_cast<std::size_t>((l + 1) % m)] +=
              (*sources[key])(j, l) * phase[static_cast<std::size_t>(l)];
        }
        if (m > 1) {
          fft.inv(values.data(), bins.data(), m);
        } else {
          values[0] = bins[0];
        }
        const double offset = key == 0 ? trajectory.q0[j] : 0.0;
        for (long k = 0; k < m; ++k) {
          (*targets[key])(k, j) = offset + values[static_cast<std::size_t>(k)].real();
        }
      }
    }
    visit(block);
  }
}

}  // namespace modelgen::detail
