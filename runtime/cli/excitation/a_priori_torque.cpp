// A-priori base parameters for the effort limits; see a_priori_torque.hpp.

#include "runtime/cli/excitation/a_priori_torque.hpp"

#include <algorithm>

namespace modelgen::internal {

namespace {

bool inertial(ParamKind kind) {
  return kind == ParamKind::kXX || kind == ParamKind::kXY || kind == ParamKind::kXZ ||
         kind == ParamKind::kYY || kind == ParamKind::kYZ || kind == ParamKind::kZZ ||
         kind == ParamKind::kMX || kind == ParamKind::kMY || kind == ParamKind::kMZ ||
         kind == ParamKind::kM;
}

}  // namespace

std::optional<Eigen::VectorXd> effort_check_parameters(std::ostream& err, const std::string& command,
                                                       const ModelSource& source) {
  const bool any_effort = std::any_of(source.limits.begin(), source.limits.end(),
                                      [](const JointLimits& limit) { return limit.effort.has_value(); });
  const RobotModel* description = source.any_description();
  if (!any_effort || description == nullptr) return std::nullopt;
  const auto note = [&](const std::string& why) {
    err << "modelid " << command << ": note: the description gives effort limits but " << why
        << "; joint torques are not checked against them\n";
    return std::nullopt;
  };
  if (description->param_names() != source.model->standard_param_names()) {
    return note("its parameters are not those of the model '" + source.model->name() + "'");
  }
  Eigen::VectorXd standard = Eigen::VectorXd::Zero(source.model->num_standard_params());
  for (std::size_t k = 0; k < description->tree.params.size(); ++k) {
    const StandardParam& param = description->tree.params[k];
    if (description->known_values[k]) {
      standard[static_cast<Eigen::Index>(k)] = *description->known_values[k];
    } else if (inertial(param.kind) && param.body != description->payload_body) {
      return note("no a-priori inertial values (" + param.name +
                  " is not given: URDF <inertial>, YAML known:)");
    }
  }
  Eigen::VectorXd beta(source.model->num_base_params());
  source.model->base_from_standard(standard.data(), beta.data());
  return beta;
}

}  // namespace modelgen::internal
