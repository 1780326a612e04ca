// Drive-model parameter files through nlohmann::json.

#include "runtime/cli/drive_parameter_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "runtime/cli/json_file.hpp"

namespace modelgen::internal {

std::map<std::string, double> read_drive_parameter_values(const std::string& path,
                                                          const std::vector<std::string>& names) {
  const nlohmann::json json = read_json_file(path);
  if (!json.is_object()) {
    throw std::runtime_error(path + ": error: expected an object {\"name\": value, ...}");
  }
  std::map<std::string, double> out;
  for (const auto& [name, value] : json.items()) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw std::runtime_error(path + ": error: '" + name +
                               "' is not a parameter of the drive model (XXj..Mj, JMj, Rvj, Rcj, "
                               "Rzj, load_m, load_cx, ...)");
    }
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      throw std::runtime_error(path + ": error: '" + name + "' must be a finite number");
    }
    out[name] = value.get<double>();
  }
  return out;
}

}  // namespace modelgen::internal
