// JSON parameter files through nlohmann::json.

#include "runtime/cli/parameter_file.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "modelgen/model/error.hpp"
#include "runtime/cli/json_file.hpp"

namespace modelgen::internal {

namespace {

int index_of(const std::vector<std::string>& names, const std::string& name,
             const std::string& path, const char* kind) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) return static_cast<int>(k);
  }
  throw std::runtime_error(path + ": error: '" + name + "' is not a " + kind + " parameter of " +
                           "this model" + modelgen::did_you_mean(name, names));
}

double number(const nlohmann::json& value, const std::string& path, const std::string& name) {
  if (!value.is_number()) {
    throw std::runtime_error(path + ": error: the value of '" + name + "' is not a number");
  }
  return value.get<double>();
}

}  // namespace

Eigen::VectorXd read_base_parameters(const std::string& path, const IdentificationModel& model) {
  const nlohmann::json json = read_json_file(path);
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(model.num_base_params());
  for (const char* key : {"standard", "base"}) {
    if (json.contains(key) && !json[key].is_object()) {
      throw std::runtime_error(path + ": error: \"" + key + "\" must be an object of name: value");
    }
  }
  if (json.contains("standard")) {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(model.num_standard_params());
    for (const auto& [name, value] : json["standard"].items()) {
      p[index_of(model.standard_param_names(), name, path, "standard")] = number(value, path, name);
    }
    model.base_from_standard(p.data(), beta.data());
  } else if (json.contains("base")) {
    for (const auto& [name, value] : json["base"].items()) {
      beta[index_of(model.base_param_names(), name, path, "base")] = number(value, path, name);
    }
  } else if (json.contains("parameters") && json["parameters"].is_array()) {
    for (const auto& entry : json["parameters"]) {
      if (!entry.contains("name") || !entry["name"].is_string() || !entry.contains("value")) {
        throw std::runtime_error(path + ": error: every entry of \"parameters\" needs a \"name\" " +
                                 "and a \"value\"");
      }
      const std::string name = entry["name"].get<std::string>();
      beta[index_of(model.base_param_names(), name, path, "base")] =
          number(entry["value"], path, name);
    }
  } else {
    throw std::runtime_error(path + ": error: expected a \"standard\", \"base\" or " +
                             "\"parameters\" entry");
  }
  return beta;
}

}  // namespace modelgen::internal
