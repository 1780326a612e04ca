// Essential parameters for `modelid fit --essential`: the stacked equations of the chosen
// method rebuilt in the CLI and given to essential_parameters() (Gautier & Briot: iterative
// elimination of the parameter with the largest relative standard deviation, ratio r_sigma).
//
// Stopgap: identify() (modelgen/identify.hpp) assembles the same W, y and groups but does not
// return them. Once the runtime exposes them (for instance
//   struct Observations { Eigen::MatrixXd W; Eigen::VectorXd y; std::vector<int> group; };
//   Observations observation_equations(const IdentificationModel&,
//                                      const std::vector<Trajectory>&, Method);
// in modelgen/identify.hpp, used by identify() itself), observation_equations below goes away
// and essential_fit() calls the library's.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/data.hpp"
#include "modelgen/estimate.hpp"
#include "modelgen/identify.hpp"
#include "modelgen/model.hpp"

namespace modelgen::internal {

/// The equations a method solves: W (rows x num_base_params()), y (rows) and, for WLS, the
/// group of each row; `group` is empty for OLS.
struct Observations {
  Eigen::MatrixXd W;
  Eigen::VectorXd y;
  std::vector<int> group;
};

/// As identify() builds them: IDIM rows (one per joint and sample, Gautier & Briot eq. 4-6),
/// grouped per joint and experiment for WLS (eq. 20); PIM rows (one per sample, eq. 9-10:
/// dq . tau = dq^T W beta) grouped per experiment. Every trajectory needs dq, ddq and dof()
/// columns; throws EstimationError otherwise.
Observations observation_equations(const IdentificationModel& model,
                                   const std::vector<Trajectory>& data, Method method);

/// essential_parameters() on observation_equations(model, data, method) with the model's
/// base parameter names. r_sigma > 1. Throws EstimationError as fit_ols/fit_wls do.
EssentialParameters essential_fit(const IdentificationModel& model,
                                  const std::vector<Trajectory>& data, Method method,
                                  double r_sigma);

}  // namespace modelgen::internal
