// The joint-limit messages and table of simulate, check-trajectory and design.

#include "runtime/cli/excitation/trajectory_limits.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

// A fraction as a percentage with one decimal, "97.3%".
std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%", 100 * fraction);
  return text;
}

}  // namespace

std::string joint_label(const ModelSource& source, int j) {
  std::string label = "joint " + std::to_string(j + 1);
  if (static_cast<std::size_t>(j) < source.joint_names.size()) {
    label += " ('" + source.joint_names[static_cast<std::size_t>(j)] + "')";
  }
  return label;
}

bool note_missing_limits(std::ostream& err, const std::string& command, const ModelSource& source) {
  if (source.limits.empty()) {
    err << "modelid " << command << ": note: no description of '" << source.model->name()
        << "' was found, so no joint limit is checked\n";
    return true;
  }
  std::map<std::string, std::string> joints_by_key;
  for (const auto& [joint, key] : missing_limits(source.limits)) {
    std::string& list = joints_by_key[key];
    list += (list.empty() ? "" : ", ") + joint_label(source, joint);
  }
  // Acceleration limits are rarely published and URDF has no place for them: their absence
  // is not worth a line (check-trajectory's table shows "(none)").
  for (const char* key : {"q", "dq"}) {
    const auto found = joints_by_key.find(key);
    if (found == joints_by_key.end()) continue;
    err << "modelid " << command << ": note: the description gives no '" << key
        << "' limit for " << found->second << "; not checked\n";
  }
  return joints_by_key.count("q") + joints_by_key.count("dq") > 0;
}

void refuse_beyond_limits(const std::string& path, const FourierTrajectory& trajectory,
                          const ModelSource& source, const std::string& advice) {
  std::ostringstream message;
  for (const LimitUse& use : limit_uses(trajectory_extremes(trajectory), source.limits)) {
    if (use.use <= 1.0) continue;
    if (!message.str().empty()) message << "\n";
    message << path << ": error: " << joint_label(source, use.joint) << " leaves its " << use.key
            << " limit: " << (use.key == "q" ? "q" : "|" + use.key + "|") << " = "
            << fixed(use.value, 0, 6) << " at t = " << fixed(use.time, 0, 6) << " s, limit "
            << fixed(use.limit, 0, 6);
  }
  if (!message.str().empty()) throw std::runtime_error(message.str() + "\n" + advice);
}

int print_limit_use(std::ostream& out, const ModelSource& source,
                    const std::vector<JointExtremes>& extremes, const std::vector<JointLimits>& limits) {
  const std::vector<LimitUse> uses = limit_uses(extremes, limits);
  int exceeded = 0;
  out << pad("joint", 16) << pad("q: peak", 12) << pad("limit", 10) << pad("use", 10)
      << pad("|dq|: peak", 12) << pad("limit", 10) << pad("use", 10) << pad("|ddq|: peak", 12)
      << pad("limit", 10) << "use\n";
  for (std::size_t j = 0; j < extremes.size(); ++j) {
    std::string name = std::to_string(j + 1);
    if (j < source.joint_names.size()) name += " " + source.joint_names[j];
    std::ostringstream row;
    row << pad(name, 15) << " ";
    for (const char* key : {"q", "dq", "ddq"}) {
      const LimitUse* found = nullptr;
      for (const LimitUse& use : uses) {
        if (use.joint == static_cast<int>(j) && use.key == key) found = &use;
      }
      if (found == nullptr) {
        const JointExtremes& e = extremes[j];
        const double peak = std::string(key) == "q"     ? (std::abs(e.q_max) >= std::abs(e.q_min) ? e.q_max : e.q_min)
                            : std::string(key) == "dq" ? e.dq_peak
                                                       : e.ddq_peak;
        row << pad(fixed(peak, 0, 4), 12) << pad("(none)", 10) << pad("-", 10);
        continue;
      }
      const bool over = found->use > 1.0;
      exceeded += over ? 1 : 0;
      row << pad(fixed(found->value, 0, 4), 12) << pad(fixed(found->limit, 0, 4), 10)
          << pad(percent(found->use) + (over ? "!" : ""), 10);
    }
    std::string text = row.str();
    text.erase(text.find_last_not_of(' ') + 1);
    out << text << "\n";
  }
  return exceeded;
}

int print_torque_use(std::ostream& out, const ModelSource& source,
                     const std::vector<TorquePeak>& peaks, const std::vector<JointLimits>& limits) {
  int exceeded = 0;
  out << pad("joint", 16) << pad("|tau|: peak", 12) << pad("at t", 10) << pad("effort", 10) << "use\n";
  for (std::size_t j = 0; j < peaks.size(); ++j) {
    std::string name = std::to_string(j + 1);
    if (j < source.joint_names.size()) name += " " + source.joint_names[j];
    std::ostringstream row;
    row << pad(name, 15) << " " << pad(fixed(peaks[j].peak, 0, 4), 12) << pad(fixed(peaks[j].time, 0, 4), 10);
    const std::optional<double> effort = j < limits.size() ? limits[j].effort : std::nullopt;
    if (!effort) {
      row << "(none)";
    } else {
      const double use = peaks[j].peak / *effort;
      const bool over = use > 1.0;
      exceeded += over ? 1 : 0;
      row << pad(fixed(*effort, 0, 4), 10) << percent(use) << (over ? "!" : "");
    }
    out << row.str() << "\n";
  }
  return exceeded;
}

void apply_ddq_limit_option(const CommandLine& args, std::vector<JointLimits>& limits) {
  if (!args.has("--ddq-limit")) return;
  const std::vector<double> values =
      per_axis_values(args.one("--ddq-limit"), "--ddq-limit", static_cast<int>(limits.size()),
                      "acceleration limit", "joint", AxisValue::kPositive);
  for (std::size_t j = 0; j < limits.size(); ++j) limits[j].ddq = values[j];
}

}  // namespace modelgen::internal
