// JSON parameter files through nlohmann::json, every complaint at the line of its key.

#include "modelgen/io/parameter_file.hpp"

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"

namespace modelgen::io {

namespace {

int index_of(const std::vector<std::string>& names, const std::string& name,
             const SourceLocation& where, const char* kind) {
  if (name.empty()) {
    throw InputError(where, std::string("empty parameter name; expected a ") + kind +
                                " parameter of this model such as '" + names.front() + "'");
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) return static_cast<int>(k);
  }
  throw InputError(where, "'" + name + "' is not a " + kind + " parameter of this model" +
                              modelgen::did_you_mean(name, names));
}

double number(const nlohmann::json& value, const SourceLocation& where, const std::string& name) {
  if (!value.is_number()) {
    throw InputError(where, "the value of '" + name + "' is not a number");
  }
  return value.get<double>();
}

// fit -o writes every base parameter into "parameters": one missing was deleted by hand or
// lost, and taking it as 0, as the hand-written "base" and "standard" forms do, would predict,
// simulate or export another robot than the one identified.
void check_every_base_parameter(const JsonDocument& document, const IdentificationModel& model,
                                const std::map<std::string, int>& given) {
  const std::vector<std::string>& names = model.base_param_names();
  std::string missing;
  std::size_t count = 0;
  for (const std::string& name : names) {
    if (given.count(name) != 0) continue;
    missing += (missing.empty() ? "'" : ", '") + name + "'";
    ++count;
  }
  if (count == 0) return;
  throw InputError(document.at("/parameters"),
                   "\"parameters\" has no value for the base parameter" +
                       std::string(count > 1 ? "s " : " ") + missing + " of " + model.name() +
                       " (" + std::to_string(names.size() - count) + " of " +
                       std::to_string(names.size()) +
                       " given); an estimate of fit holds every base parameter, and a missing "
                       "one is not 0");
}

}  // namespace

Eigen::VectorXd read_base_parameters(const std::string& path, const IdentificationModel& model) {
  return read_base_parameters(read_json_document(path), model);
}

Eigen::VectorXd read_base_parameters(const JsonDocument& document,
                                     const IdentificationModel& model) {
  const nlohmann::json& json = document.value;
  if (!json.is_object()) {
    throw InputError(document.at(""), "expected an object with a \"standard\", \"base\" or "
                                      "\"parameters\" entry");
  }
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(model.num_base_params());
  for (const char* key : {"standard", "base"}) {
    if (json.contains(key) && !json[key].is_object()) {
      throw InputError(document.at(json_pointer("", key)),
                       "\"" + std::string(key) + "\" must be an object of name: value");
    }
  }
  // One source of values: with two, one of them would be ignored without a word. An estimate
  // of fit --physical has both its base parameters and the consistent standard set that gives
  // them: the base parameters are read, and must agree with the standard set.
  const bool physical_estimate =
      json.contains("physical") && json.contains("parameters") && json.contains("standard");
  std::vector<std::string> given;
  for (const char* key : {"standard", "base", "parameters"}) {
    if (json.contains(key) && !(physical_estimate && std::string(key) == "standard")) {
      given.push_back(key);
    }
  }
  if (given.size() > 1) {
    const SourceLocation first = document.at(json_pointer("", given[0]));
    throw InputError(document.at(json_pointer("", given[1])),
                     "both \"" + given[0] + "\" (line " + std::to_string(first.line) +
                         ") and \"" + given[1] + "\" are given; a parameter file holds one of "
                         "\"standard\", \"base\" or \"parameters\"");
  }
  const auto from_standard = [&] {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(model.num_standard_params());
    for (const auto& [name, value] : json["standard"].items()) {
      const SourceLocation where = document.at(json_pointer("/standard", name));
      p[index_of(model.standard_param_names(), name, where, "standard")] =
          number(value, where, name);
    }
    Eigen::VectorXd out(model.num_base_params());
    model.base_from_standard(p.data(), out.data());
    return out;
  };
  if (json.contains("standard") && !physical_estimate) {
    beta = from_standard();
  } else if (json.contains("base")) {
    for (const auto& [name, value] : json["base"].items()) {
      const SourceLocation where = document.at(json_pointer("/base", name));
      beta[index_of(model.base_param_names(), name, where, "base")] = number(value, where, name);
    }
  } else if (json.contains("parameters") && json["parameters"].is_array()) {
    std::map<std::string, int> line_of;  // parameter name -> line of its first entry
    const nlohmann::json& entries = json["parameters"];
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const nlohmann::json& entry = entries[k];
      const std::string entry_pointer = json_pointer("/parameters", std::to_string(k));
      if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string() ||
          !entry.contains("value")) {
        throw InputError(document.at(entry_pointer),
                         "every entry of \"parameters\" needs a \"name\" and a \"value\"");
      }
      const std::string name = entry["name"].get<std::string>();
      const SourceLocation where = document.at(json_pointer(entry_pointer, "name"));
      const int index = index_of(model.base_param_names(), name, where, "base");
      if (const auto [earlier, inserted] = line_of.emplace(name, where.line); !inserted) {
        throw InputError(where, "parameter '" + name + "' is given twice (first at line " +
                                    std::to_string(earlier->second) + "); give each once");
      }
      beta[index] = number(entry["value"], document.at(json_pointer(entry_pointer, "value")), name);
    }
    check_every_base_parameter(document, model, line_of);
  } else {
    throw InputError(document.at(""), "expected a \"standard\", \"base\" or \"parameters\" entry");
  }
  if (physical_estimate) {
    const Eigen::VectorXd regrouped = from_standard();
    for (Eigen::Index b = 0; b < beta.size(); ++b) {
      if (!(std::abs(regrouped[b] - beta[b]) <= 1e-6 * (1 + std::abs(beta[b])))) {
        throw InputError(document.at(json_pointer("", "standard")),
                         "the \"standard\" set gives " +
                             model.base_param_names()[static_cast<std::size_t>(b)] + " = " +
                             shortest_text(regrouped[b]) + " but \"parameters\" has " +
                             shortest_text(beta[b]) + "; the file was edited by hand?");
      }
    }
  }
  return beta;
}

PhysicalProblems physical_problems(const std::string& path, const IdentificationModel& model,
                                   const RobotModel& description) {
  return physical_problems(read_json_document(path), model, description);
}

PhysicalProblems physical_problems(const JsonDocument& document, const IdentificationModel& model,
                                   const RobotModel& description) {
  PhysicalProblems out;
  if (description.param_names() != model.standard_param_names()) return out;
  const RigidBodyTree& tree = description.tree;
  const nlohmann::json& json = document.value;
  if (json.contains("standard")) {
    out.key = "standard";
    Eigen::VectorXd p = Eigen::VectorXd::Zero(model.num_standard_params());
    for (const auto& [name, value] : json["standard"].items()) {
      const SourceLocation where = document.at(json_pointer("/standard", name));
      p[index_of(model.standard_param_names(), name, where, "standard")] =
          number(value, where, name);
    }
    for (const PhysicalViolation& v : physical_violations(tree, p)) {
      const std::string link =
          v.body >= 0 ? "link '" + tree.bodies[static_cast<std::size_t>(v.body)].name + "' " : "";
      out.problems.push_back(link + v.parameter + ": " + v.condition);
    }
  } else {
    out.key = json.contains("base") ? "base" : "parameters";
    const Eigen::VectorXd beta = read_base_parameters(document, model);
    const std::vector<std::string>& names = model.base_param_names();
    for (std::size_t b = 0; b < names.size(); ++b) {
      for (const StandardParam& param : tree.params) {
        if (param.name != names[b] || !must_be_nonnegative(param.kind)) continue;
        const double value = beta[static_cast<Eigen::Index>(b)];
        if (value < 0) {
          out.problems.push_back(names[b] + " = " + shortest_text(value) + " is negative");
        }
      }
    }
  }
  out.where = document.at(json_pointer("", out.key));
  return out;
}

std::string PhysicalProblems::text() const {
  std::string list;
  for (const std::string& problem : problems) list += (list.empty() ? "" : "; ") + problem;
  return "these parameters cannot be those of a physical robot: " + list;
}

void check_physically_possible(const std::string& path, const IdentificationModel& model,
                               const RobotModel& description) {
  check_physically_possible(read_json_document(path), model, description);
}

void check_physically_possible(const JsonDocument& document, const IdentificationModel& model,
                               const RobotModel& description) {
  const PhysicalProblems found = physical_problems(document, model, description);
  if (found.problems.empty()) return;
  throw InputError(found.where, found.text() + " (fit --physical gives estimates that can)");
}

}  // namespace modelgen::io
