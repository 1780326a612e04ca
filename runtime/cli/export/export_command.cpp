// modelid export: the identified values of an estimate of fit --physical written back into the
// robot's description: a URDF's <inertial>s (urdf_export.cpp) or a YAML description's `known:`
// section (yaml_export.cpp). The written text is loaded again and must give the estimate's base
// parameters before it replaces anything.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "modelgen/estimation/link_summary.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/urdf_export.hpp"
#include "modelgen/model/yaml_export.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/export/identified_standard.hpp"

namespace modelgen::internal {

namespace {

bool is_urdf_path(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".urdf" || extension == ".xml";
}

bool is_yaml_path(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".yaml" || extension == ".yml";
}

// The written description, loaded as the user will load it, must give the estimate's base
// parameters (what has no place in a URDF, the drive parameters, taken from the estimate).
void check_round_trip(const std::string& output, const std::string& text, bool urdf,
                      const RobotModel& description, const IdentificationModel& model,
                      const Eigen::VectorXd& standard, const LoadOptions& options,
                      const std::string& params) {
  // Values within the limits can still make one beyond them (a centre of mass h / m of 2 km
  // from a light link): said against the estimate, as the output was never written.
  RobotModel again;
  try {
    again = load_robot_text(output, text, options);
  } catch (const InputError& e) {
    throw InputError({params},
                     "the description export would write from this estimate is "
                     "refused on loading it: " +
                         e.message() + "; nothing was written");
  }
  if (again.param_names() != description.param_names()) {
    throw std::logic_error("export: the written description has other standard parameters");
  }
  Eigen::VectorXd read_back = standard;
  for (std::size_t k = 0; k < again.tree.params.size(); ++k) {
    if (!urdf || inertial_slot(again.tree.params[k].kind) >= 0) {
      read_back[static_cast<Eigen::Index>(k)] = again.known_values[k].value_or(0.0);
    }
  }
  Eigen::VectorXd expected(model.num_base_params()), got(model.num_base_params());
  model.base_from_standard(standard.data(), expected.data());
  model.base_from_standard(read_back.data(), got.data());
  for (Eigen::Index b = 0; b < got.size(); ++b) {
    if (!(std::abs(got[b] - expected[b]) <= 1e-9 * (1 + std::abs(expected[b])))) {
      throw std::logic_error("export: the written description gives " +
                             model.base_param_names()[static_cast<std::size_t>(b)] + " = " +
                             shortest_text(got[b]) + ", the estimate " +
                             shortest_text(expected[b]));
    }
  }
}

// Refuses, unless --force, an estimate with a link outside the region of its geometry or far from
// its a-priori values (mass off by more than a factor 2, centre of mass over 10 cm away;
// modelgen/estimation/link_summary.hpp): such a
// description breaks simulators, payload estimates and planners that read it, and is more often
// a prior the data could not correct than the robot.
void check_links_near_a_priori(const RobotModel& description, const Eigen::VectorXd& standard,
                               const std::string& params) {
  std::string far;
  const auto indices = inertial_param_indices(description.tree);
  for (std::size_t b = 0; b < indices.size(); ++b) {
    const auto& index = indices[b];
    if (std::find(index.begin(), index.end(), -1) != index.end()) continue;
    double identified[10], known[10];
    bool all_known = true;
    for (int s = 0; s < 10; ++s) {
      identified[s] = standard[index[s]];
      const auto& value = description.known_values[static_cast<std::size_t>(index[s])];
      all_known = all_known && value.has_value();
      known[s] = value.value_or(0.0);
    }
    // Outside the region of its geometry (the ellipsoid around its URDF shapes, its YAML
    // `region`, or the guess from its segments): no body that shape can be.
    if (b < description.body_regions.size() && description.body_regions[b]) {
      const double extent = region_extent(identified, *description.body_regions[b]);
      if (extent > 1 + 1e-6) {
        far += "\n  link '" + description.tree.bodies[b].name +
               "': its mass reaches outside the region its geometry gives (extent " +
               shortest_text(extent) + ")";
      }
    }
    if (!all_known) continue;
    const auto reasons = far_from_a_priori(link_quantities(identified), link_quantities(known));
    if (reasons.empty()) continue;
    far += "\n  link '" + description.tree.bodies[b].name + "': ";
    for (std::size_t i = 0; i < reasons.size(); ++i) far += (i ? "; " : "") + reasons[i];
  }
  if (!far.empty()) {
    throw InputError({params}, "links far from their a-priori values or their geometry:" + far +
                                   "\nnothing was written; check the description's inertials and "
                                   "the excitation, or give --force to write them anyway");
  }
}

}  // namespace

int run_export(const CommandLine& args) {
  const std::string robot = args.one("--robot");
  const std::string params = args.one("--params");
  const std::string output = args.one("-o");
  const bool urdf = is_urdf_path(robot);
  if (!std::filesystem::is_regular_file(robot) || !(urdf || is_yaml_path(robot))) {
    throw UsageError{"export needs the description file (.urdf or .yaml) as --robot, not '" +
                     robot + "': it writes that file with the identified values"};
  }
  if (urdf ? !is_urdf_path(output) : !is_yaml_path(output)) {
    throw UsageError{std::string("-o '") + output + "': the identified description is a " +
                     (urdf ? "URDF; give it the extension .urdf"
                           : "YAML description; give it "
                             "the extension .yaml")};
  }
  const LoadOptions options = description_options(args);
  const ModelSource source = load_model_source(robot, options, DescriptionModel::kNumeric);
  const RobotModel& description = *source.description;
  const IdentifiedStandard identified =
      read_identified_standard(params, description, *source.model);
  if (!args.has("--force") && !identified.converged) {
    throw InputError({params},
                     "the consistent fit that wrote it stopped short of its optimum "
                     "(\"converged\": false): nothing was written; refit (at the "
                     "default prior weight), or give --force to write it anyway");
  }
  if (!args.has("--force")) check_links_near_a_priori(description, identified.values, params);

  const std::string estimate = std::filesystem::path(params).filename().string();
  const std::string method = identified.method.empty() ? "" : " (" + identified.method + ")";
  // Which values the data decided, a line per link (fit --physical's "links" and "drives").
  std::string decided;
  for (const std::string& line : identified.decided) decided += "\n" + line;
  if (!decided.empty()) decided = "\nWhat the data decided:" + decided;
  const std::string text = read_source_file(robot);
  std::string written;
  if (urdf) {
    const UrdfExport exported = identified_urdf(
        robot, text, description, identified.values, options,
        "the <inertial> of each moving link is identified, from " + estimate + method +
            "; the links fixed to a moving link keep their a-priori inertials, unless export "
            "warned that it moved them onto the moving link." +
            decided);
    for (const std::string& warning : exported.warnings) std::cerr << warning << "\n";
    written = exported.text;
  } else {
    written = identified_yaml(robot, text, description, identified.values,
                              "Identified by modelid export from " + estimate + method +
                                  ":\nevery standard parameter, physically consistent." + decided);
  }
  check_round_trip(output, written, urdf, description, *source.model, identified.values, options,
                   params);
  write_file(output, written);
  std::cerr << "modelid export: the identified " << (urdf ? "inertials" : "values") << " of "
            << description.name << " written to " << output
            << (urdf ? "" : " as its known: section") << "\n";
  return 0;
}

}  // namespace modelgen::internal
