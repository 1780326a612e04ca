// Swevers et al. 2002, section 3.2 and approach 1 of section 4: weighted least squares on the
// base parameters of the linear drive model (efficiencies 1), then the load, friction and rotor
// inertias from the base-parameter estimates and the a-priori link values.
//
// The base parameters are numeric, of this experiment: a column-pivoted QR of the weighted,
// column-scaled regressor A D^-1 P = Q [R11 R12] gives psi = [I, R11^-1 R12] P^T D theta, the
// combinations the data determine, estimated as R11^-1 Q1^T b with covariance s^2 R11^-1 R11^-T
// (Gautier & Briot eq. 15-18 in this basis). The equations G theta = psi_hat ("solving a set of
// equations", section 3.2) are then solved for the unknown columns with the link values known, by
// generalised least squares with psi_hat's covariance: the combinations the experiment excites
// poorly (section 4's reason 3 for approach 1's errors) count as little as they deserve. The load
// comes from its ten standard parameters, load_from_standard (eq. 3 backwards).

#include "modelgen/ml/linear_route.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "modelgen/ml/identifiability.hpp"
#include "modelgen/ml/load_parameters.hpp"

namespace modelgen {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Rank of the base-parameter regressor: pivots below this fraction of the largest are taken as
// combinations the data do not determine (the regrouping relations hold to rounding error).
constexpr double kBaseTolerance = 1e-8;

// "JM", "Rv", "Rc" or "Rz" for a drive parameter JMj .. Rzj, else "" (inertial parameters).
std::string drive_stem(const std::string& name) {
  if (name.size() < 3 || name.find_first_not_of("0123456789", 2) != std::string::npos) return "";
  const std::string stem = name.substr(0, 2);
  return stem == "JM" || stem == "Rv" || stem == "Rc" || stem == "Rz" ? stem : "";
}

// The 0-based motor of drive parameter `name`.
int drive_motor(const std::string& name) { return std::stoi(name.substr(2)) - 1; }

// Minimum-norm solution of M (x - x0) = y - M x0 on unit-norm columns, and d x / d y.
void minimum_norm_step(const Eigen::MatrixXd& M, const Eigen::VectorXd& y,
                       const Eigen::VectorXd& x0, Eigen::VectorXd& x, Eigen::MatrixXd& dx_dy) {
  Eigen::VectorXd scale = M.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c) {
    if (!(scale[c] > 0)) scale[c] = 1;
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(M *
                                                              scale.cwiseInverse().asDiagonal());
  cod.setThreshold(1e-10);
  dx_dy = scale.cwiseInverse().asDiagonal() * cod.pseudoInverse();
  x = x0 + dx_dy * (y - M * x0);
}

}  // namespace

LinearRoute linear_route(const MlProblem& problem, double rank_tolerance) {
  const DriveModel& model = problem.model();
  const int P = model.num_params();
  const std::vector<std::string>& names = model.param_names();
  const std::vector<int>& axes = problem.axes();
  const std::vector<int>& unknown = problem.unknown_indices();
  const auto is_unknown = [&](int k) {
    return std::find(unknown.begin(), unknown.end(), k) != unknown.end();
  };
  const auto fitted = [&](int motor) {
    return std::find(axes.begin(), axes.end(), motor) != axes.end();
  };
  LinearRoute route;
  MlFitResult& fit = route.fit;
  Eigen::VectorXd all = problem.values();
  bool load = false;
  for (const int k : unknown) {
    if (k >= P) load = true;
    if (k < P && drive_stem(names[k]) == "Rz") all[k] = 1.0;  // no efficiency in the linear model
  }

  // The linear model's parameters: every link's inertial parameters, the fitted motors' rotor
  // inertias (unknown in approach 1) and their friction where it is unknown.
  std::vector<int> linear;
  for (int k = 0; k < P; ++k) {
    const std::string stem = drive_stem(names[k]);
    if (stem.empty() || (stem == "JM" && fitted(drive_motor(names[k]))) ||
        ((stem == "Rv" || stem == "Rc") && is_unknown(k))) {
      linear.push_back(k);
    }
  }
  const Eigen::Index L = static_cast<Eigen::Index>(linear.size());

  // Weighted regressor and right-hand side with the other parameters' torque moved over:
  // tau = tau(theta0) + J (theta - theta0), exact when the fitted efficiencies are 1.
  const Eigen::VectorXd theta = problem.drive_parameters(all);
  const int n = model.dof();
  const Eigen::Index rows = problem.num_samples() * static_cast<Eigen::Index>(axes.size());
  Eigen::MatrixXd A(rows, L);
  Eigen::VectorXd b(rows), sigma(rows);
  std::vector<double> tau(n), J(static_cast<size_t>(n) * P);
  Eigen::Index row = 0;
  for (Eigen::Index s = 0; s < problem.num_samples(); ++s) {
    model.torque_jacobian(s, theta.data(), tau.data(), J.data());
    for (const int i : axes) {
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

  // Base parameters of this experiment by the column-pivoted QR of the column-scaled regressor.
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
  const Eigen::Index r = qr.rank();
  route.base_parameters = static_cast<int>(r);
  const Eigen::MatrixXd R11 = qr.matrixR().topLeftCorner(r, r).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R12 = qr.matrixR().topRightCorner(r, L - r);
  const Eigen::VectorXd Qtb = qr.householderQ().adjoint() * b;
  const auto R11_upper = R11.triangularView<Eigen::Upper>();
  const Eigen::VectorXd psi = R11_upper.solve(Qtb.head(r));
  const Eigen::MatrixXd R11_inv = R11_upper.solve(Eigen::MatrixXd::Identity(r, r));
  const Eigen::VectorXi& order = qr.colsPermutation().indices();
  // psi = [I, R11^-1 R12] P^T D theta_L =: G theta_L; column order[j] of As is the j-th pivot.
  Eigen::MatrixXd G(r, L);
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
  const Eigen::VectorXd residual = b - pivots * psi;
  const double s2 =
      residual.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, rows - r));
  const Eigen::MatrixXd psi_covariance = s2 * R11_inv * R11_inv.transpose();
  fit.residual_std_dev = std::sqrt(s2);
  // Per-motor rms error of the linear model, N m.
  fit.rms_error = Eigen::VectorXd::Zero(n);
  row = 0;
  for (Eigen::Index s = 0; s < problem.num_samples(); ++s) {
    for (const int i : axes) {
      const double e = residual[row] * sigma[row];
      fit.rms_error[i] += e * e;
      ++row;
    }
  }
  fit.rms_error = (fit.rms_error / static_cast<double>(problem.num_samples())).cwiseSqrt();

  // The equations for the unknowns: G_X x = psi_hat - G_K theta_K, the known part from the
  // a-priori values. Unknowns x: the payload's ten standard parameters of the load (its own
  // values known), then the other unknown linear parameters and the rotor inertias.
  const std::vector<int>& payload = problem.payload_indices();
  const auto column_of = [&](int k) {
    return static_cast<Eigen::Index>(std::find(linear.begin(), linear.end(), k) - linear.begin());
  };
  // A load mass known a priori (weighed, say) is the load's standard parameter M: known like the
  // links' values. The other load parameters enter the standard ones nonlinearly; when known,
  // they are imposed in the nonlinear search only.
  const bool mass_known = load && !is_unknown(P);
  const int load_x = load ? (mass_known ? kLoadParams - 1 : kLoadParams) : 0;
  std::vector<std::string> x_names;
  std::vector<Eigen::Index> x_columns;  // column of theta_L per entry of x
  for (int m = 0; m < load_x; ++m) {    // the load's XX .. MZ (and M)
    x_names.push_back(load_param_names()[m + (mass_known ? 1 : 0)]);
    x_columns.push_back(column_of(payload[m]));
  }
  const auto unknown_beyond_mass =
      std::count_if(unknown.begin(), unknown.end(), [&](int k) { return k > P; });
  if (load && unknown_beyond_mass < kLoadParams - 1) {
    fit.notes.push_back(
        "linear route: known load parameters other than the mass are imposed in the nonlinear "
        "search only");
  }
  std::vector<std::string> skipped;  // unknowns the linear model does not contain
  for (const int k : unknown) {
    if (k >= P) continue;
    const std::string stem = drive_stem(names[k]);
    if (stem == "Rz") continue;
    const Eigen::Index c = column_of(k);
    if (c == L || (load && std::find(payload.begin(), payload.end(), k) != payload.end())) {
      skipped.push_back(names[k]);
      continue;
    }
    x_names.push_back(names[k]);
    x_columns.push_back(c);
  }
  for (const int k : linear) {
    if (drive_stem(names[k]) == "JM" && !is_unknown(k)) {
      x_names.push_back(names[k]);
      x_columns.push_back(column_of(k));
    }
  }
  const Eigen::Index X = static_cast<Eigen::Index>(x_columns.size());
  Eigen::VectorXd theta_known(L);
  for (Eigen::Index c = 0; c < L; ++c) theta_known[c] = all[linear[c]];  // own values
  if (mass_known) theta_known[column_of(payload[9])] += all[P];
  Eigen::VectorXd x0(X);
  std::array<double, 10> load0{};
  if (load) load0 = standard_from_load(LoadParameters::from_vector(all.data() + P));
  for (Eigen::Index u = 0; u < X; ++u) {
    const bool load_entry = u < load_x;
    x0[u] = load_entry ? load0[static_cast<size_t>(u)] : all[linear[x_columns[u]]];
    if (!load_entry) theta_known[x_columns[u]] = 0;
  }
  Eigen::MatrixXd M(r, X);
  for (Eigen::Index u = 0; u < X; ++u) M.col(u) = G.col(x_columns[u]);
  // Generalised least squares with the estimates' covariance s^2 R11^-1 R11^-T: whitened by
  // R11 / s, so that combinations the data determine poorly count little.
  const Eigen::MatrixXd whiten = R11 / std::sqrt(s2);
  const Eigen::MatrixXd Mw = whiten * M;
  const Eigen::VectorXd yw = whiten * (psi - G * theta_known);
  Eigen::VectorXd x;
  Eigen::MatrixXd dx_dy;
  minimum_norm_step(Mw, yw, x0, x, dx_dy);
  const Eigen::MatrixXd dx_dpsi = dx_dy * whiten;
  const Eigen::MatrixXd x_covariance = dx_dpsi * psi_covariance * dx_dpsi.transpose();

  // The load in its own terms; its covariance and the identifiability in those terms through
  // d standard / d load (at the estimate, or where the search would start when it has no mass).
  Eigen::MatrixXd to_load = Eigen::MatrixXd::Identity(X, X);  // d (load terms) / d x
  LoadParameters estimate;
  bool load_found = false;
  if (load) {
    LoadParameters at = LoadParameters::from_vector(all.data() + P);
    double standard[10];
    for (int m = 0; m < load_x; ++m) standard[m] = x[m];
    if (mass_known) standard[9] = all[P];
    try {
      estimate = load_from_standard(standard);
      at = estimate;
      load_found = true;
    } catch (const std::invalid_argument& error) {
      fit.notes.push_back(
          std::string("linear route: no load from the base parameters (") + error.what() +
          (at.mass > 0 ? "); the search starts from the given load"
                       : "); with no a-priori load, the search starts from 1 kg at the origin of "
                         "the payload link's frame"));
    }
    if (!(at.mass > 0)) at.mass = 1;  // only to name directions in load terms
    // d standard / d load; with the mass known, XX .. MZ against cx .. Iyz.
    const Eigen::MatrixXd S = standard_from_load_jacobian(at);
    to_load.topLeftCorner(load_x, load_x) =
        (mass_known ? Eigen::MatrixXd(S.block(0, 1, load_x, load_x)) : S).inverse();
  }
  const Eigen::MatrixXd covariance = to_load * x_covariance * to_load.transpose();
  // At least as many rows as unknowns for identifiability(): fewer base parameters than
  // unknowns leave directions undetermined, which zero rows keep visible.
  Eigen::MatrixXd M_load = Eigen::MatrixXd::Zero(std::max(r, X), X);
  M_load.topRows(r) = Mw * to_load.inverse();
  fit.names = x_names;
  fit.identifiability = identifiability(M_load, x_names, rank_tolerance);
  fit.value = x;
  fit.std_dev = covariance.diagonal().cwiseSqrt();
  if (load_found) {
    const std::array<double, kLoadParams> v = estimate.to_vector();
    for (int m = 0; m < load_x; ++m)
      fit.value[m] = v[static_cast<size_t>(m + kLoadParams - load_x)];
  } else if (load) {
    fit.value.head(load_x).setConstant(kNaN);
    fit.std_dev.head(load_x).setConstant(kNaN);
  }
  for (Eigen::Index u = 0; u < X; ++u) {
    if (!fit.identifiability.identifiable[static_cast<size_t>(u)]) {
      fit.value[u] = kNaN;
      fit.std_dev[u] = kNaN;
    }
  }
  if (load) {
    // The ten load values; a known mass in front, with standard deviation 0.
    Eigen::VectorXd value(kLoadParams), sd(kLoadParams);
    if (mass_known) {
      value << all[P], fit.value.head(load_x);
      sd << 0.0, fit.std_dev.head(load_x);
    } else {
      value = fit.value.head(kLoadParams);
      sd = fit.std_dev.head(kLoadParams);
    }
    fit.has_load = true;
    fit.load = LoadParameters::from_vector(value.data());
    fit.load_std_dev = LoadParameters::from_vector(sd.data());
    fit.load_warnings = load_warnings(fit.load);
  }
  if (!skipped.empty()) {
    std::string list;
    for (const std::string& name : skipped) list += " " + name;
    fit.notes.push_back("linear route: not in the linear model, kept at the given values:" + list);
  }

  // The starting point of the nonlinear search: the problem's unknowns from x.
  route.values = all;
  for (Eigen::Index u = load_x; u < X; ++u) {
    const int k = linear[x_columns[u]];
    if (is_unknown(k)) route.values[k] = x[u];
  }
  if (load_found) {
    const std::array<double, kLoadParams> v = estimate.to_vector();
    for (int m = 0; m < kLoadParams; ++m) {
      if (is_unknown(P + m)) route.values[P + m] = v[static_cast<size_t>(m)];
    }
  } else if (load && !mass_known && !(all[P] > 0)) {
    // Nothing to start from: a unit mass, so that the centre of gravity has an effect and the
    // rank at the start is the generic one (at m = 0 the centre of gravity would look
    // unidentifiable and the mass identifiable, whatever the data).
    for (int m = 0; m < kLoadParams; ++m) {
      if (is_unknown(P + m)) route.values[P + m] = m == 0 ? 1.0 : 0.0;
    }
  }
  fit.all_values = route.values;
  fit.initial = fit.value;
  fit.converged = true;
  return route;
}

}  // namespace modelgen
