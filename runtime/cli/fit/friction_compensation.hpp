// Bona & Curatella, section 3.4: the measured torque is compensated for friction before the
// projection, which a linear FIR from the references cannot reproduce (sign(dq)); here with
// the friction parameters of a first IDIM-WLS on the same prepared records.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/closed_loop/projection_method.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::internal {

/// A base parameter of friction: viscous or Coulomb, symmetric or not (Fv, Fc, Fvp, Fcn, Fvm...).
bool is_friction_parameter(const std::string& name);

/// Per record, the friction torque (prepared samples x dof) of W(q, dq, ddq) beta_f, beta_f
/// the friction parameters of an IDIM-WLS on the records' prepared data (decimation and
/// `min_speed` as stage 2 uses them), every other parameter zero. Throws EstimationError as
/// identify() does.
std::vector<Eigen::MatrixXd> friction_torques(const IdentificationModel& model,
                                              const std::vector<ProjectionRecord>& records,
                                              const std::vector<double>& min_speed);

}  // namespace modelgen::internal
