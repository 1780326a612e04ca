// The base parameters of the experiment for the linear route (linear_base.hpp). With the
// fitted efficiencies 1 the drive model is linear in the chosen parameters, so
// tau = tau(theta0) + J (theta - theta0) holds exactly; A D^-1 P = Q [R11 R12] then gives
// psi = [I, R11^-1 R12] P^T D theta, estimated as R11^-1 Q1^T b with covariance s^2 R11^-1 R11^-T.

#include "runtime/src/ml/linear_base.hpp"

#include <Eigen/QR>
#include <cmath>

namespace modelgen::detail {
namespace {

// Rank of the base-parameter regressor: pivots below this fraction of the largest are taken as
// combinations the data do not determine (the regrouping relations hold to rounding error).
constexpr double kBaseTolerance = 1e-8;

}  // namespace

std::string drive_stem(const std::string& name) {
  if (name.size() < 3 || name.find_first_not_of("0123456789", 2) != std::string::npos) return "";
  const std::string stem = name.substr(0, 2);
  return stem == "JM" || stem == "Rv" || stem == "Rc" || stem == "Rz" ? stem : "";
}

int drive_motor(const std::string& name) { return std::stoi(name.substr(2)) - 1; }

// Column of theta_L that holds parameter k, or linear.size() when the linear model lacks it.
Eigen::Index column_of(const std::vector<int>& linear, int k) {
  return static_cast<Eigen::Index>(std::find(linear.begin(), linear.end(), k) - linear.begin());
}

// The linear model's parameters: every link's inertial parameters, the fitted motors' rotor
// inertias (unknown in approach 1) and their friction where it is unknown.
std::vector<int> linear_parameters(const RouteInputs& in) {
  std::vector<int> linear;
  for (int k = 0; k < in.P; ++k) {
    const std::string stem = drive_stem(in.names[k]);
    if (stem.empty() || (stem == "JM" && in.fitted(drive_motor(in.names[k]))) ||
        ((stem == "Rv" || stem == "Rc") && in.is_unknown(k))) {
      linear.push_back(k);
    }
  }
  return linear;
}

// Weighted regressor and right-hand side with the other parameters' torque moved over:
// tau = tau(theta0) + J (theta - theta0), exact when the fitted efficiencies are 1.
WeightedSystem weighted_system(const RouteInputs& in, const std::vector<int>& linear) {
  const MlProblem& problem = in.problem;
  const int P = in.P;
  const Eigen::Index L = static_cast<Eigen::Index>(linear.size());
  const Eigen::VectorXd theta = problem.drive_parameters(in.all);
  const int n = in.model.dof();
  const Eigen::Index rows = problem.num_samples() * static_cast<Eigen::Index>(in.axes.size());
  WeightedSystem system;
  Eigen::MatrixXd& A = system.A;
  Eigen::VectorXd& b = system.b;
  Eigen::VectorXd& sigma = system.sigma;
  A.resize(rows, L);
  b.resize(rows);
  sigma.resize(rows);
  std::vector<double> tau(n), J(static_cast<size_t>(n) * P);
  Eigen::Index row = 0;
  for (Eigen::Index s = 0; s < problem.num_samples(); ++s) {
    in.model.torque_jacobian(s, theta.data(), tau.data(), J.data());
    for (const int i : in.axes) {
      double other = tau[i];
      for (Eigen::Index c = 0; c < L; ++c) {
        const double d = J[static_cast<size_t>(i) * P + linear[c]];
        A(row, c) = d;
        other -= d * theta[linear[c]];
      }
      sigma[row] = problem.sigma()(s, i);
      A.row(row) /= sigma[row];
      b[row] = (problem.measured()(s, i) - other) / sigma[row];
      ++row;
    }
  }
  return system;
}

// Base parameters of this experiment by the column-pivoted QR of the column-scaled regressor;
// counts the excited and the base parameters into `route`.
BaseEstimate base_estimate(const WeightedSystem& system, LinearRoute& route) {
  const Eigen::MatrixXd& A = system.A;
  const Eigen::Index L = A.cols();
  const Eigen::Index rows = A.rows();
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < L; ++c) {
    if (scale[c] > 0) {
      ++route.excited_parameters;
    } else {
      scale[c] = 1;
    }
  }
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  qr.setThreshold(kBaseTolerance);
  BaseEstimate base;
  const Eigen::Index r = base.r = qr.rank();
  route.base_parameters = static_cast<int>(r);
  base.R11 = qr.matrixR().topLeftCorner(r, r).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R12 = qr.matrixR().topRightCorner(r, L - r);
  const Eigen::VectorXd Qtb = qr.householderQ().adjoint() * system.b;
  const auto R11_upper = base.R11.triangularView<Eigen::Upper>();
  base.psi = R11_upper.solve(Qtb.head(r));
  const Eigen::MatrixXd R11_inv = R11_upper.solve(Eigen::MatrixXd::Identity(r, r));
  const Eigen::VectorXi& order = qr.colsPermutation().indices();
  // psi = [I, R11^-1 R12] P^T D theta_L =: G theta_L; column order[j] of As is the j-th pivot.
  Eigen::MatrixXd& G = base.G;
  G.resize(r, L);
  const Eigen::MatrixXd dependent = R11_inv * R12;
  Eigen::MatrixXd pivots(rows, r);  // the first r pivoted columns of As: Q1 R11
  for (Eigen::Index j = 0; j < L; ++j) {
    const Eigen::Index c = order[j];
    if (j < r) {
      G.col(c) = Eigen::VectorXd::Unit(r, j) * scale[c];
      pivots.col(j) = As.col(c);
    } else {
      G.col(c) = dependent.col(j - r) * scale[c];
    }
  }
  base.residual = system.b - pivots * base.psi;
  base.s2 = base.residual.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, rows - r));
  base.psi_covariance = base.s2 * R11_inv * R11_inv.transpose();
  return base;
}

// Per-motor rms error of the linear model, N m.
Eigen::VectorXd linear_rms_error(const RouteInputs& in, const WeightedSystem& system,
                                 const BaseEstimate& base) {
  Eigen::VectorXd rms = Eigen::VectorXd::Zero(in.model.dof());
  Eigen::Index row = 0;
  for (Eigen::Index s = 0; s < in.problem.num_samples(); ++s) {
    for (const int i : in.axes) {
      const double e = base.residual[row] * system.sigma[row];
      rms[i] += e * e;
      ++row;
    }
  }
  return (rms / static_cast<double>(in.problem.num_samples())).cwiseSqrt();
}

}  // namespace modelgen::detail
