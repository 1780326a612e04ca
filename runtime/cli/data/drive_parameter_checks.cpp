// What makes drive-model parameter values impossible for a robot.

#include "runtime/cli/data/drive_parameter_checks.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"

namespace modelgen::internal {

std::vector<std::string> drive_parameter_violations(const std::map<std::string, double>& values,
                                                    const RigidBodyTree& tree) {
  std::vector<std::string> out;
  // Links: only those whose ten inertial values are all given are judged.
  const auto indices = inertial_param_indices(tree);
  Eigen::VectorXd standard = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(tree.params.size()));
  std::vector<char> complete(indices.size(), 0);
  for (std::size_t b = 0; b < indices.size(); ++b) {
    complete[b] = std::all_of(indices[b].begin(), indices[b].end(), [&](int k) {
      return k >= 0 && values.count(tree.params[static_cast<std::size_t>(k)].name) > 0;
    });
    if (!complete[b]) continue;
    for (int k : indices[b]) standard[k] = values.at(tree.params[static_cast<std::size_t>(k)].name);
  }
  for (const PhysicalViolation& v : physical_violations(tree, standard)) {
    if (v.body < 0 || !complete[static_cast<std::size_t>(v.body)]) continue;
    out.push_back("link '" + tree.bodies[static_cast<std::size_t>(v.body)].name + "' " +
                  v.parameter + ": " + v.condition);
  }
  for (const auto& [name, value] : values) {
    if (name.size() < 3 || name.find_first_not_of("0123456789", 2) != std::string::npos) continue;
    const std::string stem = name.substr(0, 2);
    if ((stem == "JM" || stem == "Rv" || stem == "Rc") && value < 0) {
      out.push_back(name + " = " + shortest_text(value) + " is negative");
    } else if (stem == "Rz" && !(value > 0 && value <= 1)) {
      out.push_back(name + " = " + shortest_text(value) + " is no efficiency (0 < Rz <= 1)");
    }
  }
  std::array<double, kLoadParams> load{};
  int given = 0;
  for (int i = 0; i < kLoadParams; ++i) {
    const auto found = values.find(load_param_names()[static_cast<std::size_t>(i)]);
    if (found == values.end()) continue;
    load[static_cast<std::size_t>(i)] = found->second;
    ++given;
  }
  if (given == kLoadParams) {
    for (const std::string& w :
         physical_consistency_warnings(LoadParameters::from_vector(load.data()))) {
      out.push_back("load: " + w);
    }
  }
  return out;
}

}  // namespace modelgen::internal
