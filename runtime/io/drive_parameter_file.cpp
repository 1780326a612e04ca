// Drive-model parameter files through the position-reporting JSON reader.

#include "modelgen/io/drive_parameter_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"

namespace modelgen::io {

std::map<std::string, double> read_drive_parameter_values(const std::string& path,
                                                          const std::vector<std::string>& names) {
  const JsonDocument document = read_json_document(path);
  const nlohmann::json& json = document.value;
  if (!json.is_object()) {
    throw InputError(document.at(""), "expected an object {\"name\": value, ...}");
  }
  std::map<std::string, double> out;
  for (const auto& [name, value] : json.items()) {
    const SourceLocation where = document.at(json_pointer("", name));
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw InputError(where, "'" + name +
                                  "' is not a parameter of the drive model (XXj..Mj, JMj, Rvj, "
                                  "Rcj, Rzj, load_m, load_cx, ...)" +
                                  did_you_mean(name, names));
    }
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      throw InputError(where, "'" + name + "' must be a finite number");
    }
    out[name] = value.get<double>();
  }
  return out;
}

}  // namespace modelgen::io
