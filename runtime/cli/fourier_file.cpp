// Fourier trajectory YAML through yaml-cpp; every yaml-cpp error becomes a positioned
// modelgen::InputError.

#include "runtime/cli/fourier_file.hpp"

#include <algorithm>
#include <array>
#include <numbers>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/error.hpp"

namespace modelgen::internal {

namespace {

FourierTrajectory read_fourier_checked(const std::string& path, int dof) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw modelgen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
  auto at = [&](const YAML::Node& node) -> modelgen::SourceLocation {
    return {path, node.Mark().line + 1, node.Mark().column + 1};
  };
  FourierTrajectory f;
  if (!root["period"] || !root["joints"] || !root["joints"].IsSequence()) {
    throw modelgen::InputError({path},
                          "a trajectory needs 'period' (s) and 'joints' (one entry per "
                          "joint with q0 and a, b or terms)");
  }
  f.period = root["period"].as<double>();
  if (!(f.period > 0)) throw modelgen::InputError(at(root["period"]), "'period' must be positive (s)");
  std::string form = "velocity";
  if (root["form"]) form = root["form"].as<std::string>();
  if (form != "velocity" && form != "position") {
    throw modelgen::InputError(at(root["form"]),
                          "'form' is 'velocity' (a/(l w) sin - b/(l w) cos, Swevers 1997) or "
                          "'position' (a sin + b cos, Swevers 2002 eq. 15), not '" +
                              form + "'");
  }
  const YAML::Node joints = root["joints"];
  if (static_cast<int>(joints.size()) != dof) {
    throw modelgen::InputError(at(joints), "'joints' has " + std::to_string(joints.size()) +
                                          " entries, the robot has " + std::to_string(dof) +
                                          " joints");
  }
  // Coefficients as written: dense lists a, b (harmonics 1, 2, ...) or sparse terms
  // [{l, a, b}], zero elsewhere.
  std::vector<std::vector<std::array<double, 3>>> written(static_cast<std::size_t>(dof));
  int harmonics = 0;
  f.q0 = Eigen::VectorXd::Zero(dof);
  for (int j = 0; j < dof; ++j) {
    const YAML::Node joint = joints[j];
    if (joint["q0"]) f.q0[j] = joint["q0"].as<double>();
    auto& terms = written[static_cast<std::size_t>(j)];
    if (joint["terms"]) {
      if (joint["a"] || joint["b"]) {
        throw modelgen::InputError(at(joint), "joint " + std::to_string(j + 1) +
                                             ": give either 'a' and 'b' or 'terms', not both");
      }
      for (const YAML::Node& term : joint["terms"]) {
        if (!term["l"] || !term["a"] || !term["b"]) {
          throw modelgen::InputError(at(term), "a term needs 'l' (harmonic, 1 or more), 'a' and 'b'");
        }
        const int l = term["l"].as<int>();
        if (l < 1) throw modelgen::InputError(at(term["l"]), "harmonic 'l' must be 1 or more");
        terms.push_back({static_cast<double>(l), term["a"].as<double>(), term["b"].as<double>()});
        harmonics = std::max(harmonics, l);
      }
    } else {
      if (!joint["a"] || !joint["b"] || joint["a"].size() != joint["b"].size()) {
        throw modelgen::InputError(at(joint), "joint " + std::to_string(j + 1) +
                                             " needs 'a' and 'b' with as many coefficients "
                                             "each, or 'terms'");
      }
      for (std::size_t l = 0; l < joint["a"].size(); ++l) {
        terms.push_back(
            {static_cast<double>(l + 1), joint["a"][l].as<double>(), joint["b"][l].as<double>()});
      }
      harmonics = std::max(harmonics, static_cast<int>(joint["a"].size()));
    }
  }
  const double wf = 2.0 * std::numbers::pi / f.period;
  f.a = Eigen::MatrixXd::Zero(dof, harmonics);
  f.b = Eigen::MatrixXd::Zero(dof, harmonics);
  for (int j = 0; j < dof; ++j) {
    for (const auto& [l, a, b] : written[static_cast<std::size_t>(j)]) {
      const int k = static_cast<int>(l) - 1;
      if (form == "velocity") {
        f.a(j, k) = a;
        f.b(j, k) = b;
      } else {
        // a sin(l w t) + b cos(l w t) = (a l w)/(l w) sin - (-b l w)/(l w) cos.
        f.a(j, k) = a * l * wf;
        f.b(j, k) = -b * l * wf;
      }
    }
  }
  return f;
}

}  // namespace

FourierTrajectory read_fourier(const std::string& path, int dof) {
  // Conversion errors (as<double>() on text) surface here with their mark.
  try {
    return read_fourier_checked(path, dof);
  } catch (const YAML::Exception& e) {
    throw modelgen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
}

}  // namespace modelgen::internal
