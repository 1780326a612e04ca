// The TinyXML2 pass of the URDF loader: structure and numbers checked with line numbers.

#include "runtime/model/urdf_structure.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <utility>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <tinyxml2.h>

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

class StructureChecker {
 public:
  explicit StructureChecker(const std::string& path) : path_(path) {}

  UrdfStructure check(const std::string& text) {
    tinyxml2::XMLDocument document;
    document.Parse(text.data(), text.size());
    if (document.Error()) {
      throw InputError({path_, document.ErrorLineNum(), 0},
                       "malformed XML: " + xml_error(document));
    }
    const tinyxml2::XMLElement* robot = document.RootElement();
    if (robot == nullptr) throw InputError({path_}, "malformed XML: the file holds no element");
    if (std::string_view(robot->Name()) != "robot") {
      fail(robot, "the root element is <" + std::string(robot->Name()) +
                      ">, but a URDF file starts with <robot name=\"...\">");
    }
    const char* robot_name = robot->Attribute("name");
    if (robot_name == nullptr || *robot_name == '\0') {
      fail(robot, "<robot> has no name attribute");
    }
    structure_.robot_name = robot_name;
    structure_.robot_line = robot->GetLineNum();

    // Links first: joints may name links written further down the file.
    for (const tinyxml2::XMLElement* link = robot->FirstChildElement("link"); link != nullptr;
         link = link->NextSiblingElement("link")) {
      if (structure_.links.size() == static_cast<std::size_t>(kMaxUrdfLinks)) {
        fail(link, "more than " + std::to_string(kMaxUrdfLinks) +
                       " links; a URDF may hold at most that many (README, Limits)");
      }
      check_link(link);
    }
    if (structure_.links.empty()) fail(robot, "the robot has no <link> elements");
    for (const auto& entry : structure_.links) link_names_.push_back(entry.name);
    structure_.parent_joint.assign(structure_.links.size(), -1);
    structure_.child_joints.assign(structure_.links.size(), {});

    std::map<std::string, int> joint_lines;
    for (const tinyxml2::XMLElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
         joint = joint->NextSiblingElement("joint")) {
      JointEntry entry = check_joint(joint);
      const auto [previous, inserted] = joint_lines.emplace(entry.name, entry.line);
      if (!inserted) {
        fail(joint, "joint '" + entry.name + "' is defined twice (first at line " +
                        std::to_string(previous->second) + ")");
      }
      link_joint(std::move(entry));
    }
    check_tree();
    return std::move(structure_);
  }

 private:
  [[noreturn]] void fail(const tinyxml2::XMLElement* element, const std::string& message) const {
    throw InputError({path_, element->GetLineNum(), 0}, message);
  }

  // TinyXML2's error names are its enum identifiers; say the same in words.
  static std::string xml_error(const tinyxml2::XMLDocument& document) {
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

  // Checks that `attribute` of `element` holds `count` numbers; `what` names the owner and the
  // element for the message ("joint 'j1': origin"). Returns the numbers, nullopt if absent.
  std::optional<std::vector<double>> numbers(const tinyxml2::XMLElement* element,
                                             const char* attribute, std::size_t count,
                                             const std::string& what, bool required,
                                             double limit = 0, const char* unit = "") const {
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
  void check_single(const tinyxml2::XMLElement* parent, const char* element,
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
  void check_geometry_owner(const tinyxml2::XMLElement* element, const std::string& owner) const {
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

  OriginEntry check_origin(const tinyxml2::XMLElement* parent, const std::string& what) const {
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

  void check_link(const tinyxml2::XMLElement* link) {
    const char* name = link->Attribute("name");
    if (name == nullptr || *name == '\0') fail(link, "<link> has no name attribute");
    const std::string owner = "link '" + std::string(name) + "'";
    const auto [previous, inserted] =
        structure_.link_index.emplace(name, static_cast<int>(structure_.links.size()));
    if (!inserted) {
      fail(link, owner + " is defined twice (first at line " +
                     std::to_string(structure_.links[previous->second].line) + ")");
    }
    structure_.links.push_back({name, link->GetLineNum(), {}});
    check_single(link, "inertial", owner);
    for (const char* kind : {"visual", "collision"}) {
      for (const tinyxml2::XMLElement* element = link->FirstChildElement(kind); element != nullptr;
           element = element->NextSiblingElement(kind)) {
        check_geometry_owner(element, owner);
      }
    }

    const tinyxml2::XMLElement* inertial = link->FirstChildElement("inertial");
    if (inertial == nullptr) return;
    for (const char* element : {"origin", "mass", "inertia"}) {
      check_single(inertial, element, owner + ": <inertial>");
    }
    structure_.links.back().inertial_origin = check_origin(inertial, owner + ": inertial origin");
    const tinyxml2::XMLElement* mass = inertial->FirstChildElement("mass");
    if (mass == nullptr) fail(inertial, owner + ": <inertial> has no <mass value=\"...\"/>");
    const auto m = numbers(mass, "value", 1, owner + ": mass", true, kMaxMass, " kg");
    if ((*m)[0] < 0) {
      fail(mass, owner + ": mass value='" + mass->Attribute("value") + "' is negative");
    }
    const tinyxml2::XMLElement* inertia = inertial->FirstChildElement("inertia");
    if (inertia == nullptr) {
      fail(inertial, owner +
                         ": <inertial> has no <inertia ixx=... ixy=... ixz=... iyy=... "
                         "iyz=... izz=.../>");
    }
    std::array<double, 6> I{};  // ixx ixy ixz iyy iyz izz
    int k = 0;
    for (const char* entry : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
      I[k++] = (*numbers(inertia, entry, 1, owner + ": inertia", true, kMaxMagnitude))[0];
    }
    check_inertia(inertia, owner, I);
  }

  // The inertia about the centre of mass must be positive semi-definite (a body whose mass is
  // all in one point has zero inertia, which URDFs write); anything else has no mass
  // distribution and makes every "physically consistent" check downstream meaningless.
  void check_inertia(const tinyxml2::XMLElement* inertia, const std::string& owner,
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
    const Eigen::Vector3d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                                            J, Eigen::EigenvaluesOnly).eigenvalues();
    if (eigenvalues.minCoeff() < -1e-9 * scale) {
      char text[96];
      std::snprintf(text, sizeof text, "%.6g, %.6g, %.6g", eigenvalues[0], eigenvalues[1],
                    eigenvalues[2]);
      fail(inertia, owner + ": the inertia tensor is not positive semi-definite (principal " +
                        "moments " + text + "): no mass distribution has it");
    }
  }

  const tinyxml2::XMLElement* link_reference(const tinyxml2::XMLElement* joint,
                                             const std::string& owner, const char* role,
                                             std::string& name) const {
    const tinyxml2::XMLElement* element = joint->FirstChildElement(role);
    const char* link = element ? element->Attribute("link") : nullptr;
    if (link == nullptr || *link == '\0') {
      fail(element ? element : joint,
           owner + " has no <" + role + " link=\"...\"/> naming its " + role + " link");
    }
    name = link;
    if (!structure_.link_index.count(name)) {
      fail(element, owner + ": " + role + " link '" + name + "' is not defined" +
                        did_you_mean(name, link_names_));
    }
    return element;
  }

  JointEntry check_joint(const tinyxml2::XMLElement* joint) {
    JointEntry entry;
    entry.line = joint->GetLineNum();
    const char* name = joint->Attribute("name");
    if (name == nullptr || *name == '\0') fail(joint, "<joint> has no name attribute");
    entry.name = name;
    const std::string owner = "joint '" + entry.name + "'";

    const char* type = joint->Attribute("type");
    if (type == nullptr) {
      fail(joint, owner + " has no type attribute (revolute, continuous, prismatic or fixed)");
    }
    entry.type = type;
    if (entry.type == "floating" || entry.type == "planar") {
      fail(joint, owner + ": joint type '" + entry.type +
                      "' is not supported; modelgen models fixed-base robots with revolute, "
                      "continuous, prismatic and fixed joints");
    }
    if (!is_moving(entry.type) && entry.type != "fixed") {
      fail(joint, owner + ": unknown joint type '" + entry.type + "'" +
                      did_you_mean(entry.type, {"revolute", "continuous", "prismatic", "fixed"}) +
                      "; expected revolute, continuous, prismatic or fixed");
    }

    for (const char* element : {"parent", "child", "origin", "axis", "limit"}) {
      check_single(joint, element, owner);
    }
    link_reference(joint, owner, "parent", entry.parent);
    link_reference(joint, owner, "child", entry.child);
    entry.origin = check_origin(joint, owner + ": origin");

    // urdfdom reads the axis of moving joints only; a fixed joint's axis means nothing.
    if (const tinyxml2::XMLElement* axis = joint->FirstChildElement("axis");
        axis != nullptr && is_moving(entry.type)) {
      const auto xyz = numbers(axis, "xyz", 3, owner + ": axis", false, kMaxMagnitude);
      if (xyz && (*xyz)[0] == 0 && (*xyz)[1] == 0 && (*xyz)[2] == 0) {
        fail(axis, owner + ": axis xyz='" + axis->Attribute("xyz") +
                       "' is the zero vector; give the direction of motion");
      }
      // Scaled before squaring, so that the norm of 1e-200 does not underflow to 0 here.
      if (xyz) {
        const double scale = std::max({std::abs((*xyz)[0]), std::abs((*xyz)[1]), std::abs((*xyz)[2])});
        const double norm = scale * std::hypot((*xyz)[0] / scale, (*xyz)[1] / scale, (*xyz)[2] / scale);
        if (norm < kMinAxisNorm) {
          fail(axis, owner + ": axis xyz='" + axis->Attribute("xyz") + "' has norm " +
                         shortest_text(norm) + ", below the limit of " +
                         shortest_text(kMinAxisNorm) + " (README, Limits); write a unit vector");
        }
      }
      if (xyz) {
        entry.axis = std::array<double, 3>{(*xyz)[0], (*xyz)[1], (*xyz)[2]};
        entry.axis_line = axis->GetLineNum();
      }
    }

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
    return entry;
  }

  void link_joint(JointEntry entry) {
    const int index = static_cast<int>(structure_.joints.size());
    const int child = structure_.link_index.at(entry.child);
    const int parent = structure_.link_index.at(entry.parent);
    if (const int other = structure_.parent_joint[child]; other != -1) {
      const JointEntry& first = structure_.joints[other];
      throw InputError({path_, entry.line, 0},
                       "closed loop: link '" + entry.child + "' is the child of joints '" +
                           first.name + "' (line " + std::to_string(first.line) + ") and '" +
                           entry.name + "' (line " + std::to_string(entry.line) +
                           "); URDF describes trees only");
    }
    structure_.parent_joint[child] = index;
    structure_.child_joints[parent].push_back(index);
    structure_.joints.push_back(std::move(entry));
  }

  // Every link has at most one parent joint by now, so a link that no root reaches sits on or
  // under a cycle; walking up its parents finds that cycle.
  void check_tree() const {
    const std::size_t n = structure_.links.size();
    std::vector<bool> reached(n, false);
    std::vector<int> roots;
    std::vector<int> stack;
    for (std::size_t l = 0; l < n; ++l) {
      if (structure_.parent_joint[l] == -1) {
        roots.push_back(static_cast<int>(l));
        stack.push_back(static_cast<int>(l));
      }
    }
    while (!stack.empty()) {
      const int link = stack.back();
      stack.pop_back();
      reached[link] = true;
      for (int j : structure_.child_joints[link]) {
        stack.push_back(structure_.link_index.at(structure_.joints[j].child));
      }
    }
    for (std::size_t l = 0; l < n; ++l) {
      if (!reached[l]) report_cycle(static_cast<int>(l));
    }
    if (roots.size() > 1) {
      const LinkEntry& a = structure_.links[roots[0]];
      const LinkEntry& b = structure_.links[roots[1]];
      throw InputError({path_, b.line, 0},
                       "links '" + a.name + "' (line " + std::to_string(a.line) + ") and '" +
                           b.name + "' (line " + std::to_string(b.line) +
                           ") both have no parent joint; a URDF tree has exactly one root link");
    }
  }

  [[noreturn]] void report_cycle(int start) const {
    std::vector<bool> seen(structure_.links.size(), false);
    int link = start;
    while (!seen[link]) {
      seen[link] = true;
      link = structure_.link_index.at(structure_.joints[structure_.parent_joint[link]].parent);
    }
    // `link` is on the cycle: go round once more, collecting the joints.
    std::vector<int> cycle;
    const int first = link;
    do {
      const int joint = structure_.parent_joint[link];
      cycle.push_back(joint);
      link = structure_.link_index.at(structure_.joints[joint].parent);
    } while (link != first);
    std::sort(cycle.begin(), cycle.end());  // file order, so the message reads top-down
    std::string names;
    for (int j : cycle) {
      const JointEntry& joint = structure_.joints[j];
      names += (names.empty() ? "'" : ", '") + joint.name + "' (line " +
               std::to_string(joint.line) + ")";
    }
    throw InputError({path_, structure_.joints[cycle.front()].line, 0},
                     "joints " + names + " form a cycle; URDF describes trees only");
  }

  const std::string& path_;
  UrdfStructure structure_;
  std::vector<std::string> link_names_;
};

}  // namespace

UrdfStructure check_urdf_structure(const std::string& path, const std::string& text) {
  return StructureChecker(path).check(text);
}

}  // namespace modelgen
