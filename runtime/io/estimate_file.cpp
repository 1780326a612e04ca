// EST.json through nlohmann::json: writing the estimate of fit, checking the model of an
// estimate before predict uses it.

#include "modelgen/io/estimate_file.hpp"

#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/error.hpp"

namespace modelgen::io {

namespace {

// JSON has no infinity or NaN: a relative standard deviation of a zero estimate is null.
nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

nlohmann::json parameters_json(const std::vector<EstimatedParameter>& parameters) {
  nlohmann::json list = nlohmann::json::array();
  for (const EstimatedParameter& p : parameters) {
    nlohmann::json entry = {{"name", p.name},
                            {"value", number(p.value)},
                            {"std", number(p.std_dev)},
                            {"rel_std", number(p.rel_std_dev)}};
    if (p.truth) entry["truth"] = number(*p.truth);
    list.push_back(std::move(entry));
  }
  return list;
}

nlohmann::json numbers(const std::vector<double>& values) {
  nlohmann::json list = nlohmann::json::array();
  for (double value : values) list.push_back(number(value));
  return list;
}

}  // namespace

std::string estimate_json(const EstimateFile& estimate) {
  nlohmann::json out;
  out["model"] = estimate.model;
  out["description_sha256"] = estimate.description_sha256;
  out["method"] = estimate.method;
  out["samples"] = estimate.samples;
  out["data"] = estimate.data;
  out["data_options"] = estimate.data_options;
  out["rel_error_norm"] = number(estimate.rel_error_norm);
  out["condition_number"] = number(estimate.condition_number);
  out["residual_std"] = number(estimate.residual_std);
  out["rms_per_axis"] = numbers(estimate.rms_per_axis);
  out["rms_torque_per_axis"] = numbers(estimate.rms_torque_per_axis);
  out["parameters"] = parameters_json(estimate.parameters);
  if (estimate.essential) {
    const EssentialEstimate& e = *estimate.essential;
    out["essential"] = {{"r_sigma", e.r_sigma},
                        {"kept", e.kept},
                        {"eliminated", e.eliminated},
                        {"parameters", parameters_json(e.parameters)},
                        {"rel_error_norm", number(e.rel_error_norm)},
                        {"condition_number", number(e.condition_number)}};
  }
  if (estimate.physical) {
    const PhysicalBlock& p = *estimate.physical;
    nlohmann::json standard = nlohmann::json::object();
    for (const auto& [name, value] : p.standard) standard[name] = number(value);
    out["standard"] = std::move(standard);
    nlohmann::json links = nlohmann::json::array();
    for (const LinkInertial& link : p.links) {
      nlohmann::json entry = {
          {"body", link.body},
          {"mass", number(link.mass)},
          {"com", numbers({link.com.begin(), link.com.end()})},
          {"inertia_com", numbers({link.inertia_com.begin(), link.inertia_com.end()})},
          {"principal_moments",
           numbers({link.principal_moments.begin(), link.principal_moments.end()})},
          {"decided_by",
           {{"mass", link.mass_decided_by},
            {"com", link.com_decided_by},
            {"principal_moments", link.moments_decided_by}}}};
      if (link.a_priori) {
        const auto& a = *link.a_priori;
        entry["a_priori"] = {{"mass", number(a.mass)},
                             {"com", numbers({a.com.begin(), a.com.end()})},
                             {"principal_moments",
                              numbers({a.principal_moments.begin(), a.principal_moments.end()})}};
      }
      entry["far_from_a_priori"] = link.far_from_a_priori;
      if (link.a_priori) entry["a_priori_rejected_in"] = link.a_priori_rejected_in;
      if (link.region_extent) entry["region_extent"] = number(*link.region_extent);
      links.push_back(std::move(entry));
    }
    out["links"] = std::move(links);
    nlohmann::json drives = nlohmann::json::array();
    for (const DriveParameter& drive : p.drives) {
      nlohmann::json entry = {{"name", drive.name},
                              {"value", number(drive.value)},
                              {"decided_by", drive.decided_by},
                              {"regrouped_with", drive.regrouped_with}};
      if (drive.a_priori) entry["a_priori"] = number(*drive.a_priori);
      drives.push_back(std::move(entry));
    }
    out["drives"] = std::move(drives);
    out["physical"] = {{"prior_weight", number(p.prior_weight)},
                       {"prior_weight_rule", p.prior_weight_rule},
                       {"cost_increase", number(p.cost_increase)},
                       {"converged", p.converged},
                       {"binding_constraints", p.binding_constraints},
                       {"prior_notes", p.prior_notes},
                       {"unconstrained_rel_error_norm", number(p.unconstrained_rel_error_norm)},
                       {"unconstrained", parameters_json(p.unconstrained)}};
  }
  return out.dump(2) + "\n";
}

void check_estimate_model(const std::string& path, const IdentificationModel& model,
                          const std::string& what) {
  check_estimate_model(read_json_document(path), model, what);
}

void check_estimate_model(const JsonDocument& document, const IdentificationModel& model,
                          const std::string& what) {
  const std::string& path = document.path;
  const nlohmann::json& json = document.value;
  if (!json.is_object() || !json.contains("description_sha256")) return;
  const nlohmann::json& field = json["description_sha256"];
  if (!field.is_string()) {
    throw InputError(document.at("/description_sha256"), "\"description_sha256\" must be a string");
  }
  const std::string sha = field.get<std::string>();
  if (sha.empty() || sha == model.description_sha256()) return;
  std::string made_for = "another model";
  if (json.contains("model") && json["model"].is_string()) {
    made_for = "'" + json["model"].get<std::string>() + "'";
  }
  throw InputError({path}, "the " + what + " belongs to another model: it was " +
                               "identified on " + made_for + " (description_sha256 '" + sha +
                               "'), --robot is '" + model.name() + "' (description_sha256 '" +
                               model.description_sha256() + "'); the hashes differ");
}

std::optional<std::vector<std::string>> read_data_options(const std::string& path) {
  return read_data_options(read_json_document(path));
}

std::optional<std::vector<std::string>> read_data_options(const JsonDocument& document) {
  const std::string& path = document.path;
  const nlohmann::json& json = document.value;
  if (!json.is_object() || !json.contains("data_options")) return std::nullopt;
  const nlohmann::json& field = json["data_options"];
  std::vector<std::string> words;
  if (field.is_array()) {
    for (const nlohmann::json& word : field) {
      if (!word.is_string()) break;
      words.push_back(word.get<std::string>());
    }
  }
  if (!field.is_array() || words.size() != field.size()) {
    throw std::runtime_error(path + ": error: \"data_options\" must be a list of strings (the " +
                             "command-line words of the fit's data options)");
  }
  return words;
}

}  // namespace modelgen::io
