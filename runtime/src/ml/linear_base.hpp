// The first half of the linear route (linear_route.cpp, Swevers et al. 2002, section 3.2): the
// linear model's parameters, its weighted regressor with the other parameters' torque moved to
// the right-hand side, and the base parameters of this experiment from a column-pivoted QR of
// the weighted, column-scaled regressor (Gautier & Briot eq. 15-18 in this basis).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/ml/linear_route.hpp"
#include "modelgen/ml/problem.hpp"

namespace modelgen::detail {

// "JM", "Rv", "Rc" or "Rz" for a drive parameter JMj .. Rzj, else "" (inertial parameters).
std::string drive_stem(const std::string& name);

// The 0-based motor of drive parameter `name`.
int drive_motor(const std::string& name);

// The problem's sets the route's steps share, with the values the linear model starts from.
struct RouteInputs {
  explicit RouteInputs(const MlProblem& p)
      : problem(p),
        model(p.model()),
        P(model.num_params()),
        names(model.param_names()),
        axes(p.axes()),
        unknown(p.unknown_indices()),
        all(p.values()) {
    for (const int k : unknown) {
      if (k >= P) load = true;
      if (k < P && drive_stem(names[k]) == "Rz") all[k] = 1.0;  // no efficiency in the linear model
    }
  }
  bool is_unknown(int k) const {
    return std::find(unknown.begin(), unknown.end(), k) != unknown.end();
  }
  bool fitted(int motor) const { return std::find(axes.begin(), axes.end(), motor) != axes.end(); }

  const MlProblem& problem;
  const DriveModel& model;
  const int P;
  const std::vector<std::string>& names;
  const std::vector<int>& axes;
  const std::vector<int>& unknown;
  Eigen::VectorXd all;
  bool load = false;
};

// Column of theta_L that holds parameter k, or linear.size() when the linear model lacks it.
Eigen::Index column_of(const std::vector<int>& linear, int k);

// The linear model's parameters: every link's inertial parameters, the fitted motors' rotor
// inertias (unknown in approach 1) and their friction where it is unknown.
std::vector<int> linear_parameters(const RouteInputs& in);

struct WeightedSystem {
  Eigen::MatrixXd A;
  Eigen::VectorXd b, sigma;
};

// Weighted regressor and right-hand side with the other parameters' torque moved over:
// tau = tau(theta0) + J (theta - theta0), exact when the fitted efficiencies are 1.
WeightedSystem weighted_system(const RouteInputs& in, const std::vector<int>& linear);

// The base parameters psi = G theta_L, their estimate and covariance.
struct BaseEstimate {
  Eigen::Index r = 0;
  Eigen::MatrixXd R11, G, psi_covariance;
  Eigen::VectorXd psi, residual;
  double s2 = 0;
};

// Base parameters of this experiment by the column-pivoted QR of the column-scaled regressor;
// counts the excited and the base parameters into `route`.
BaseEstimate base_estimate(const WeightedSystem& system, LinearRoute& route);

// Per-motor rms error of the linear model, N m.
Eigen::VectorXd linear_rms_error(const RouteInputs& in, const WeightedSystem& system,
                                 const BaseEstimate& base);

}  // namespace modelgen::detail
