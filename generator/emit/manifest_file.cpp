// The manifest as a JSON document (nlohmann::ordered_json, members in a fixed order) laid out
// for review: one member per line at the top level, one element per line in arrays, each
// element on one line. Numbers read back as the exact double (shortest round trip, as in the
// generated code).

#include "generator/emit/manifest_file.hpp"

#include <nlohmann/json.hpp>

#include "generator/emit/loadable_file.hpp"
#include "generator/emit/number_format.hpp"
#include "generator/version.hpp"
#include "modelgen/model/generated_format.hpp"

namespace modelgen::gen {

namespace {

using Json = nlohmann::ordered_json;

// `value` on one line: {"name": "ZZ1R", "relation": {"ZZ1": 1.0, "ZZ2": 1.0}}.
std::string one_line(const Json& value) {
  if (value.is_object() || value.is_array()) {
    std::string text;
    for (auto item = value.begin(); item != value.end(); ++item) {
      if (!text.empty()) text += ", ";
      if (value.is_object()) text += one_line(Json(item.key())) + ": ";
      text += one_line(item.value());
    }
    return value.is_object() ? "{" + text + "}" : "[" + text + "]";
  }
  if (value.is_number_float()) return format_literal(value.get<double>(), Scalar::kDouble);
  return value.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string layout(const Json& document) {
  std::string text = "{\n";
  for (auto member = document.begin(); member != document.end(); ++member) {
    text += "  " + one_line(Json(member.key())) + ": ";
    if (member.value().is_array()) {
      text += "[\n";
      for (std::size_t i = 0; i < member.value().size(); ++i) {
        text += "    " + one_line(member.value()[i]) + (i + 1 < member.value().size() ? "," : "") +
                "\n";
      }
      text += "  ]";
    } else {
      text += one_line(member.value());
    }
    text += std::next(member) != document.end() ? ",\n" : "\n";
  }
  return text + "}\n";
}

Json base_parameters(const RenderInput& in) {
  Json list = Json::array();
  for (const BaseParameter& b : in.base.params) {
    Json relation = Json::object();
    for (const auto& [k, coefficient] : b.relation) {
      relation[in.model.tree.params[k].name] = coefficient;
    }
    list.push_back(Json{{"name", b.name}, {"relation", relation}});
  }
  return list;
}

// The generated files, header and manifest included, in the order modelgen writes them.
Json files(const RenderInput& in) {
  Json list = Json::array();
  list.push_back(in.header_name());
  list.push_back(in.source_name());
  for (const EmittedFunction& f : in.functions) list.push_back(in.function_source_name(f.name));
  if (in.input.loadable) list.push_back(in.loadable_name());
  list.push_back(in.manifest_name());
  return list;
}

Json functions(const RenderInput& in) {
  Json list = Json::array();
  for (const EmittedFunction& f : in.functions) {
    Json entry{{"name", f.name},
               {"mul", f.counts.mul},
               {"add", f.counts.add},
               {"sin_cos", f.counts.trig}};
    // Entries zero for every input, which the function leaves to the caller's zeroed array.
    if (!f.unwritten.empty()) {
      Json unwritten = Json::object();
      for (const UnwrittenEntries& entries : f.unwritten) unwritten[entries.array] = entries.indices;
      entry["unwritten"] = unwritten;
    }
    list.push_back(entry);
  }
  return list;
}

}  // namespace

std::string render_manifest(const RenderInput& in) {
  Json standard = Json::array();
  for (const StandardParam& p : in.model.tree.params) standard.push_back(p.name);
  Json document;
  document["generator"] = "modelgen";
  document["generator_version"] = kVersion;
  document["format_version"] = kGeneratedFormatVersion;
  document["robot"] = in.model.name;
  document["input"] = in.input.input_name;
  document["input_sha256"] = in.sha256;
  document["command"] = in.input.command_line;
  document["dof"] = in.model.dof();
  document["standard_parameters"] = standard;
  document["base_parameters"] = base_parameters(in);
  document["drive_parameters"] = in.drive_param_names;
  // Packed entry p of drive_regressor's Y is entry drive_regressor_index[p] of the dense one.
  document["drive_regressor_index"] = in.drive_regressor_index;
  document["functions"] = functions(in);
  document["files"] = files(in);
  // What a shared library of the model compiles (--loadable): the table's functions only.
  if (in.input.loadable) document["loadable_sources"] = loadable_sources(in);
  if (in.input.estimate) {
    const EstimateFile& estimate = *in.input.estimate;
    document["identified_from"] = Json{
        {"file", estimate.file_name}, {"sha256", estimate.sha256}, {"method", estimate.method}};
    Json values = Json::array();
    for (std::size_t b = 0; b < in.identified_base.size(); ++b) {
      values.push_back(Json{{"name", in.base.params[b].name}, {"value", in.identified_base[b]}});
    }
    document["identified_base"] = values;
  }
  return layout(document);
}

}  // namespace modelgen::gen
