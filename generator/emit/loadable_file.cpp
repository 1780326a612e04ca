// The loadable entry point's file and the sources a shared library of the model needs.

#include "generator/emit/loadable_file.hpp"

#include "generator/emit/banner.hpp"
#include "generator/emit/printer.hpp"
#include "generator/functions/entry_points.hpp"
#include "modelgen/model/loadable_model.h"

namespace modelgen::gen {

const std::vector<std::string>& loadable_functions() {
  // The function members of modelgen_loadable_table, which templates/loadable.cpp.tmpl fills.
  static const std::vector<std::string> kFunctions = {"idim_regressor",
                                                      "power_regressor",
                                                      "inverse_dynamics",
                                                      "mass_matrix",
                                                      "mass_matrix_and_bias",
                                                      "inverse_dynamics_state_jacobian",
                                                      "base_from_standard",
                                                      "drive_regressor",
                                                      "drive_torque_given_regressor",
                                                      "drive_torque_jacobian_given_regressor"};
  return kFunctions;
}

std::string render_loadable_source(const RenderInput& in) {
  return Printer(embedded_template("loadable.cpp"))
      .set("banner", render_banner(in.loadable_name(), in))
      .set("header", in.header_name())
      .set("robot", in.model.name)
      .set("sha256", in.sha256)
      .set("abi_version", MODELGEN_LOADABLE_ABI_VERSION)
      .render();
}

std::vector<std::string> loadable_sources(const RenderInput& in) {
  std::vector<std::string> files = {in.source_name()};
  const FunctionSelection needed =
      select_functions(loadable_functions(), in.input.estimate.has_value());
  for (const EntryPoint& point : needed.generated) {
    files.push_back(in.function_source_name(point.name()));
  }
  files.push_back(in.loadable_name());
  return files;
}

}  // namespace modelgen::gen
