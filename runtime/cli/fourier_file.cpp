// Fourier trajectory YAML through yaml-cpp; every yaml-cpp error becomes a positioned
// gen::InputError.

#include "runtime/cli/fourier_file.hpp"

#include <yaml-cpp/yaml.h>

#include "generator/description/diagnostics.hpp"

namespace modelgen::internal {

namespace {

FourierTrajectory read_fourier_checked(const std::string& path, int dof) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw gen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
  auto at = [&](const YAML::Node& node) -> gen::SourceLocation {
    return {path, node.Mark().line + 1, node.Mark().column + 1};
  };
  FourierTrajectory f;
  if (!root["period"] || !root["joints"] || !root["joints"].IsSequence()) {
    throw gen::InputError({path},
                          "a trajectory needs 'period' (s) and 'joints' (one entry per "
                          "joint with q0, a, b)");
  }
  f.period = root["period"].as<double>();
  if (!(f.period > 0)) throw gen::InputError(at(root["period"]), "'period' must be positive (s)");
  const YAML::Node joints = root["joints"];
  if (static_cast<int>(joints.size()) != dof) {
    throw gen::InputError(at(joints), "'joints' has " + std::to_string(joints.size()) +
                                          " entries, the robot has " + std::to_string(dof) +
                                          " joints");
  }
  const std::size_t harmonics = joints[0]["a"] ? joints[0]["a"].size() : 0;
  f.q0 = Eigen::VectorXd::Zero(dof);
  f.a = Eigen::MatrixXd::Zero(dof, harmonics);
  f.b = Eigen::MatrixXd::Zero(dof, harmonics);
  for (int j = 0; j < dof; ++j) {
    const YAML::Node joint = joints[j];
    if (!joint["a"] || !joint["b"] || joint["a"].size() != harmonics ||
        joint["b"].size() != harmonics) {
      throw gen::InputError(at(joint), "joint " + std::to_string(j + 1) +
                                           " needs 'a' and 'b' with " + std::to_string(harmonics) +
                                           " coefficients each");
    }
    if (joint["q0"]) f.q0[j] = joint["q0"].as<double>();
    for (std::size_t l = 0; l < harmonics; ++l) {
      f.a(j, l) = joint["a"][l].as<double>();
      f.b(j, l) = joint["b"][l].as<double>();
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
    throw gen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
}

}  // namespace modelgen::internal
