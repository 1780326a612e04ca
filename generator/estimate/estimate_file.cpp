// EST.json for modelgen --params: the checks that keep a wrong or broken estimate from
// silently becoming firmware constants.

#include "generator/estimate/estimate_file.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include <nlohmann/json.hpp>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/sha256.hpp"

namespace modelgen::gen {

using io::read_json_document;

namespace {

using io::json_pointer;
using io::JsonDocument;

// The base parameters are linear combinations of standard ones whose coefficients come from the
// geometry (Gautier & Briot, regrouping): another description's estimate carries the same names
// with other meanings, so a differing hash is an error, as for modelid predict.
void check_description(const JsonDocument& document, const std::string& description_path,
                       const std::string& description_sha256, EstimateFile& estimate) {
  const nlohmann::json& json = document.value;
  const std::string description = std::filesystem::path(description_path).filename().string();
  if (!json.contains("description_sha256") ||
      (json["description_sha256"].is_string() && json["description_sha256"].empty())) {
    estimate.warnings.push_back(
        SourceLocation{estimate.path}.to_string() +
        ": warning: no \"description_sha256\", so nothing shows that the estimate was made on " +
        description + "; its values are taken by base parameter name");
    return;
  }
  const SourceLocation where = document.at("/description_sha256");
  if (!json["description_sha256"].is_string()) {
    throw InputError(where,
                     "\"description_sha256\" must be a string (the SHA-256 of the "
                     "description the estimate was made on)");
  }
  const std::string sha = json["description_sha256"].get<std::string>();
  if (sha == description_sha256) return;
  std::string model = "another robot";
  if (json.contains("model") && json["model"].is_string()) {
    model = "'" + json["model"].get<std::string>() + "'";
  }
  throw InputError(where, "the estimate was identified on another description: " + model +
                              " (description_sha256 '" + sha + "'), but " + description_path +
                              " has SHA-256 '" + description_sha256 +
                              "'; its values would be another robot's constants: fit again on "
                              "this description, or generate from the one the estimate was "
                              "made on");
}

// The file name and the method go into comments of the generated code: a line break there
// would end the comment and inject code.
bool printable(const std::string& text) {
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  }
  return true;
}

EstimateEntry read_entry(const JsonDocument& document, std::size_t k) {
  const std::string pointer = json_pointer("/parameters", std::to_string(k));
  const nlohmann::json& entry = document.value["parameters"][k];
  if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string() ||
      !entry.contains("value")) {
    throw InputError(document.at(pointer),
                     "every entry of \"parameters\" needs a \"name\" and a \"value\"");
  }
  EstimateEntry out;
  out.name = entry["name"].get<std::string>();
  out.name_at = document.at(json_pointer(pointer, "name"));
  out.value_at = document.at(json_pointer(pointer, "value"));
  const nlohmann::json& value = entry["value"];
  if (value.is_null()) {
    throw InputError(out.value_at, "the value of '" + out.name +
                                       "' is null: modelid writes an estimate that is not finite "
                                       "as null, and a constant must be a finite number");
  }
  if (!value.is_number()) {
    throw InputError(out.value_at, "the value of '" + out.name + "' is not a number");
  }
  out.value = value.get<double>();
  if (!std::isfinite(out.value)) {
    throw InputError(out.value_at, "the value of '" + out.name + "' is not finite");
  }
  return out;
}

}  // namespace

EstimateFile read_estimate_file(const std::string& path, const std::string& description_path,
                                const std::string& description_sha256) {
  const JsonDocument document = read_json_document(path);
  EstimateFile estimate;
  estimate.path = path;
  estimate.file_name = std::filesystem::path(path).filename().string();
  // The bytes read a second time, for the hash: the reader keeps no copy of its text.
  estimate.sha256 = sha256_hex(read_source_file(path));
  const nlohmann::json& json = document.value;
  if (!json.is_object()) {
    throw InputError(document.at(""), "expected an object, as modelid fit -o writes");
  }
  check_description(document, description_path, description_sha256, estimate);
  if (!printable(estimate.file_name)) {
    throw InputError({path},
                     "the file name holds a control character; it would be copied into "
                     "comments of the generated code");
  }
  if (json.contains("method") && json["method"].is_string()) {
    estimate.method = json["method"].get<std::string>();
    if (!printable(estimate.method)) {
      throw InputError(document.at("/method"),
                       "\"method\" holds a control character; it would "
                       "be copied into comments of the generated code");
    }
  }
  if (!json.contains("parameters") || !json["parameters"].is_array()) {
    throw InputError(json.contains("parameters") ? document.at("/parameters") : document.at(""),
                     "no \"parameters\" list of base parameters, as modelid fit -o writes for "
                     "--method ols, wls and pim-wls (an ML estimate holds drive parameters)");
  }
  estimate.parameters_at = document.at("/parameters");
  std::map<std::string, int> line_of;  // name -> line of its entry
  for (std::size_t k = 0; k < json["parameters"].size(); ++k) {
    EstimateEntry entry = read_entry(document, k);
    if (const auto [first, inserted] = line_of.emplace(entry.name, entry.name_at.line); !inserted) {
      throw InputError(entry.name_at, "parameter '" + entry.name +
                                          "' is given twice (first at line " +
                                          std::to_string(first->second) + "); give each once");
    }
    estimate.entries.push_back(std::move(entry));
  }
  return estimate;
}

std::vector<double> base_values(const EstimateFile& estimate,
                                const std::vector<std::string>& base_names,
                                const std::string& robot) {
  std::map<std::string, std::size_t> index;
  for (std::size_t b = 0; b < base_names.size(); ++b) index.emplace(base_names[b], b);
  std::vector<double> values(base_names.size(), 0.0);
  std::vector<bool> given(base_names.size(), false);
  for (const EstimateEntry& entry : estimate.entries) {
    const auto found = index.find(entry.name);
    if (found == index.end()) {
      throw InputError(entry.name_at, "'" + entry.name + "' is not a base parameter of " + robot +
                                          did_you_mean(entry.name, base_names));
    }
    values[found->second] = entry.value;
    given[found->second] = true;
  }
  std::string missing;
  std::size_t count = 0;
  for (std::size_t b = 0; b < base_names.size(); ++b) {
    if (given[b]) continue;
    missing += (missing.empty() ? "'" : ", '") + base_names[b] + "'";
    ++count;
  }
  if (count > 0) {
    throw InputError(
        estimate.parameters_at,
        "\"parameters\" has no value for the base parameter" + std::string(count > 1 ? "s " : " ") +
            missing + " of " + robot + " (" + std::to_string(base_names.size() - count) + " of " +
            std::to_string(base_names.size()) + " given); the constants need every base parameter");
  }
  return values;
}

void check_fits_float(const EstimateFile& estimate) {
  constexpr float kLargest = std::numeric_limits<float>::max();
  for (const EstimateEntry& entry : estimate.entries) {
    if (std::abs(entry.value) <= kLargest) continue;
    throw InputError(entry.value_at,
                     "the value of '" + entry.name + "' (" + shortest_text(entry.value) +
                         ") is beyond the range of a float (" + shortest_text(kLargest) +
                         "), and float entry points are generated; use "
                         "--scalar double");
  }
}

}  // namespace modelgen::gen
