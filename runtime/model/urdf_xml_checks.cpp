// Checks of single URDF elements and their attributes, with the line of each problem: the
// numbers of the TinyXML2 pass (urdf_structure.cpp), and the elements urdfdom would reject
// without a line or read without a word.

#include "runtime/model/urdf_xml_checks.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tinyxml2.h>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"

namespace modelgen {

namespace {

// White-space separated finite numbers, as URDF writes vectors; nullopt if any token is not one.
std::optional<std::vector<double>> parse_numbers(std::string_view text) {
  std::vector<double> values;
  std::size_t at = 0;
  while (true) {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    if (at == text.size()) break;
    std::size_t end = at;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    std::string_view token = text.substr(at, end - at);
    at = end;
    // from_chars rejects a leading '+', which strtod (and so urdfdom) accepts.
    if (token.front() == '+') {
      token.remove_prefix(1);
      if (token.empty() || token.front() == '-') return std::nullopt;
    }
    double value = 0;
    const auto [last, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || last != token.data() + token.size() || !std::isfinite(value)) {
      return std::nullopt;
    }
    values.push_back(value);
  }
  return values;
}

}  // namespace

// TinyXML2's error names are its enum identifiers; say the same in words.
std::string xml_error(const tinyxml2::XMLDocument& document) {
  std::string element;
  const std::string detail = document.ErrorStr() ? document.ErrorStr() : "";
  const std::string marker = "XMLElement name=";
  if (const std::size_t at = detail.find(marker); at != std::string::npos) {
    element = detail.substr(at + marker.size());
  }
  const std::string which = element.empty() ? "an element" : "<" + element + ">";
  switch (document.ErrorID()) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return which + " opened on this line is not closed by a matching closing tag";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return which + " is not well formed";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "an attribute of " + which + " is not well formed (write name=\"value\")";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "text could not be read";
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return "a CDATA section is not closed";
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return "a comment is not closed with '-->'";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return "an <?...?> declaration is not well formed";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return "a <!...> construct could not be read";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "the file is empty";
    case tinyxml2::XML_ERROR_PARSING:
      return "the document ends before all elements are closed, or holds stray text";
    default:
      return detail;
  }
}

[[noreturn]] void UrdfElementChecker::fail(const tinyxml2::XMLElement* element,
                                           const std::string& message) const {
  throw InputError({path_, element->GetLineNum(), 0}, message);
}

// Checks that `attribute` of `element` holds `count` numbers; `what` names the owner and the
// element for the message ("joint 'j1': origin"). Returns the numbers, nullopt if absent.
std::optional<std::vector<double>> UrdfElementChecker::numbers(
    const tinyxml2::XMLElement* element, const char* attribute, std::size_t count,
    const std::string& what, bool required, double limit, const char* unit) const {
  const char* text = element->Attribute(attribute);
  if (text == nullptr) {
    if (required) fail(element, what + " has no " + attribute + " attribute");
    return std::nullopt;
  }
  auto values = parse_numbers(text);
  if (!values || values->size() != count) {
    fail(element, what + " " + attribute + "='" + text + "' is not " +
                      (count == 1   ? "a number"
                       : count == 3 ? "three numbers"
                                    : std::to_string(count) + " numbers"));
  }
  // Beyond the description limits, products in the dynamics overflow (README, Limits).
  for (const double value : *values) {
    if (limit > 0 && std::abs(value) > limit) {
      fail(element, what + " " + attribute + "='" + text + "' holds " + shortest_text(value) +
                        unit + ", beyond the limit of " + shortest_text(limit) + unit +
                        " a description may hold (README, Limits)");
    }
  }
  return values;
}

// urdfdom reads the first of each of these and ignores the rest without a word; a second
// one is a mistake (two <child> in a joint, two <inertial> in a link) the user should see.
void UrdfElementChecker::check_single(const tinyxml2::XMLElement* parent, const char* element,
                                      const std::string& owner) const {
  const tinyxml2::XMLElement* first = parent->FirstChildElement(element);
  if (first == nullptr) return;
  if (const tinyxml2::XMLElement* second = first->NextSiblingElement(element)) {
    fail(second, owner + " has a second <" + element + "> (the first is at line " +
                     std::to_string(first->GetLineNum()) + "); give exactly one");
  }
}

// <visual> and <collision>: urdfdom rejects a bad one with "Could not parse visual/collision
// element" on the console and no line; check what it checks, with the line.
void UrdfElementChecker::check_geometry_owner(const tinyxml2::XMLElement* element,
                                              const std::string& owner) const {
  const std::string what = owner + ": <" + element->Name() + ">";
  check_origin(element, what + " origin");
  const tinyxml2::XMLElement* geometry = element->FirstChildElement("geometry");
  if (geometry == nullptr) fail(element, what + " has no <geometry>");
  const tinyxml2::XMLElement* shape = geometry->FirstChildElement();
  if (shape == nullptr) {
    fail(geometry, what + ": <geometry> holds no shape (box, cylinder, sphere or mesh)");
  }
  const std::string name = shape->Name();
  const std::string shape_what = what + " " + name;
  if (name == "box") {
    numbers(shape, "size", 3, shape_what, true);
  } else if (name == "cylinder" || name == "capsule") {
    numbers(shape, "radius", 1, shape_what, true);
    numbers(shape, "length", 1, shape_what, true);
  } else if (name == "sphere") {
    numbers(shape, "radius", 1, shape_what, true);
  } else if (name == "mesh") {
    const char* file = shape->Attribute("filename");
    if (file == nullptr || *file == '\0') fail(shape, shape_what + " has no filename attribute");
    numbers(shape, "scale", 3, shape_what, false);
  } else {
    fail(shape, what + ": unknown geometry <" + name + ">" +
                    did_you_mean(name, {"box", "cylinder", "sphere", "mesh"}) +
                    "; expected box, cylinder, sphere or mesh");
  }
}

OriginEntry UrdfElementChecker::check_origin(const tinyxml2::XMLElement* parent,
                                             const std::string& what) const {
  OriginEntry entry;
  const tinyxml2::XMLElement* origin = parent->FirstChildElement("origin");
  if (origin == nullptr) return entry;
  entry.line = origin->GetLineNum();
  if (const auto xyz = numbers(origin, "xyz", 3, what, false, kMaxLength, " m")) {
    std::copy(xyz->begin(), xyz->end(), entry.xyz.begin());
  }
  if (const auto rpy = numbers(origin, "rpy", 3, what, false, kMaxAngle, " rad")) {
    std::copy(rpy->begin(), rpy->end(), entry.rpy.begin());
  }
  return entry;
}

// The inertia about the centre of mass must be positive semi-definite (a body whose mass is
// all in one point has zero inertia, which URDFs write); anything else has no mass
// distribution and makes every "physically consistent" check downstream meaningless.
void UrdfElementChecker::check_inertia(const tinyxml2::XMLElement* inertia,
                                       const std::string& owner,
                                       const std::array<double, 6>& I) const {
  for (const auto& [index, name] : {std::pair{0, "ixx"}, {3, "iyy"}, {5, "izz"}}) {
    if (I[index] < 0) {
      fail(inertia, owner + ": inertia " + name + "='" + inertia->Attribute(name) +
                        "' is negative; a moment of inertia cannot be");
    }
  }
  Eigen::Matrix3d J;
  J << I[0], I[1], I[2], I[1], I[3], I[4], I[2], I[4], I[5];
  const double scale = J.cwiseAbs().maxCoeff();
  const Eigen::Vector3d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J, Eigen::EigenvaluesOnly).eigenvalues();
  if (eigenvalues.minCoeff() < -1e-9 * scale) {
    char text[96];
    std::snprintf(text, sizeof text, "%.6g, %.6g, %.6g", eigenvalues[0], eigenvalues[1],
                  eigenvalues[2]);
    fail(inertia, owner + ": the inertia tensor is not positive semi-definite (principal " +
                      "moments " + text + "): no mass distribution has it");
  }
}

// urdfdom reads the axis of moving joints only; a fixed joint's axis means nothing.
void UrdfElementChecker::check_joint_axis(const tinyxml2::XMLElement* joint,
                                          const std::string& owner, JointEntry& entry) const {
  const tinyxml2::XMLElement* axis = joint->FirstChildElement("axis");
  if (axis == nullptr || !is_moving(entry.type)) return;
  // The URDF specification defaults the axis to 1 0 0 when <axis> is left out (urdfdom does
  // so) but requires xyz in an <axis>; urdfdom then leaves the axis 0 0 0, which no joint
  // moves along. A misspelt attribute (xyzz) is most likely the axis meant, so it is named.
  if (axis->Attribute("xyz") == nullptr) {
    std::string others;
    std::string suggestion;
    for (const tinyxml2::XMLAttribute* a = axis->FirstAttribute(); a != nullptr; a = a->Next()) {
      others += std::string(others.empty() ? ", but " : ", ") + "'" + a->Name() + "'";
      if (suggestion.empty()) suggestion = did_you_mean(a->Name(), {"xyz"});
    }
    fail(axis, owner + ": <axis> has no xyz attribute" + others + suggestion +
                   "; URDF requires xyz in an <axis> (leave <axis> out for the default axis 1 0 "
                   "0)");
  }
  const std::vector<double> xyz = *numbers(axis, "xyz", 3, owner + ": axis", true, kMaxMagnitude);
  if (xyz[0] == 0 && xyz[1] == 0 && xyz[2] == 0) {
    fail(axis, owner + ": axis xyz='" + axis->Attribute("xyz") +
                   "' is the zero vector; give the direction of motion");
  }
  // Scaled before squaring, so that the norm of 1e-200 does not underflow to 0 here.
  const double scale = std::max({std::abs(xyz[0]), std::abs(xyz[1]), std::abs(xyz[2])});
  const double norm = scale * std::hypot(xyz[0] / scale, xyz[1] / scale, xyz[2] / scale);
  if (norm < kMinAxisNorm) {
    fail(axis, owner + ": axis xyz='" + axis->Attribute("xyz") + "' has norm " +
                   shortest_text(norm) + ", below the limit of " + shortest_text(kMinAxisNorm) +
                   " (README, Limits); write a unit vector");
  }
  entry.axis = std::array<double, 3>{xyz[0], xyz[1], xyz[2]};
  entry.axis_line = axis->GetLineNum();
}

// The <limit> of a joint, required for revolute and prismatic joints.
void UrdfElementChecker::check_joint_limit(const tinyxml2::XMLElement* joint,
                                           const std::string& owner, JointEntry& entry) const {
  const tinyxml2::XMLElement* limit = joint->FirstChildElement("limit");
  if (limit != nullptr) {
    const std::string what = owner + ": limit";
    const auto lower = numbers(limit, "lower", 1, what, false);
    const auto upper = numbers(limit, "upper", 1, what, false);
    entry.has_lower = lower.has_value();
    entry.has_upper = upper.has_value();
    // Continuous joints ignore lower and upper (urdfdom too), so only the others are checked.
    if (lower && upper && entry.type != "continuous" && (*lower)[0] > (*upper)[0]) {
      fail(limit, what + " lower='" + limit->Attribute("lower") + "' is above upper='" +
                      limit->Attribute("upper") + "'; write lower <= upper");
    }
    // urdfdom rejects a <limit> without these two; say so with the line. 0 is what files
    // write for "unknown"; below 0 is no limit at all.
    for (const char* attribute : {"velocity", "effort"}) {
      if ((*numbers(limit, attribute, 1, what, true))[0] < 0) {
        fail(limit, what + " " + attribute + "='" + limit->Attribute(attribute) +
                        "' is negative; give the largest magnitude (or 0 when unknown)");
      }
    }
  } else if (entry.type == "revolute" || entry.type == "prismatic") {
    fail(joint, owner + " is " + entry.type +
                    " but has no <limit lower=... upper=... velocity=... effort=.../>; URDF "
                    "requires one (use type 'continuous' for an unlimited revolute joint)");
  }
}

}  // namespace modelgen
