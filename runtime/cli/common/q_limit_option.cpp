// --q-limit JOINT=LO,HI: a continuous joint has no position range, and a user who wants one
// (cables, a tool that must not wind up) says it here rather than editing the description,
// whose SHA-256 then still matches its generated code.

#include "runtime/cli/common/q_limit_option.hpp"

#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "modelgen/model/error.hpp"

namespace modelgen::internal {

namespace {

// The 0-based joint JOINT names: a joint name of the description, or a number 1..dof.
int joint_index(const std::string& joint, const ModelSource& source, const std::string& item) {
  for (std::size_t j = 0; j < source.joint_names.size(); ++j) {
    if (source.joint_names[j] == joint) return static_cast<int>(j);
  }
  const int dof = source.model->dof();
  if (!joint.empty() && joint.find_first_not_of("0123456789") == std::string::npos &&
      joint.size() <= 3) {
    const int number = std::stoi(joint);
    if (number >= 1 && number <= dof) return number - 1;
  }
  std::string known;
  for (const std::string& name : source.joint_names) known += (known.empty() ? "" : ", ") + name;
  throw UsageError("--q-limit '" + item + "': no moving joint '" + joint + "'" +
                   did_you_mean(joint, source.joint_names) + "; give a joint's name" +
                   (known.empty() ? "" : " (" + known + ")") + " or its number, 1 to " +
                   std::to_string(dof));
}

}  // namespace

OptionSpec q_limit_option_spec() {
  return {.name = "--q-limit",
          .value = "JOINT=LO,HI",
          .help =
              "the position range of a joint (by name or 1-based number), replacing the "
              "description's or giving a continuous joint one",
          .unit = "rad or m",
          .repeatable = true};
}

void apply_q_limit_option(const CommandLine& args, ModelSource& source) {
  if (!args.has("--q-limit")) return;
  const std::size_t dof = static_cast<std::size_t>(source.model->dof());
  if (source.limits.size() != dof) source.limits.assign(dof, JointLimits{});
  std::set<int> given;
  for (const std::string& item : args.all("--q-limit")) {
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) {
      throw UsageError("--q-limit '" + item + "': expected JOINT=LO,HI (joint_6=-3.14,3.14)");
    }
    const int j = joint_index(item.substr(0, equals), source, item);
    const std::vector<std::string> bounds = comma_items(item.substr(equals + 1), "--q-limit");
    if (bounds.size() != 2) {
      throw UsageError("--q-limit '" + item + "': expected two bounds LO,HI after '='");
    }
    const double lower = parse_number(bounds[0], "--q-limit");
    const double upper = parse_number(bounds[1], "--q-limit");
    if (!(lower < upper)) {
      throw UsageError("--q-limit '" + item + "': the lower bound must be below the upper one");
    }
    if (!given.insert(j).second) {
      throw UsageError("--q-limit '" + item + "': joint " + std::to_string(j + 1) +
                       " is given a range twice");
    }
    JointLimits& limits = source.limits[static_cast<std::size_t>(j)];
    limits.q_lower = lower;
    limits.q_upper = upper;
    limits.continuous = false;
  }
}

}  // namespace modelgen::internal
