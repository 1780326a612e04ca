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

template <class Generated>
std::unique_ptr<IdentificationModel> make() {
  return std::make_unique<GeneratedModel<Generated>>();
}

const std::map<std::string, std::function<std::unique_ptr<IdentificationModel>()>>& registry() {
  static const std::map<std::string, std::function<std::unique_ptr<IdentificationModel>()>>
      kModels = {
          {"tx40", make<modelgen::tx40::Model>},
          {"kr150", make<modelgen::kr150::Model>},
          {"ur5", make<modelgen::ur5::Model>},
          {"iiwa14", make<modelgen::iiwa14::Model>},
          {"panda", make<modelgen::panda::Model>},
          {"kuka_kr150_2", make<modelgen::kuka_kr150_2::Model>},
          {"panda_arm", make<modelgen::panda_arm::Model>},
      };
  return kModels;
}

}  // namespace

std::unique_ptr<IdentificationModel> make_shipped_model(const std::string& name) {
  auto found = registry().find(name);
  return found == registry().end() ? nullptr : found->second();
}

std::vector<std::string> shipped_model_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

}  // namespace modelgen::internal
