// Reads the 'known' map of an MDH YAML description and checks that the values could belong to
// real bodies: signs of masses, inertias and friction coefficients, each fully known body's
// pseudo-inertia and each fully known inertia tensor.

#include "runtime/model/mdh_known_values.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "runtime/model/magnitude_checks.hpp"

namespace modelgen {

namespace {

// No negative mass, moment of inertia, drive inertia or friction coefficient.
void check_known_signs(const YamlReader& in, const RobotModel& model,
                       const std::map<int, YAML::Node>& keys) {
  const std::vector<StandardParam>& params = model.tree.params;
  for (const auto& [k, node] : keys) {
    const ParamKind kind = params[k].kind;
    const bool inertial = kind == ParamKind::kM || kind == ParamKind::kXX ||
                          kind == ParamKind::kYY || kind == ParamKind::kZZ;
    if ((inertial || must_be_nonnegative(kind)) && *model.known_values[k] < 0) {
      const char* what = kind == ParamKind::kM ? "a mass"
                         : inertial || kind == ParamKind::kIa || kind == ParamKind::kIam
                             ? "an inertia"
                             : "a friction coefficient";
      in.fail(node, "'" + params[k].name + "' in 'known' is " +
                        shortest_text(*model.known_values[k]) + ", but " + what +
                        " cannot be negative");
    }
  }
}

// A body whose ten inertial parameters are all known must be one some mass distribution
// has: its pseudo-inertia positive semidefinite (mass, centre of mass and the inertia about
// it with the triangle inequalities), which the tensor about the frame origin alone is not.
void check_known_bodies(const YamlReader& in, const RobotModel& model,
                        const std::map<int, YAML::Node>& keys) {
  const auto indices = inertial_param_indices(model.tree);
  Eigen::VectorXd standard =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.tree.params.size()));
  std::vector<char> complete(indices.size(), 0);
  for (std::size_t body = 0; body < indices.size(); ++body) {
    complete[body] = std::all_of(indices[body].begin(), indices[body].end(), [&](int k) {
      return k >= 0 && model.known_values[static_cast<std::size_t>(k)].has_value();
    });
    if (!complete[body]) continue;
    for (int k : indices[body]) standard[k] = *model.known_values[static_cast<std::size_t>(k)];
  }
  for (const PhysicalViolation& violation : physical_violations(model.tree, standard)) {
    if (violation.body < 0 || !complete[static_cast<std::size_t>(violation.body)]) continue;
    const int first = indices[static_cast<std::size_t>(violation.body)][0];
    in.fail(keys.at(first), "link " + std::to_string(violation.body + 1) + " in 'known' (" +
                                violation.parameter + "): " + violation.condition +
                                "; no mass distribution has these values");
  }
}

// An inertia tensor of which all six entries are known must be one some mass distribution
// has, i.e. positive semi-definite (zero for a massless link is fine).
void check_known_tensors(const YamlReader& in, const RobotModel& model,
                         const std::map<int, YAML::Node>& keys) {
  const std::vector<StandardParam>& params = model.tree.params;
  for (std::size_t body = 0; body < model.tree.bodies.size(); ++body) {
    static const ParamKind kTensor[] = {ParamKind::kXX, ParamKind::kXY, ParamKind::kXZ,
                                        ParamKind::kYY, ParamKind::kYZ, ParamKind::kZZ};
    std::array<double, 6> I{};
    int first = -1;
    bool complete = true;
    for (int e = 0; e < 6; ++e) {
      int index = -1;
      for (std::size_t k = 0; k < params.size(); ++k) {
        if (params[k].body == static_cast<int>(body) && params[k].kind == kTensor[e]) {
          index = static_cast<int>(k);
        }
      }
      if (index < 0 || !model.known_values[index]) {
        complete = false;
        break;
      }
      if (first < 0) first = index;
      I[e] = *model.known_values[index];
    }
    if (!complete) continue;
    // Khalil's tensor entries: XY = -integral of x y dm, so J is [XX XY XZ; XY YY YZ; ...].
    Eigen::Matrix3d J;
    J << I[0], I[1], I[2], I[1], I[3], I[4], I[2], I[4], I[5];
    const Eigen::Vector3d eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J, Eigen::EigenvaluesOnly).eigenvalues();
    if (eigenvalues.minCoeff() < -1e-9 * J.cwiseAbs().maxCoeff()) {
      char text[96];
      std::snprintf(text, sizeof text, "%.6g, %.6g, %.6g", eigenvalues[0], eigenvalues[1],
                    eigenvalues[2]);
      const std::string suffix = std::to_string(body + 1);
      in.fail(keys.at(first), "the inertia tensor of link " + suffix + " in 'known' (XX" + suffix +
                                  " .. ZZ" + suffix +
                                  ") is not positive semi-definite (principal moments " + text +
                                  "): no mass distribution has it");
    }
  }
}

// The known value of `kind` for `body`, if any.
std::optional<double> known_of(const RobotModel& model, int body, ParamKind kind, int* index) {
  const std::vector<StandardParam>& params = model.tree.params;
  for (std::size_t k = 0; k < params.size(); ++k) {
    if (params[k].body == body && params[k].kind == kind && model.known_values[k]) {
      if (index != nullptr) *index = static_cast<int>(k);
      return model.known_values[k];
    }
  }
  return std::nullopt;
}

// Inertias too large for the link (magnitude_checks.hpp), for bodies whose XX, YY, ZZ, MX, MY,
// MZ and M are known. They are about the frame origin: by the parallel-axis theorem the trace
// about the centre of mass is XX + YY + ZZ - 2 |MS|^2 / M. The size is the farthest child frame
// or the centre of mass from the frame origin.
void note_known_inertia_sizes(const YamlReader& in, const RobotModel& model,
                              const std::map<int, YAML::Node>& keys,
                              std::vector<DescriptionNote>& notes) {
  for (std::size_t b = 0; b < model.tree.bodies.size(); ++b) {
    const int body = static_cast<int>(b);
    int first = -1;
    const auto xx = known_of(model, body, ParamKind::kXX, &first);
    const auto yy = known_of(model, body, ParamKind::kYY, nullptr);
    const auto zz = known_of(model, body, ParamKind::kZZ, nullptr);
    const auto mx = known_of(model, body, ParamKind::kMX, nullptr);
    const auto my = known_of(model, body, ParamKind::kMY, nullptr);
    const auto mz = known_of(model, body, ParamKind::kMZ, nullptr);
    const auto m = known_of(model, body, ParamKind::kM, nullptr);
    if (!xx || !yy || !zz || !mx || !my || !mz || !m || !(*m > 0)) continue;
    const double ms2 = *mx * *mx + *my * *my + *mz * *mz;
    double size = std::sqrt(ms2) / *m;
    for (const Body& child : model.tree.bodies) {
      if (child.parent != body) continue;
      const auto& t = child.fixed.translation;
      size = std::max(size, std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]));
    }
    const std::string suffix = std::to_string(body + 1);
    check_inertia_size(
        in.at(keys.at(first)),
        "link " + suffix + " in 'known' (XX" + suffix + ", YY" + suffix + ", ZZ" + suffix + ")", *m,
        *xx + *yy + *zz - 2 * ms2 / *m, size, notes);
  }
}

// A-priori values describe a real body: no negative mass, moment of inertia or drive
// inertia, and an inertia tensor (when all six entries are known) that some mass
// distribution has, i.e. positive semi-definite (zero for a massless link is fine).
void check_known_physical(const YamlReader& in, const RobotModel& model,
                          const std::map<int, YAML::Node>& keys) {
  check_known_signs(in, model, keys);
  check_known_bodies(in, model, keys);
  check_known_tensors(in, model, keys);
}

}  // namespace

void read_known_values(const YamlReader& in, const YAML::Node& node, RobotModel& model) {
  if (!node.IsMap()) in.fail(node, "'known' must map standard parameter names to values");
  const std::vector<std::string> names = model.param_names();
  std::map<int, YAML::Node> keys;  // where each known value was given
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    const int k = model.param_index(key);
    if (k < 0) {
      in.fail(entry.first, "'" + key + "' in 'known' is not a standard parameter of this robot" +
                               did_you_mean(key, names) + "; run 'modelgen describe' to list them");
    }
    if (model.known_values[k]) in.fail(entry.first, "'" + key + "' is given twice in 'known'");
    const bool mass = model.tree.params[k].kind == ParamKind::kM;
    model.known_values[k] =
        mass ? in.number(entry.second, key, kMaxMass, " kg") : in.number(entry.second, key);
    keys[k] = entry.first;
    if (mass) check_mass(in.at(entry.second), "known." + key, *model.known_values[k], model.notes);
  }
  check_known_physical(in, model, keys);
  note_known_inertia_sizes(in, model, keys, model.notes);
}

}  // namespace modelgen
