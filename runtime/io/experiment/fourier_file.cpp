// Fourier trajectory YAML through yaml-cpp and the description loader's positioned reader:
// every key checked (unknown or given twice), every number finite, and hard limits on the
// period and the harmonics so that a typo cannot make `simulate` run for hours.

#include "modelgen/io/experiment/fourier_file.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numbers>
#include <sstream>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/error.hpp"
#include "runtime/io/experiment/yaml_file.hpp"
#include "runtime/model/yaml_reader.hpp"

namespace modelgen::io {

namespace {

FourierTrajectory read_fourier_checked(const std::string& path, int dof) {
  const YAML::Node root = load_yaml_file(path, "a trajectory file");
  const YamlReader in(path);
  FourierTrajectory f;
  if (!root.IsMap() || !root["period"] || !root["joints"] || !root["joints"].IsSequence()) {
    throw modelgen::InputError({path},
                          "a trajectory needs 'period' (s) and 'joints' (one entry per "
                          "joint with q0 and a, b or terms)");
  }
  in.check_keys(root, {"period", "form", "joints"}, "the trajectory");
  f.period = in.number(root["period"], "period");
  if (f.period < kMinFourierPeriod || f.period > kMaxFourierPeriod) {
    std::ostringstream limits;
    limits << kMinFourierPeriod << " s and " << kMaxFourierPeriod << " s";
    in.fail(root["period"], "'period' must be between " + limits.str() +
                                " (a hard limit of modelid), got " + root["period"].Scalar());
  }
  std::string form = "velocity";
  if (root["form"]) form = in.text(root["form"], "form");
  if (form != "velocity" && form != "position") {
    in.fail(root["form"],
            "'form' is 'velocity' (a/(l w) sin - b/(l w) cos, Swevers 1997) or "
            "'position' (a sin + b cos, Swevers 2002 eq. 15), not '" + form + "'");
  }
  const YAML::Node joints = root["joints"];
  if (static_cast<int>(joints.size()) != dof) {
    in.fail(joints, "'joints' has " + std::to_string(joints.size()) + " entries, the robot has " +
                        std::to_string(dof) + " joints");
  }
  auto harmonic_limit = [](const std::string& what) {
    return what + " (a hard limit of modelid: " + std::to_string(kMaxFourierHarmonic) +
           " harmonics)";
  };
  // Coefficients as written: dense lists a, b (harmonics 1, 2, ...) or sparse terms
  // [{l, a, b}], zero elsewhere.
  std::vector<std::vector<std::array<double, 3>>> written(static_cast<std::size_t>(dof));
  int harmonics = 0;
  f.q0 = Eigen::VectorXd::Zero(dof);
  for (int j = 0; j < dof; ++j) {
    const YAML::Node joint = joints[j];
    const std::string context = "joint " + std::to_string(j + 1);
    in.check_keys(joint, {"q0", "a", "b", "terms"}, context);
    if (joint["q0"]) f.q0[j] = in.number(joint["q0"], "q0");
    auto& terms = written[static_cast<std::size_t>(j)];
    if (joint["terms"]) {
      if (joint["a"] || joint["b"]) {
        in.fail(joint, context + ": give either 'a' and 'b' or 'terms', not both");
      }
      if (!joint["terms"].IsSequence()) in.fail(joint["terms"], "'terms' must be a list");
      std::map<long, int> line_of;  // harmonic -> line of its first term
      for (const YAML::Node& term : joint["terms"]) {
        if (!term.IsMap() || !term["l"] || !term["a"] || !term["b"]) {
          in.fail(term, "a term needs 'l' (harmonic, 1 or more), 'a' and 'b'");
        }
        in.check_keys(term, {"l", "a", "b"}, "a term of " + context);
        const long l = in.integer(term["l"], "l");
        if (l < 1) in.fail(term["l"], "harmonic 'l' must be 1 or more");
        if (l > kMaxFourierHarmonic) {
          in.fail(term["l"], harmonic_limit("harmonic 'l' is " + std::to_string(l) +
                                            ", more than " +
                                            std::to_string(kMaxFourierHarmonic)));
        }
        const int line = in.at(term["l"]).line;
        if (const auto [earlier, inserted] = line_of.emplace(l, line); !inserted) {
          in.fail(term["l"], context + ": harmonic " + std::to_string(l) +
                                 " is given twice (first at line " +
                                 std::to_string(earlier->second) + "); give each harmonic once");
        }
        terms.push_back({static_cast<double>(l), in.number(term["a"], "a"),
                         in.number(term["b"], "b")});
        harmonics = std::max(harmonics, static_cast<int>(l));
      }
    } else {
      if (!joint["a"] || !joint["b"] || !joint["a"].IsSequence() || !joint["b"].IsSequence() ||
          joint["a"].size() != joint["b"].size()) {
        in.fail(joint, context + " needs 'a' and 'b' with as many coefficients each, or 'terms'");
      }
      if (joint["a"].size() > static_cast<std::size_t>(kMaxFourierHarmonic)) {
        in.fail(joint["a"], harmonic_limit(context + ": 'a' and 'b' have " +
                                           std::to_string(joint["a"].size()) +
                                           " coefficients, more than " +
                                           std::to_string(kMaxFourierHarmonic)));
      }
      for (std::size_t l = 0; l < joint["a"].size(); ++l) {
        terms.push_back({static_cast<double>(l + 1), in.number(joint["a"][l], "a"),
                         in.number(joint["b"][l], "b")});
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

}  // namespace modelgen::io
