// Resolves --robot: a path that exists is a description, otherwise a compiled-in model name.

#include "runtime/cli/model_source.hpp"

#include <filesystem>
#include <stdexcept>

#include "generator/description/load_robot.hpp"
#include "generator/output/sha256.hpp"
#include "runtime/cli/shipped_models.hpp"

namespace modelgen::internal {

ModelSource load_model_source(const std::string& robot) {
  ModelSource source;
  if (std::filesystem::exists(robot)) {
    source.description = gen::load_robot(robot);
    const gen::DriveChain& drives = source.description->drives;
    const int dof = source.description->dof();
    Transmission drive{drives.motor_from_joint,
                       Eigen::Map<const Eigen::VectorXd>(drives.torque_constant.data(), dof),
                       Eigen::Map<const Eigen::VectorXd>(drives.joint_offset.data(), dof)};
    source.model = std::make_unique<ReferenceModel>(
        source.description->name, source.description->tree,
        gen::sha256_hex(gen::read_source_file(robot)), std::move(drive));
    return source;
  }
  source.model = make_shipped_model(robot);
  if (source.model == nullptr) {
    std::string names;
    for (const std::string& name : shipped_model_names()) names += " " + name;
    throw std::invalid_argument("--robot '" + robot +
                                "' is neither a description file nor a compiled-in model (" +
                                "compiled in:" + names + ")");
  }
  return source;
}

}  // namespace modelgen::internal
