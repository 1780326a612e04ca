// The covariance of the errors-in-variables score J' r (Bona & Curatella eq. 16) when the
// noise of the observations is correlated: a few Fourier lines per axis (periodic_noise.hpp),
// so the standard deviations use (J'J)^-1 Cov(J' r) (J'J)^-1 instead of the white s^2 (J'J)^-1.

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>

#include "runtime/src/estimation/errors_in_variables_access.hpp"
#include "runtime/src/signal/dft.hpp"

namespace modelgen {

using RowMajor = RowMajorMatrix;

namespace {

// Lines 0..L of the DFT of g, sum_k g_k exp(-2 pi i l k / N): direct sums for few lines, the
// FFT for many.
std::vector<std::complex<double>> low_lines(const Eigen::VectorXd& g, Eigen::Index L) {
  const Eigen::Index N = g.size();
  std::vector<std::complex<double>> out;
  if (L > 64) {
    out = detail::dft(g);
    out.resize(static_cast<std::size_t>(L + 1));
    return out;
  }
  out.assign(static_cast<std::size_t>(L + 1), 0.0);
  for (Eigen::Index l = 0; l <= L; ++l) {
    // exp(-2 pi i l k / N) by a rotating phasor (rounding grows like N eps, ~1e-12).
    const std::complex<double> step =
        std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(l) / static_cast<double>(N));
    std::complex<double> sum = 0, phasor = 1;
    for (Eigen::Index k = 0; k < N; ++k) {
      sum += g[k] * phasor;
      phasor *= step;
    }
    out[static_cast<std::size_t>(l)] = sum;
  }
  return out;
}

// cov += (1 / N^2) [v_0 K_0 K_0' + 2 sum_{l >= 1} v_l Re(K_l K_l^H)] (K: lines x params).
void add_line_covariance(const Eigen::MatrixXcd& K, const Eigen::VectorXd& v, double N,
                         Eigen::MatrixXd& cov) {
  for (Eigen::Index l = 0; l < K.rows(); ++l) {
    const Eigen::VectorXcd k = K.row(l).transpose();
    const double weight = (l == 0 ? 1.0 : 2.0) * v[l] / (N * N);
    cov += weight * (k * k.adjoint()).real();
  }
}

}  // namespace

// Covariance of the score J' r at theta from the noise of the observations, linearised:
// r_k = L_k^-1 (Js_k e_x,k - e_tau,k), so J' r = sum_k A_k (Js_k e_x,k - e_tau,k) with
// A_k = J_k' L_k^-1. The noise of axis j's q, dq, ddq is the kept Fourier lines E_l of its
// averaged positions (see periodic_noise.hpp), e(t_k) = (1/N) sum_{|l|<=H} E_l exp(2 pi i l k/N)
// and its derivatives (i w l)^m E_l..., so the sum over k is (1/N) sum_l E_l K_l with
// K_l = conj(G_q,l - i w l G_dq,l - (w l)^2 G_ddq,l), G_l the DFT of the per-sample weights
// g_q(k) = A_k Js_k[:, j], etc. Lines independent with E|E_l|^2 = v_l give
// Cov = (1/N^2) [v_0 K_0 K_0' + 2 sum_{l>=1} v_l Re(K_l K_l^H)]; the torques likewise over
// their kept lines, or white (sum_k g g' sigma^2) when kept whole. Nullopt when the noise has
// no lines (not from periodic_noise()). When the regressor is projected on the torques' kept
// harmonics, the state noise reaches the residual through that projection too, which this
// leaves out: the state noise above the kept harmonics is counted, and the standard
// deviations err on the large side.
std::optional<Eigen::MatrixXd> ErrorsInVariablesAccess::score_covariance(
    const ErrorsInVariablesObjective& o, const Eigen::VectorXd& theta, const Eigen::MatrixXd& J) {
  const IdentificationModel& model = o.model_;
  const int n = model.dof(), b = model.num_base_params();
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(b, b);
  RowMajor Js(n, 3 * n);
  Eigen::MatrixXd M(n, 3 * n), S2(n, n);
  Eigen::VectorXd q(n), dq(n), ddq(n);
  for (std::size_t e = 0; e < o.data_.size(); ++e) {
    const Trajectory& x = o.data_[e];
    const PeriodicNoise& v = o.noise_[e];
    const Eigen::Index N = x.q.rows(), first = o.first_[e];
    if (v.q_lines.cols() != n || v.samples != N || !(v.period > 0) ||
        (v.tau_lines.size() != 0 && v.tau_lines.cols() != n)) {
      return std::nullopt;
    }
    // Per sample: A_k (b x n) and the state Jacobian.
    std::vector<Eigen::MatrixXd> A(static_cast<std::size_t>(N));
    std::vector<RowMajor> state(static_cast<std::size_t>(N));
    for (Eigen::Index k = 0; k < N; ++k) {
      q = x.q.row(k).transpose();
      dq = x.dq.row(k).transpose();
      ddq = x.ddq.row(k).transpose();
      model.inverse_dynamics_state_jacobian(q.data(), dq.data(), ddq.data(), theta.data(),
                                            Js.data());
      equation_error_covariance(Js, v, M, S2);
      const Eigen::LLT<Eigen::MatrixXd> llt(S2);
      const Eigen::MatrixXd Jk = J.middleRows((first + k) * n, n);
      A[static_cast<std::size_t>(k)] = llt.matrixU().solve(Jk).transpose();  // L^-T J_k
      state[static_cast<std::size_t>(k)] = Js;
    }
    const double w = 2.0 * std::numbers::pi / v.period, Nd = static_cast<double>(N);
    const Eigen::Index H = v.q_lines.rows() - 1, Ht = v.tau_lines.rows() - 1;
    Eigen::VectorXd gq(N), gdq(N), gddq(N), gtau(N);
    for (int j = 0; j < n; ++j) {
      Eigen::MatrixXcd Kq(H + 1, b), Kt(std::max<Eigen::Index>(Ht + 1, 0), b);
      Eigen::MatrixXd white(N, b);
      for (int p = 0; p < b; ++p) {
        for (Eigen::Index k = 0; k < N; ++k) {
          const Eigen::MatrixXd& Ak = A[static_cast<std::size_t>(k)];
          const RowMajor& Jsk = state[static_cast<std::size_t>(k)];
          gq[k] = Ak.row(p).dot(Jsk.col(j));
          gdq[k] = Ak.row(p).dot(Jsk.col(n + j));
          gddq[k] = Ak.row(p).dot(Jsk.col(2 * n + j));
          gtau[k] = -Ak(p, j);
        }
        const auto Gq = low_lines(gq, H), Gdq = low_lines(gdq, H), Gddq = low_lines(gddq, H);
        for (Eigen::Index l = 0; l <= H; ++l) {
          const double wl = w * static_cast<double>(l);
          const auto i = static_cast<std::size_t>(l);
          Kq(l, p) = Gq[i] - std::complex<double>(0, wl) * Gdq[i] - wl * wl * Gddq[i];
        }
        if (Ht >= 0) {
          const auto Gt = low_lines(gtau, Ht);
          for (Eigen::Index l = 0; l <= Ht; ++l) Kt(l, p) = Gt[static_cast<std::size_t>(l)];
        } else {
          white.col(p) = gtau;
        }
      }
      add_line_covariance(Kq, v.q_lines.col(j), Nd, cov);
      if (Ht >= 0) {
        add_line_covariance(Kt, v.tau_lines.col(j), Nd, cov);
      } else {
        cov += v.tau[j] * white.transpose() * white;
      }
    }
  }
  return cov;
}

}  // namespace modelgen
