// controller.yaml through yaml-cpp and the description loader's positioned reader.

#include "modelgen/io/experiment/controller_file.hpp"

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "runtime/io/experiment/yaml_file.hpp"
#include "runtime/model/yaml_reader.hpp"

namespace modelgen::io {

namespace {

constexpr double kMinControllerSampleTime = 1e-6;
// Joint controllers run at 100 Hz or faster; from 0.1 s on, a millisecond value is the likely slip.
constexpr double kSlowControllerSampleTime = 0.1;

PidGains read_checked(const std::string& path, int dof, std::vector<std::string>* warnings) {
  const YAML::Node root = load_yaml_file(path, "a controller file");
  const YamlReader in(path);
  if (!root.IsMap()) {
    throw modelgen::InputError({path}, "a controller is a mapping: type: pid, sample_time, kp, "
                                       "ki, kd");
  }
  in.check_keys(root, {"type", "sample_time", "kp", "ki", "kd"}, "the controller");
  const std::string type = in.text(in.require(root, "type", "the controller"), "type");
  if (type != "pid") {
    in.fail(root["type"], "controller 'type' must be 'pid' (the one controller modelid "
                          "simulates), not '" + type + "'");
  }
  PidGains gains;
  const YAML::Node ts = in.require(root, "sample_time", "the controller");
  gains.sample_time = in.number(ts, "sample_time");
  // Below a microsecond no joint controller runs, and a closed-loop simulation would take
  // hours of steps per second of motion.
  if (!(gains.sample_time >= kMinControllerSampleTime) || gains.sample_time > 1) {
    in.fail(ts,
            "'sample_time' is the controller's period in seconds, from 1e-06 (1 MHz) to 1 "
            "(e.g. 0.001 for 1 kHz), got " +
                ts.Scalar());
  }
  if (gains.sample_time >= kSlowControllerSampleTime && warnings != nullptr) {
    const SourceLocation where = in.at(ts);
    warnings->push_back(where.to_string() + ": warning: 'sample_time' is " + ts.Scalar() +
                        " s, a controller running at " + shortest_text(1 / gains.sample_time) +
                        " Hz; sample_time is in seconds: milliseconds? (0.001 for 1 kHz)");
  }
  Eigen::VectorXd* lists[] = {&gains.kp, &gains.ki, &gains.kd};
  const char* names[] = {"kp", "ki", "kd"};
  for (int i = 0; i < 3; ++i) {
    const YAML::Node node = in.require(root, names[i], "the controller");
    if (!node.IsSequence() || static_cast<int>(node.size()) != dof) {
      in.fail(node, std::string("'") + names[i] + "' must be a list of " + std::to_string(dof) +
                        " gains, one per joint" +
                        (node.IsSequence() ? ", not " + std::to_string(node.size()) : ""));
    }
    lists[i]->resize(dof);
    for (int j = 0; j < dof; ++j) {
      const double g = in.number(node[j], names[i]);
      if (g < 0 || (i == 0 && g == 0)) {
        in.fail(node[j], std::string("'") + names[i] + "' of joint " + std::to_string(j + 1) +
                             (i == 0 ? " must be greater than 0 (without it the loop does not "
                                       "hold the joint)"
                                     : " cannot be negative") +
                             ", got " + node[j].Scalar());
      }
      (*lists[i])[j] = g;
    }
  }
  return gains;
}

}  // namespace

PidGains read_controller(const std::string& path, int dof, std::vector<std::string>* warnings) {
  try {
    return read_checked(path, dof, warnings);
  } catch (const YAML::Exception& e) {
    throw modelgen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
}

}  // namespace modelgen::io
