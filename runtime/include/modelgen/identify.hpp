// From trajectories to base-parameter estimates: the stacked IDIM (torques, one equation per
// joint and sample) or PIM (power, one equation per sample) with OLS or WLS (Gautier & Briot
// eq. 14-20), and the torque prediction errors per axis.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data.hpp"
#include "modelgen/estimate.hpp"
#include "modelgen/model.hpp"

namespace modelgen {

enum class Method {
  kOls,     ///< IDIM, ordinary least squares
  kWls,     ///< IDIM, one weight per joint and experiment (eq. 20)
  kPimWls,  ///< PIM, one weight per experiment (power equations, eq. 21)
};

/// "ols", "wls", "pim-wls"; throws EstimationError for anything else.
Method parse_method(const std::string& text);

struct Identification {
  LeastSquaresResult fit;           ///< base parameters in model.base_param_names() order
  std::vector<std::string> names;   ///< model.base_param_names()
  /// Per joint, over all experiments: rms of measured minus predicted torque, and rms of the
  /// measured torque (Swevers Table 3 style).
  Eigen::VectorXd rms_error, rms_torque;
  /// ||tau - W beta|| / ||tau|| over all torque equations (Gautier & Briot Tables III-IV).
  double torque_rel_error_norm = 0;
  Eigen::Index samples = 0;
};

/// Identifies the base parameters of `model` from `data` (each trajectory with dq and ddq set,
/// dof columns). Throws EstimationError with the reason (rank deficiency names parameters).
Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& data,
                        Method method);

}  // namespace modelgen
