// Errors-in-variables maximum likelihood (Bona & Curatella eq. 15-16): the residuals
// r_i = L_i(theta)^-1 b_i(theta) and their analytic Jacobian, minimised on Ceres
// (Levenberg-Marquardt) from the IDIM-WLS estimate.

#include "modelgen/estimation/errors_in_variables.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <future>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "modelgen/estimation/estimation_error.hpp"
#include "runtime/src/estimation/errors_in_variables_access.hpp"
#include "runtime/src/estimation/solver_setup.hpp"
#include "runtime/src/signal/dft.hpp"

namespace modelgen {

using RowMajor = RowMajorMatrix;

namespace {

void check_noise(const std::string& source, const char* what, const Eigen::VectorXd& v, int dof,
                 bool variance) {
  if (v.size() != dof) {
    throw EstimationError("errors in variables: " + source + ": the " + what + " noise has " +
                          std::to_string(v.size()) + " values for " + std::to_string(dof) +
                          " axes (the data must come from the periodic route)");
  }
  for (int j = 0; j < dof; ++j) {
    if (!std::isfinite(v[j]) || (variance && v[j] < 0)) {
      throw EstimationError("errors in variables: " + source + ": the " + what +
                            " noise variance of axis " + std::to_string(j + 1) +
                            " is negative or not finite");
    }
  }
}

// Keeps harmonics 0..H of every column (one period each) by the DFT: the same projection as
// keep_harmonics (fourier_fit.hpp). Few lines: summed line by line over all columns at once;
// many: the spectrum Y with the other lines zeroed, transformed back by real DFTs,
// x_k = (1/N) sum_l Y_l exp(2 pi i l k / N) = (Re DFT(Re Y) + Im DFT(Im Y))_k / N.
void keep_lines(Eigen::MatrixXd& columns, Eigen::Index H) {
  const Eigen::Index N = columns.rows();
  if (H > 32) {
    Eigen::VectorXd re(N), im(N);
    for (Eigen::Index c = 0; c < columns.cols(); ++c) {
      const std::vector<std::complex<double>> X = detail::dft(columns.col(c));
      re.setZero();
      im.setZero();
      for (Eigen::Index l = 0; l <= H; ++l) {
        const std::complex<double> line = X[static_cast<std::size_t>(l)];
        re[l] = line.real();
        im[l] = line.imag();
        if (l > 0) {  // the conjugate line N - l
          re[N - l] = line.real();
          im[N - l] = -line.imag();
        }
      }
      const std::vector<std::complex<double>> a = detail::dft(re), b = detail::dft(im);
      for (Eigen::Index k = 0; k < N; ++k) {
        columns(k, c) = (a[static_cast<std::size_t>(k)].real() +
                         b[static_cast<std::size_t>(k)].imag()) / static_cast<double>(N);
      }
    }
    return;
  }
  Eigen::MatrixXcd X(H + 1, columns.cols());
  for (Eigen::Index c = 0; c < columns.cols(); ++c) {
    const std::vector<std::complex<double>> spectrum = detail::dft(columns.col(c));
    for (Eigen::Index l = 0; l <= H; ++l) X(l, c) = spectrum[static_cast<std::size_t>(l)];
  }
  const Eigen::ArrayXd k = Eigen::ArrayXd::LinSpaced(N, 0.0, static_cast<double>(N - 1));
  const double Nd = static_cast<double>(N);
  columns = Eigen::VectorXd::Ones(N) * (X.row(0).real() / Nd);
  for (Eigen::Index l = 1; l <= H; ++l) {
    const Eigen::ArrayXd angle = k * (2.0 * std::numbers::pi * static_cast<double>(l) / Nd);
    const Eigen::VectorXd c = angle.cos().matrix() * (2.0 / Nd), s = angle.sin().matrix() * (2.0 / Nd);
    // 2 Re(X_l exp(i angle)) / N.
    columns.noalias() += c * X.row(l).real() - s * X.row(l).imag();
  }
}

}  // namespace

ErrorsInVariablesObjective::ErrorsInVariablesObjective(const IdentificationModel& model,
                                                       const std::vector<Trajectory>& data,
                                                       const std::vector<PeriodicNoise>& noise)
    : model_(model), noise_(noise) {
  const int n = model.dof();
  if (data.empty()) throw EstimationError("errors in variables: no experiments");
  if (noise.size() != data.size()) {
    throw EstimationError("errors in variables: " + std::to_string(noise.size()) +
                          " noise descriptions for " + std::to_string(data.size()) +
                          " experiments");
  }
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Trajectory& x = data[e];
    if (!x.has_velocity || x.q.cols() != n || x.tau.cols() != n || x.dq.rows() != x.q.rows() ||
        x.ddq.rows() != x.q.rows() || x.tau.rows() != x.q.rows() || x.q.rows() == 0) {
      throw EstimationError("errors in variables: " + x.source +
                            ": needs samples with q, dq, ddq and tau of " + std::to_string(n) +
                            " axes");
    }
    if (!x.q.allFinite() || !x.dq.allFinite() || !x.ddq.allFinite() || !x.tau.allFinite()) {
      throw EstimationError("errors in variables: " + x.source + ": a value is not finite");
    }
    const PeriodicNoise& v = noise[e];
    check_noise(x.source, "q", v.q, n, true);
    check_noise(x.source, "dq", v.dq, n, true);
    check_noise(x.source, "ddq", v.ddq, n, true);
    check_noise(x.source, "tau", v.tau, n, true);
    check_noise(x.source, "q-ddq", v.q_ddq, n, false);
    for (int j = 0; j < n; ++j) {
      if (v.q_ddq[j] * v.q_ddq[j] > v.q[j] * v.ddq[j] * (1 + 1e-12)) {
        throw EstimationError("errors in variables: " + x.source + ": the q-ddq covariance of axis " +
                              std::to_string(j + 1) + " exceeds what its variances allow");
      }
    }
    data_.push_back(x);
    projected_.push_back(Eigen::MatrixXd());
    if (v.tau_lines.size() != 0) {
      const int b = model.num_base_params();
      const Eigen::Index N = x.q.rows();
      Eigen::MatrixXd& rows = projected_.back();
      rows.resize(N, static_cast<Eigen::Index>(n) * b);
      RowMajor W(n, b);
      for (Eigen::Index k = 0; k < N; ++k) {
        const Eigen::VectorXd q = x.q.row(k), dq = x.dq.row(k), ddq = x.ddq.row(k);
        model.regressor(q.data(), dq.data(), ddq.data(), W.data());
        rows.row(k) = Eigen::Map<const Eigen::RowVectorXd>(W.data(), W.size());
      }
      keep_lines(rows, v.tau_lines.rows() - 1);
    }
    first_.push_back(samples_);
    samples_ += x.q.rows();
  }
  first_.push_back(samples_);
}

bool ErrorsInVariablesAccess::evaluate_block(const ErrorsInVariablesObjective& o,
                                             const double* theta, Eigen::Index begin,
                                             Eigen::Index end, double* r_out, double* J_out) {
  const IdentificationModel& model = o.model_;
  const int n = model.dof(), b = model.num_base_params();
  RowMajor W(n, b), Js(n, 3 * n), dJs(n, 3 * n);
  Eigen::MatrixXd M(n, 3 * n), S2(n, n), dS2(n, n), A(n, n);
  Eigen::VectorXd q(n), dq(n), ddq(n), tau(n), unit = Eigen::VectorXd::Zero(b);
  const Eigen::Map<const Eigen::VectorXd> th(theta, b);
  auto e = static_cast<std::size_t>(
      std::upper_bound(o.first_.begin(), o.first_.end(), begin) - o.first_.begin() - 1);
  for (Eigen::Index s = begin; s < end; ++s) {
    while (s >= o.first_[e + 1]) ++e;
    const Trajectory& x = o.data_[e];
    const PeriodicNoise& v = o.noise_[e];
    const Eigen::Index k = s - o.first_[e];
    q = x.q.row(k).transpose();
    dq = x.dq.row(k).transpose();
    ddq = x.ddq.row(k).transpose();
    if (o.projected_[e].size() != 0) {
      W = Eigen::Map<const RowMajor>(o.projected_[e].row(k).eval().data(), n, b);
    } else {
      model.regressor(q.data(), dq.data(), ddq.data(), W.data());
    }
    // b = -G = W theta - tau.
    const Eigen::VectorXd bi = W * th - x.tau.row(k).transpose();
    model.inverse_dynamics_state_jacobian(q.data(), dq.data(), ddq.data(), theta, Js.data());
    equation_error_covariance(Js, v, M, S2);
    const Eigen::LLT<Eigen::MatrixXd> llt(S2);
    if (llt.info() != Eigen::Success) return false;
    const auto L = llt.matrixL();
    Eigen::Map<Eigen::VectorXd> r(r_out + (s - begin) * n, n);
    r = L.solve(bi);
    if (!r.allFinite()) return false;
    if (J_out == nullptr) continue;
    // d r = L^-1 W d theta - Phi(L^-1 dS2 L^-T) r (derivative of the Cholesky factor).
    Eigen::Map<RowMajor> J(J_out + (s - begin) * n * b, n, b);
    J = L.solve(Eigen::MatrixXd(W));
    for (int p = 0; p < b; ++p) {
      unit[p] = 1;
      model.inverse_dynamics_state_jacobian(q.data(), dq.data(), ddq.data(), unit.data(),
                                            dJs.data());
      unit[p] = 0;
      if (dJs.isZero(0)) continue;  // theta_p does not change this sample's S
      dS2 = dJs * M.transpose();
      dS2 += dS2.transpose().eval();
      A = L.solve(L.solve(dS2).transpose());  // L^-1 dS2 L^-T (dS2 symmetric)
      A.diagonal() *= 0.5;
      J.col(p) -= A.triangularView<Eigen::Lower>() * r;
    }
  }
  return true;
}

bool ErrorsInVariablesObjective::evaluate(const Eigen::VectorXd& theta, Eigen::VectorXd& r,
                                          Eigen::MatrixXd* J) const {
  const int n = model_.dof(), b = num_params();
  r.resize(num_residuals());
  RowMajor Jr;
  if (J != nullptr) Jr.resize(num_residuals(), b);
  // Two halves in two threads (the models are stateless).
  const Eigen::Index half = samples_ / 2;
  auto part = [&](Eigen::Index begin, Eigen::Index end) {
    return ErrorsInVariablesAccess::evaluate_block(
        *this, theta.data(), begin, end, r.data() + begin * n,
        J != nullptr ? Jr.data() + begin * n * b : nullptr);
  };
  auto second = std::async(std::launch::async, part, half, samples_);
  const bool ok = part(0, half);
  const bool ok2 = second.get();
  if (J != nullptr) *J = Jr;
  return ok && ok2;
}

double ErrorsInVariablesObjective::cost(const Eigen::VectorXd& theta) const {
  Eigen::VectorXd r;
  if (!evaluate(theta, r, nullptr)) return std::numeric_limits<double>::infinity();
  return 0.5 * r.squaredNorm();
}

namespace {

// One block of samples as a Ceres cost function over the one parameter block theta.
class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const ErrorsInVariablesObjective& objective, Eigen::Index begin, Eigen::Index end,
            int dof)
      : objective_(objective), begin_(begin), end_(end) {
    set_num_residuals(static_cast<int>((end - begin) * dof));
    mutable_parameter_block_sizes()->push_back(objective.num_params());
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    return ErrorsInVariablesAccess::evaluate_block(
        objective_, parameters[0], begin_, end_, residuals,
        jacobians != nullptr ? jacobians[0] : nullptr);
  }

 private:
  const ErrorsInVariablesObjective& objective_;
  Eigen::Index begin_, end_;
};

// Torque errors of theta per joint, as identify() reports them.
void torque_errors(const IdentificationModel& model, const std::vector<Trajectory>& data,
                   const Eigen::VectorXd& theta, Identification& id) {
  const int n = model.dof(), b = model.num_base_params();
  RowMajor W(n, b);
  Eigen::VectorXd error2 = Eigen::VectorXd::Zero(n), torque2 = error2;
  Eigen::Index samples = 0;
  for (const Trajectory& x : data) {
    for (Eigen::Index k = 0; k < x.q.rows(); ++k) {
      const Eigen::VectorXd q = x.q.row(k), dq = x.dq.row(k), ddq = x.ddq.row(k);
      model.regressor(q.data(), dq.data(), ddq.data(), W.data());
      const Eigen::VectorXd tau = x.tau.row(k).transpose();
      error2 += (tau - W * theta).cwiseAbs2();
      torque2 += tau.cwiseAbs2();
    }
    samples += x.q.rows();
  }
  id.rms_error = (error2 / static_cast<double>(samples)).cwiseSqrt();
  id.rms_torque = (torque2 / static_cast<double>(samples)).cwiseSqrt();
  id.torque_rel_error_norm = std::sqrt(error2.sum() / torque2.sum());
  id.fit.relative_error_norm = id.torque_rel_error_norm;
  id.samples = samples;
}

}  // namespace

ErrorsInVariablesResult fit_errors_in_variables(const IdentificationModel& model,
                                                const std::vector<Trajectory>& data,
                                                const std::vector<PeriodicNoise>& noise,
                                                const ErrorsInVariablesOptions& options) {
  const ErrorsInVariablesObjective objective(model, data, noise);
  ErrorsInVariablesResult result;
  result.initial = identify(model, data, Method::kWls);
  const int n = model.dof(), b = model.num_base_params();

  Eigen::VectorXd theta = result.initial.fit.value, r;
  if (!objective.evaluate(theta, r, nullptr)) {
    throw EstimationError(
        "errors in variables: a sample's torque equations carry no noise at the IDIM-WLS "
        "estimate (S^2 of eq. 16 is singular): the noise variances are zero");
  }
  result.initial_cost = 0.5 * r.squaredNorm();

  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  constexpr Eigen::Index kBlock = 64;  // samples per cost block
  for (Eigen::Index begin = 0; begin < objective.samples(); begin += kBlock) {
    problem.AddResidualBlock(
        new BlockCost(objective, begin, std::min(objective.samples(), begin + kBlock), n),
        nullptr, theta.data());
  }
  const ceres::Solver::Summary summary = detail::solve_levenberg_marquardt(
      problem, options.max_iterations, options.threads, "errors in variables");
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.solver_report = summary.BriefReport();
  result.solve_seconds = summary.minimizer_time_in_seconds;

  Eigen::MatrixXd J;
  if (!objective.evaluate(theta, r, &J)) {
    throw EstimationError("errors in variables: S^2 of eq. 16 is singular at the optimum");
  }
  result.final_cost = 0.5 * r.squaredNorm();
  Identification& id = result.id;
  id.names = model.base_param_names();
  LeastSquaresResult& fit = id.fit;
  fit.value = theta;
  fit.equations = static_cast<long long>(r.size());
  // s^2: the residuals' variance, 1 when the noise model (Sigma_x) is right.
  const double s2 = r.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, r.size() - b));
  fit.residual_std_dev = std::sqrt(s2);
  // The naive covariance s^2 (J'J)^-1 (eq. 16's reading: white samples) from the QR of J, and
  // the one that knows the samples' noise is correlated (a few Fourier lines):
  // (J'J)^-1 Cov(J' r) (J'J)^-1, which the standard deviations report when the noise has lines.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
  if (qr.rank() < b) {
    throw EstimationError("errors in variables: the Jacobian at the optimum is rank-deficient (" +
                          std::to_string(qr.rank()) + " of " + std::to_string(b) + ")");
  }
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(b, b).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd RP = R * qr.colsPermutation().transpose();
  fit.information = RP.transpose() * RP / s2;
  const Eigen::MatrixXd R_inverse =
      R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(b, b));
  const Eigen::VectorXd diagonal = R_inverse.rowwise().squaredNorm();
  fit.std_dev.resize(b);
  fit.rel_std_dev.resize(b);
  for (Eigen::Index i = 0; i < b; ++i) {
    fit.std_dev[qr.colsPermutation().indices()[i]] = std::sqrt(s2 * diagonal[i]);
  }
  result.white_std_dev = fit.std_dev;
  const std::optional<Eigen::MatrixXd> score =
      ErrorsInVariablesAccess::score_covariance(objective, theta, J);
  if (score) {
    const Eigen::MatrixXd inverse =
        qr.colsPermutation() * (R_inverse * R_inverse.transpose()) *
        qr.colsPermutation().transpose();  // (J'J)^-1
    const Eigen::MatrixXd covariance = inverse * *score * inverse;
    fit.std_dev = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    fit.information = covariance.inverse();
    result.correlated_noise = true;
  }
  for (Eigen::Index i = 0; i < b; ++i) {
    fit.rel_std_dev[i] = theta[i] != 0.0 ? 100.0 * fit.std_dev[i] / std::abs(theta[i])
                                         : std::numeric_limits<double>::infinity();
  }
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(R).singularValues();
  fit.condition_number = singular[0] / singular[b - 1];
  torque_errors(model, data, theta, id);
  return result;
}

}  // namespace modelgen
