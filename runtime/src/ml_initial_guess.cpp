// Swevers et al. 2002, section 3.2: the linear estimate (efficiencies 1) that starts the
// Levenberg-Marquardt search, solved as one weighted least-squares problem on the payload's
// standard parameters and the unknown drive parameters, then the load from eq. 3 backwards.

#include "modelgen/ml_initial_guess.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <stdexcept>

#include "modelgen/load_parameters.hpp"

namespace modelgen {

Eigen::VectorXd linear_initial_guess(const MlProblem& problem, std::vector<std::string>& notes) {
  const DriveModel& model = problem.model();
  const int n = model.dof(), P = model.num_params();
  const std::vector<std::string>& names = model.param_names();
  Eigen::VectorXd all = problem.values();
  std::vector<int> columns;  // drive-parameter indices solved for
  bool load = false;
  for (const int k : problem.unknown_indices()) {
    if (k >= P) {
      load = true;
    } else if (names[k].compare(0, 2, "Rz") == 0) {
      all[k] = 1.0;  // section 3.2: the linear model has no transmission efficiency
    } else {
      columns.push_back(k);
    }
  }
  if (load) {
    for (const int k : problem.payload_indices()) {
      if (std::find(columns.begin(), columns.end(), k) == columns.end()) columns.push_back(k);
    }
  }
  if (columns.empty()) return all;
  Eigen::VectorXd theta = problem.drive_parameters(all);
  const std::vector<int>& axes = problem.axes();
  const Eigen::Index rows = problem.num_samples() * static_cast<Eigen::Index>(axes.size());
  Eigen::MatrixXd A(rows, static_cast<Eigen::Index>(columns.size()));
  Eigen::VectorXd b(rows);
  std::vector<double> tau(n), J(static_cast<size_t>(n) * P);
  Eigen::Index row = 0;
  for (Eigen::Index s = 0; s < problem.num_samples(); ++s) {
    model.torque_jacobian(s, theta.data(), tau.data(), J.data());
    for (const int i : axes) {
      const double w = 1.0 / problem.sigma()(s, i);
      for (size_t c = 0; c < columns.size(); ++c) {
        A(row, static_cast<Eigen::Index>(c)) = w * J[static_cast<size_t>(i) * P + columns[c]];
      }
      b[row++] = w * (problem.measured()(s, i) - tau[i]);
    }
  }
  // Minimum-norm step on unit-norm columns: what the data do not determine stays put.
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c) {
    if (!(scale[c] > 0)) scale[c] = 1;
  }
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(As);
  cod.setThreshold(1e-10);
  const Eigen::VectorXd step = scale.cwiseInverse().asDiagonal() * cod.solve(b);
  for (size_t c = 0; c < columns.size(); ++c)
    theta[columns[c]] += step[static_cast<Eigen::Index>(c)];
  for (const int k : columns) {
    if (std::find(problem.unknown_indices().begin(), problem.unknown_indices().end(), k) !=
        problem.unknown_indices().end()) {
      all[k] = theta[k];
    }
  }
  if (load) {
    double standard[10];
    for (int m = 0; m < 10; ++m) {
      const int k = problem.payload_indices()[m];
      standard[m] = theta[k] - all[k];  // the payload link's own values are known
    }
    try {
      const LoadParameters guess = load_from_standard(standard);
      const std::array<double, kLoadParams> v = guess.to_vector();
      for (const int k : problem.unknown_indices()) {
        if (k >= P) all[k] = v[static_cast<size_t>(k - P)];
      }
      for (const std::string& warning : physical_consistency_warnings(guess)) {
        notes.push_back("linear initial guess: " + warning);
      }
    } catch (const std::invalid_argument& error) {
      notes.push_back(std::string("linear initial guess of the load not used (") + error.what() +
                      "); the given load values start the search");
    }
  }
  return all;
}

}  // namespace modelgen
