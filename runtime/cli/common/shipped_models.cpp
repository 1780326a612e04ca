// Registry of the generated models in generated/ that modelid carries compiled in.

#include "runtime/cli/common/shipped_models.hpp"

#include <filesystem>
#include <functional>
#include <map>

#include "comau_smart_six.hpp"
#include "franka_panda.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"
#include "kr150.hpp"
#include "kuka_iiwa14_drake.hpp"
#include "kuka_kr150_2.hpp"
#include "panda_arm.hpp"
#include "tx40.hpp"
#include "ur5.hpp"

namespace modelgen::internal {

namespace {

// One compiled-in model: its identification model, its drive model and the SHA-256 of the
// description it was generated from.
struct Shipped {
  std::function<std::unique_ptr<IdentificationModel>()> model;
  std::function<std::unique_ptr<DriveModel>()> drive_model;
  std::string description_sha256;
  std::string description;  ///< relative to the source tree (MODELGEN_SHIPPED_ROBOTS)
};

template <class Generated>
Shipped shipped(std::string description) {
  return {[] { return std::make_unique<GeneratedModel<Generated>>(); },
          [] { return std::make_unique<GeneratedDriveModel<Generated>>(); },
          Generated::input_sha256(), std::move(description)};
}

const std::map<std::string, Shipped>& registry() {
  static const std::map<std::string, Shipped> kModels = {
      {"tx40", shipped<modelgen::tx40::Model>("robots/tx40.yaml")},
      {"kr150", shipped<modelgen::kr150::Model>("robots/kr150.yaml")},
      {"ur5", shipped<modelgen::ur5::Model>("robots/urdf/ur5.urdf")},
      {"iiwa14", shipped<modelgen::iiwa14::Model>("robots/urdf/kuka_iiwa14_drake.urdf")},
      {"panda", shipped<modelgen::panda::Model>("robots/urdf/franka_panda.urdf")},
      {"kuka_kr150_2", shipped<modelgen::kuka_kr150_2::Model>("robots/urdf/kuka_kr150_2.urdf")},
      {"panda_arm", shipped<modelgen::panda_arm::Model>("robots/panda_arm.yaml")},
      {"comau_smart_six",
       shipped<modelgen::comau_smart_six::Model>("robots/comau_smart_six.yaml")},
  };
  return kModels;
}

}  // namespace

std::unique_ptr<IdentificationModel> make_shipped_model(const std::string& name) {
  auto found = registry().find(name);
  return found == registry().end() ? nullptr : found->second.model();
}

std::unique_ptr<DriveModel> make_shipped_drive_model(const std::string& description_sha256,
                                                     std::string* name) {
  for (const auto& [model_name, entry] : registry()) {
    if (entry.description_sha256 != description_sha256) continue;
    if (name != nullptr) *name = model_name;
    return entry.drive_model();
  }
  return nullptr;
}

std::string shipped_description_path(const std::string& name) {
  auto found = registry().find(name);
  if (found == registry().end()) return "";
  const std::string path = std::string(MODELGEN_SOURCE_DIR) + "/" + found->second.description;
  std::error_code missing;
  if (!std::filesystem::is_regular_file(path, missing)) return "";
  try {
    if (sha256_hex(read_source_file(path)) != found->second.description_sha256) return "";
  } catch (const InputError&) {
    return "";
  }
  return path;
}

std::vector<std::string> shipped_model_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

}  // namespace modelgen::internal
