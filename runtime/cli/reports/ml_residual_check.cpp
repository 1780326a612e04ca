// The ML route's torque errors on the joint side, judged by residual_check's rules.

#include "runtime/cli/reports/ml_residual_check.hpp"

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/ml/joint_errors.hpp"
#include "runtime/cli/reports/residual_check.hpp"

namespace modelgen::internal {

int warn_ml_residual_against_noise(std::ostream& err, const IdentificationModel& model,
                                   const Experiments& experiments,
                                   const Eigen::MatrixXd& motor_errors,
                                   const std::vector<int>& axes, Eigen::Index unknowns,
                                   const std::string& whose) {
  std::vector<Eigen::Index> samples;
  for (const Trajectory& x : experiments.data) samples.push_back(x.t.size());
  const MlJointErrors joint =
      ml_joint_errors(motor_errors, model.drive_chain().motor_from_joint, axes, samples);
  ResidualWording wording;
  wording.whose = whose;
  wording.judged = joint.judged;
  wording.drive_model = true;
  wording.unknowns = unknowns;
  return warn_period_residual_against_noise(err, model, experiments, joint.errors, wording);
}

}  // namespace modelgen::internal
