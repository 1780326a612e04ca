// The plant of a closed-loop simulation: joint accelerations from joint torques, with the
// generated mass matrix and inverse dynamics when the model is compiled in (issue 13).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"

namespace modelgen {

/// ddq = M(q)^-1 (tau - h(q, dq)): M the joint-space inertia matrix (drive inertias on its
/// diagonal), h the torques at zero acceleration (Coriolis, centrifugal and gravity torques,
/// friction and torque offsets), both from the base parameters beta; M by a Cholesky
/// factorisation (LDL^T). Coulomb friction is sign(dq) here, discontinuous at rest: an integrator
/// that needs smoothness smooths it itself.
class ForwardDynamics {
 public:
  /// `beta` has model.num_base_params() values. The model must outlive this object.
  /// Throws std::invalid_argument for a wrong number of base parameters.
  ForwardDynamics(const IdentificationModel& model, std::vector<double> beta);

  /// ddq receives dof() values; q, dq and tau have dof() each. Throws std::domain_error naming
  /// q when M(q) is not positive definite (base parameters no robot has) or a value is not
  /// finite. Allocates nothing.
  void accelerations(const double* q, const double* dq, const double* tau, double* ddq);

  int dof() const { return n_; }

 private:
  const IdentificationModel& model_;
  std::vector<double> beta_;
  int n_;
  Eigen::MatrixXd M_;        // the model's values, then L and D in place (LDL^T)
  Eigen::VectorXd h_, rhs_;  // rhs_: the solve's z, then 1/D for a size not unrolled
};

}  // namespace modelgen
