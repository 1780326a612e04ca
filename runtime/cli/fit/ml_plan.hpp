// The plan of fit --method ml (Swevers et al. 2002, section 4): the a-priori values theta2
// from the description's `known:` and --known, the moving axes, and per approach the unknowns
// theta1 and the values the fit starts from (ml_plan.cpp).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/ml/problem.hpp"
#include "modelgen/model/drive_chain.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::internal {

struct MlPlan {
  std::vector<std::string> names;           ///< ml_param_names() of the drive model
  std::set<std::string> groups;             ///< --unknown: load, Rv, Rc, Rz
  std::map<std::string, double> overrides;  ///< --known
  std::vector<int> axes;                    ///< the moving motors, 0-based
  int payload_link = 0;                     ///< 1-based, 0 for none
  Eigen::VectorXd priors;                   ///< a-priori value of every name
  std::vector<std::string> missing;         ///< names without an a-priori value (taken as 0, Rz 1)

  /// theta1 of an approach: the chosen groups for the moving axes; the efficiencies only in
  /// approach 3. UsageError when it is empty.
  MlSetup setup(int approach) const;
  /// The values of an approach: the priors, every Rz 1 outside approach 3.
  Eigen::VectorXd values(int approach) const;
};

/// The plan for `description` with `drive`, the drive model's parameter `names`, the --unknown
/// `groups`, the --known `overrides` and the prepared `data`. EstimationError when no motor
/// moves.
MlPlan make_ml_plan(const RobotModel& description, const DriveChain& drive,
                    std::vector<std::string> names, std::set<std::string> groups,
                    std::map<std::string, double> overrides, const std::vector<MlExperiment>& data);

/// A warning on standard error naming the a-priori values the `approaches` use without having
/// been given (taken as 0, Rz as 1); the unknowns only start there.
void warn_defaulted_priors(const MlPlan& plan, const std::vector<int>& approaches);

}  // namespace modelgen::internal
