// Registry of the generated models in generated/ that modelid carries compiled in.

#include "runtime/cli/shipped_models.hpp"

#include <functional>
#include <map>

#include "franka_panda.hpp"
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
};

template <class Generated>
Shipped shipped() {
  return {[] { return std::make_unique<GeneratedModel<Generated>>(); },
          [] { return std::make_unique<GeneratedDriveModel<Generated>>(); },
          Generated::input_sha256()};
}

const std::map<std::string, Shipped>& registry() {
  static const std::map<std::string, Shipped> kModels = {
      {"tx40", shipped<modelgen::tx40::Model>()},
      {"kr150", shipped<modelgen::kr150::Model>()},
      {"ur5", shipped<modelgen::ur5::Model>()},
      {"iiwa14", shipped<modelgen::iiwa14::Model>()},
      {"panda", shipped<modelgen::panda::Model>()},
      {"kuka_kr150_2", shipped<modelgen::kuka_kr150_2::Model>()},
      {"panda_arm", shipped<modelgen::panda_arm::Model>()},
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

std::vector<std::string> shipped_model_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

}  // namespace modelgen::internal
