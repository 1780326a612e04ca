// The plan of fit --method ml: a-priori values, moving axes, unknowns per approach.

#include "runtime/cli/fit/ml_plan.hpp"

#include <algorithm>
#include <cctype>
#include <iostream>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/model/command_line.hpp"

namespace modelgen::internal {

namespace {

// The a-priori values of every ml_param_names() entry, and the names that had none.
// Mapping from the description's standard parameters: XXj..Mj keep their names; the joint-side
// rotor inertia Iaj becomes the motor-side JMj = Iaj / K_jj^2 (K = motor_from_joint; for a
// diagonal K the two models then agree on tau_joint = K^T tau_M). Friction Fv/Fc is not mapped:
// the drive model's Rv/Rc are motor-side and usually unknown. Without a value: Rzj 1 (no loss),
// everything else 0; those names are reported.
Eigen::VectorXd prior_values(const modelgen::RobotModel& description, const DriveChain& drive,
                             const std::vector<std::string>& names,
                             const std::map<std::string, double>& overrides,
                             std::vector<std::string>& missing) {
  std::map<std::string, double> known;
  for (std::size_t k = 0; k < description.known_values.size(); ++k) {
    if (!description.known_values[k]) continue;
    const std::string& name = description.tree.params[k].name;
    const double value = *description.known_values[k];
    if (name.compare(0, 2, "Ia") == 0 && name.size() > 2 && std::isdigit(name[2]) &&
        name.find_first_not_of("0123456789", 2) == std::string::npos) {
      const int j = std::stoi(name.substr(2)) - 1;
      if (j >= 0 && j < drive.motor_from_joint.rows()) {
        const double ratio = drive.motor_from_joint(j, j);
        known["JM" + name.substr(2)] = value / (ratio * ratio);
      }
    } else {
      known[name] = value;
    }
  }
  for (const auto& [name, value] : overrides) known[name] = value;
  Eigen::VectorXd values(static_cast<Eigen::Index>(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto found = known.find(names[k]);
    if (found != known.end()) {
      values[static_cast<Eigen::Index>(k)] = found->second;
    } else {
      values[static_cast<Eigen::Index>(k)] = names[k].compare(0, 2, "Rz") == 0 ? 1.0 : 0.0;
      missing.push_back(names[k]);
    }
  }
  return values;
}

// The motors (0-based) that move: max |dq_M,i| (dq_M = K dq, eq. 9) above 1e-6 times the
// largest motor speed. Not an exact zero test: the periodic route's Fourier re-estimation
// leaves rounding-level velocities on axes held still.
std::vector<int> moving_axes(const std::vector<MlExperiment>& data, const DriveChain& drive) {
  const Eigen::Index dof = drive.motor_from_joint.rows();
  Eigen::VectorXd speed = Eigen::VectorXd::Zero(dof);
  for (const MlExperiment& x : data) {
    const Eigen::MatrixXd dq_M = x.dq * drive.motor_from_joint.transpose();
    speed = speed.cwiseMax(dq_M.cwiseAbs().colwise().maxCoeff().transpose());
  }
  std::vector<int> axes;
  for (Eigen::Index i = 0; i < dof; ++i) {
    if (speed[i] > 1e-6 * speed.maxCoeff()) axes.push_back(static_cast<int>(i));
  }
  return axes;
}

// The motor (1-based) a drive parameter name JMj/Rvj/Rcj/Rzj belongs to, or 0.
int drive_motor(const std::string& name) {
  for (const char* stem : {"JM", "Rv", "Rc", "Rz"}) {
    if (name.compare(0, 2, stem) == 0 && name.size() > 2 &&
        name.find_first_not_of("0123456789", 2) == std::string::npos) {
      return std::stoi(name.substr(2));
    }
  }
  return 0;
}

}  // namespace

MlSetup MlPlan::setup(int approach) const {
  MlSetup setup;
  setup.payload_link = payload_link;
  setup.axes = axes;
  // Load parameters given in --known are known (a weighed mass, say); the rest are unknown.
  if (groups.count("load")) {
    for (const std::string& name : load_param_names()) {
      if (!overrides.count(name)) setup.unknown.push_back(name);
    }
  }
  for (const char* stem : {"Rv", "Rc", "Rz"}) {
    if (!groups.count(stem) || (std::string(stem) == "Rz" && approach != 3)) continue;
    for (const int j : axes) setup.unknown.push_back(stem + std::to_string(j + 1));
  }
  if (setup.unknown.empty()) throw UsageError{"--unknown leaves nothing to identify"};
  return setup;
}

Eigen::VectorXd MlPlan::values(int approach) const {
  Eigen::VectorXd out = priors;
  if (approach != 3) {
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (names[k].compare(0, 2, "Rz") == 0) out[static_cast<Eigen::Index>(k)] = 1.0;
    }
  }
  return out;
}

MlPlan make_ml_plan(const RobotModel& description, const DriveChain& drive,
                    std::vector<std::string> names, std::set<std::string> groups,
                    std::map<std::string, double> overrides,
                    const std::vector<MlExperiment>& data) {
  MlPlan plan;
  plan.names = std::move(names);
  plan.groups = std::move(groups);
  plan.overrides = std::move(overrides);
  plan.priors = prior_values(description, drive, plan.names, plan.overrides, plan.missing);
  plan.axes = moving_axes(data, drive);
  if (plan.axes.empty()) throw EstimationError("maximum likelihood: no motor moves in the data");
  plan.payload_link = description.payload_body >= 0 ? description.payload_body + 1 : 0;
  return plan;
}

void warn_defaulted_priors(const MlPlan& plan, const std::vector<int>& approaches) {
  const bool with_rz = std::find(approaches.begin(), approaches.end(), 3) != approaches.end();
  const MlSetup widest = plan.setup(approaches.back());
  std::string list;
  for (const std::string& name : plan.missing) {
    if (std::find(widest.unknown.begin(), widest.unknown.end(), name) != widest.unknown.end()) {
      continue;
    }
    if (name.compare(0, 2, "Rz") == 0 && !with_rz) continue;
    // Approach 1 estimates the rotor inertias.
    if (name.compare(0, 2, "JM") == 0 && approaches == std::vector<int>{1}) continue;
    // Drive parameters of motors not fitted do not enter eq. 18.
    const int motor = drive_motor(name);
    if (motor > 0 && std::find(plan.axes.begin(), plan.axes.end(), motor - 1) == plan.axes.end()) {
      continue;
    }
    list += " " + name;
  }
  if (!list.empty()) {
    std::cerr << "modelid: warning: no a-priori value (description 'known:' or --known) for" << list
              << "; taken as 0 (Rz as 1)\n";
  }
}

}  // namespace modelgen::internal
