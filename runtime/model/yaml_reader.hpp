// Typed, positioned reading of YAML values for the description loader: every value is checked
// and every problem is an InputError at the node's line and column (yaml-cpp's marks), naming
// the field. Private to the model core.
#pragma once

#include <algorithm>
#include <cmath>
#include <locale>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

class YamlReader {
 public:
  explicit YamlReader(const std::string& path) : path_(path) {}

  SourceLocation at(const YAML::Node& node) const {
    const YAML::Mark mark = node.Mark();
    if (mark.is_null()) return {path_};
    return {path_, mark.line + 1, mark.column + 1};
  }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    throw InputError(at(node), message);
  }

  // Rejects keys outside `allowed` (suggesting the closest) and duplicate keys.
  void check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                  const std::string& context) const {
    if (!map.IsMap()) fail(map, context + " must be a mapping of keys to values");
    std::set<std::string> seen;
    for (const auto& entry : map) {
      const std::string key = entry.first.Scalar();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string valid;
        for (const std::string& a : allowed) valid += (valid.empty() ? "" : ", ") + a;
        fail(entry.first, "unknown key '" + key + "' in " + context + did_you_mean(key, allowed) +
                              "; valid keys: " + valid);
      }
      if (!seen.insert(key).second) fail(entry.first, "duplicate key '" + key + "' in " + context);
    }
  }

  YAML::Node require(const YAML::Node& map, const std::string& key,
                     const std::string& context) const {
    YAML::Node value = map[key];
    if (!value) fail(map, "missing field '" + key + "' in " + context);
    return value;
  }

  /// A finite number of magnitude at most `limit` (the description limits; `unit` for the
  /// message).
  double number(const YAML::Node& node, const std::string& field, double limit = kMaxMagnitude,
                const std::string& unit = "") const {
    if (!node.IsScalar()) fail(node, "'" + field + "' must be a number");
    std::istringstream in(node.Scalar());
    in.imbue(std::locale::classic());
    double value = 0;
    in >> value;
    if (in.fail() || !in.eof() || !std::isfinite(value)) {
      fail(node, "'" + field + "' must be a number, got '" + node.Scalar() + "'");
    }
    within(node, field, value, limit, unit);
    return value;
  }

  /// Fails unless |value| <= limit; `unit` (" m", " kg") completes the message.
  void within(const YAML::Node& node, const std::string& field, double value, double limit,
              const std::string& unit) const {
    if (std::abs(value) > limit) {
      fail(node, "'" + field + "' is " + node.Scalar() + unit + ", beyond the limit of " +
                     shortest_text(limit) + unit + " a description may hold (README, Limits)");
    }
  }

  /// A length in metres (or gravity in m/s^2), |value| <= kMaxLength.
  double length(const YAML::Node& node, const std::string& field) const {
    return number(node, field, kMaxLength, " m");
  }

  double positive(const YAML::Node& node, const std::string& field) const {
    const double value = number(node, field);
    if (value <= 0) fail(node, "'" + field + "' must be positive, got " + node.Scalar());
    return value;
  }

  long integer(const YAML::Node& node, const std::string& field) const {
    const double value = number(node, field);
    if (value != std::floor(value) || std::abs(value) > 1e9) {
      fail(node, "'" + field + "' must be an integer, got '" + node.Scalar() + "'");
    }
    return static_cast<long>(value);
  }

  bool boolean(const YAML::Node& node, const std::string& field) const {
    if (node.IsScalar()) {
      const std::string& s = node.Scalar();
      if (s == "true" || s == "True" || s == "yes") return true;
      if (s == "false" || s == "False" || s == "no") return false;
    }
    fail(node, "'" + field + "' must be true or false");
  }

  std::string text(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(node, "'" + field + "' must be a string");
    return node.Scalar();
  }

  Angle angle(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar()) fail(node, "'" + field + "' must be an angle");
    auto parsed = parse_angle(node.Scalar());
    if (!parsed) {
      fail(node, "'" + field + "' must be an angle in radians: a number or an expression of pi "
                               "such as pi/2, -pi/2, 3*pi/4; got '" + node.Scalar() + "'");
    }
    within(node, field, parsed->value, kMaxAngle, " rad");
    return *parsed;
  }

  std::vector<double> numbers(const YAML::Node& node, const std::string& field,
                              std::size_t expected) const {
    if (!node.IsSequence() || node.size() != expected) {
      fail(node, "'" + field + "' must be a list of " + std::to_string(expected) + " numbers");
    }
    std::vector<double> out;
    for (const auto& item : node) out.push_back(number(item, field));
    return out;
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace modelgen
