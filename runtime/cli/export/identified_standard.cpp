// EST.json's "standard" block for modelid export, through the same JSON reader (positions for
// every key) as the other parameter files.

#include "runtime/cli/export/identified_standard.hpp"

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/json_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// The description export writes is loaded again, and the loaders refuse values beyond the
// description limits (README, Limits): said here, against the estimate, rather than against a
// description that was never written.
void check_within_limits(const SourceLocation& where, const std::string& name, double value,
                         ParamKind kind) {
  const bool mass = kind == ParamKind::kM;
  const double limit = mass ? kMaxMass : kMaxMagnitude;
  if (std::abs(value) <= limit) return;
  const std::string unit = mass ? " kg" : "";
  throw InputError(where, "'" + name + "' is " + shortest_text(value) + unit +
                              ", beyond the limit of " + shortest_text(limit) + unit +
                              " a description may hold (README, Limits); export writes only "
                              "what loads again");
}

// The lines of IdentifiedStandard::decided from EST.json's "links" and "drives" (fit
// --physical); entries of another form are left out, as the file's values were checked above.
std::vector<std::string> decided_lines(const nlohmann::json& json) {
  std::vector<std::string> out;
  const auto text = [](const nlohmann::json& v) {
    return v.is_string() ? v.get<std::string>() : "";
  };
  if (json.contains("links") && json["links"].is_array()) {
    for (const nlohmann::json& link : json["links"]) {
      if (!link.is_object() || !link.contains("decided_by") || !link["decided_by"].is_object())
        continue;
      std::string data, prior, bound;
      for (const auto& [key, words] :
           {std::pair{"mass", "mass"}, std::pair{"com", "centre of mass"},
            std::pair{"principal_moments", "principal moments"}}) {
        const std::string by = text(link["decided_by"].value(key, nlohmann::json()));
        std::string& list = by == "data" ? data : by == "bound" ? bound : prior;
        list += (list.empty() ? "" : ", ") + std::string(words);
      }
      out.push_back(
          "link '" + text(link.value("body", nlohmann::json())) + "': " +
          (data.empty() ? "the data decided nothing of it alone" : "the data decided its " + data) +
          (prior.empty() ? "" : "; the prior (a-priori model) its " + prior) +
          (bound.empty() ? "" : "; the bound (its region from the geometry) its " + bound));
    }
  }
  if (json.contains("drives") && json["drives"].is_array()) {
    std::string prior;
    for (const nlohmann::json& drive : json["drives"]) {
      if (drive.is_object() && text(drive.value("decided_by", nlohmann::json())) == "prior")
        prior += (prior.empty() ? "" : ", ") + text(drive.value("name", nlohmann::json()));
    }
    if (!prior.empty())
      out.push_back("drive parameters the data did not decide (regrouped): " + prior);
  }
  return out;
}

}  // namespace

IdentifiedStandard read_identified_standard(const std::string& path, const RobotModel& description,
                                            const IdentificationModel& model) {
  const JsonDocument document = read_json_document(path);  // read once, for every check below
  check_estimate_model(document, model);
  const nlohmann::json& json = document.value;
  if (!json.is_object() || !json.contains("standard")) {
    throw InputError(document.at(""),
                     "the estimate has no \"standard\" block: base parameters alone do not "
                     "determine each link's inertial; refit with 'modelid fit --physical -o "
                     "EST.json', which writes a physically consistent standard set");
  }
  const nlohmann::json& block = json["standard"];
  const std::string block_pointer = json_pointer("", "standard");
  if (!block.is_object()) {
    throw InputError(document.at(block_pointer), "\"standard\" must be an object of name: value");
  }

  const std::vector<std::string>& names = model.standard_param_names();
  IdentifiedStandard out;
  out.values = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(names.size()));
  std::vector<bool> given(names.size(), false);
  for (const auto& [name, value] : block.items()) {
    const SourceLocation where = document.at(json_pointer(block_pointer, name));
    std::size_t k = 0;
    while (k < names.size() && names[k] != name) ++k;
    if (k == names.size()) {
      throw InputError(where, "'" + name + "' is not a standard parameter of '" + model.name() +
                                  "'" + did_you_mean(name, names));
    }
    if (!value.is_number()) throw InputError(where, "the value of '" + name + "' is not a number");
    out.values[static_cast<Eigen::Index>(k)] = value.get<double>();
    check_within_limits(where, name, value.get<double>(), description.tree.params[k].kind);
    given[k] = true;
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (!given[k]) {
      throw InputError(document.at(block_pointer),
                       "\"standard\" has no value for '" + names[k] +
                           "'; an estimate of fit --physical gives every standard parameter of "
                           "the robot");
    }
  }
  // The base estimate and the standard set must agree (a hand-edited file would make export
  // write something else than was identified); read_base_parameters checks it.
  if (json.contains("parameters")) read_base_parameters(document, model);
  if (json.contains("method") && json["method"].is_string()) out.method = json["method"];
  out.decided = decided_lines(json);
  if (json.contains("physical") && json["physical"].is_object()) {
    const nlohmann::json converged = json["physical"].value("converged", nlohmann::json(true));
    out.converged = !converged.is_boolean() || converged.get<bool>();
  }

  // What export writes must load again: the loaders refuse impossible inertials.
  for (const PhysicalViolation& violation : physical_violations(description.tree, out.values)) {
    const std::string& link =
        description.tree.bodies[static_cast<std::size_t>(violation.body)].name;
    throw InputError(document.at(json_pointer(block_pointer, violation.parameter)),
                     "link '" + link + "': " + violation.condition +
                         "; export writes physically consistent values only (fit --physical "
                         "gives them)");
  }
  return out;
}

}  // namespace modelgen::internal
