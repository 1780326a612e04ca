// Loads a URDF into a RobotModel. A TinyXML2 pass checks structure and numbers first, because
// urdfdom forgets line numbers and reports problems only on the console; urdfdom then supplies
// the values. Each moving joint becomes a body; fixed joints fold into the transforms of the
// moving joints below them and merge their link's inertia into the nearest moving ancestor.

#include "generator/description/urdf_loader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <exception>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include "generator/description/diagnostics.hpp"
#include "generator/description/robot_model.hpp"
#include "modelgen/rigid_body_tree.hpp"

namespace modelgen::gen {

namespace {

// What the TinyXML2 pass keeps: names, file order and lines. urdfdom keeps joints in a map
// sorted by name, so the deterministic child order (file order) must come from here.
struct LinkEntry {
  std::string name;
  int line = 0;
};

struct JointEntry {
  std::string name;
  std::string type;
  std::string parent;
  std::string child;
  int line = 0;
  bool has_lower = false;  // <limit lower=...> written; urdfdom reads a missing one as 0
  bool has_upper = false;
};

struct UrdfStructure {
  std::string robot_name;
  int robot_line = 0;
  std::vector<LinkEntry> links;
  std::map<std::string, int> link_index;
  std::vector<JointEntry> joints;
  std::vector<int> parent_joint;               // per link: index into joints, -1 for a root
  std::vector<std::vector<int>> child_joints;  // per link: indices into joints, file order
};

bool is_moving(const std::string& type) {
  return type == "revolute" || type == "continuous" || type == "prismatic";
}

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
                                             const std::string& what, bool required) const {
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
    return values;
  }

  void check_origin(const tinyxml2::XMLElement* parent, const std::string& what) const {
    const tinyxml2::XMLElement* origin = parent->FirstChildElement("origin");
    if (origin == nullptr) return;
    numbers(origin, "xyz", 3, what, false);
    numbers(origin, "rpy", 3, what, false);
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
    structure_.links.push_back({name, link->GetLineNum()});

    const tinyxml2::XMLElement* inertial = link->FirstChildElement("inertial");
    if (inertial == nullptr) return;
    check_origin(inertial, owner + ": inertial origin");
    const tinyxml2::XMLElement* mass = inertial->FirstChildElement("mass");
    if (mass == nullptr) fail(inertial, owner + ": <inertial> has no <mass value=\"...\"/>");
    const auto m = numbers(mass, "value", 1, owner + ": mass", true);
    if ((*m)[0] < 0) {
      fail(mass, owner + ": mass value='" + mass->Attribute("value") + "' is negative");
    }
    const tinyxml2::XMLElement* inertia = inertial->FirstChildElement("inertia");
    if (inertia == nullptr) {
      fail(inertial, owner +
                         ": <inertial> has no <inertia ixx=... ixy=... ixz=... iyy=... "
                         "iyz=... izz=.../>");
    }
    for (const char* entry : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
      numbers(inertia, entry, 1, owner + ": inertia", true);
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

    link_reference(joint, owner, "parent", entry.parent);
    link_reference(joint, owner, "child", entry.child);
    check_origin(joint, owner + ": origin");

    // urdfdom reads the axis of moving joints only; a fixed joint's axis means nothing.
    if (const tinyxml2::XMLElement* axis = joint->FirstChildElement("axis");
        axis != nullptr && is_moving(entry.type)) {
      const auto xyz = numbers(axis, "xyz", 3, owner + ": axis", false);
      if (xyz && (*xyz)[0] == 0 && (*xyz)[1] == 0 && (*xyz)[2] == 0) {
        fail(axis, owner + ": axis xyz='" + axis->Attribute("xyz") +
                       "' is the zero vector; give the direction of motion");
      }
    }

    const tinyxml2::XMLElement* limit = joint->FirstChildElement("limit");
    if (limit != nullptr) {
      const std::string what = owner + ": limit";
      entry.has_lower = numbers(limit, "lower", 1, what, false).has_value();
      entry.has_upper = numbers(limit, "upper", 1, what, false).has_value();
      // urdfdom rejects a <limit> without these two; say so with the line.
      numbers(limit, "velocity", 1, what, true);
      numbers(limit, "effort", 1, what, true);
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

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  q.normalize();
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = q.toRotationMatrix();
  transform.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return transform;
}

// URDFs write quarter turns with a rounded pi ("1.5707963267949"), which leaves entries such as
// 4.9e-12 where the robot has an exact zero. A rotation whose entries are all within 1e-9 of
// 0 or +-1 is such a signed permutation and is snapped to it exactly (still orthonormal), so the
// symbolic models fold those zeros and ones away; likewise translations below 1e-12 m.
Frame to_frame(const Eigen::Isometry3d& transform) {
  Frame frame;
  bool quarter_turn = true;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double entry = transform.linear()(i, j);
      frame.rotation[3 * i + j] = entry;
      const double nearest = std::round(entry);
      if (std::abs(entry - nearest) > 1e-9) quarter_turn = false;
    }
    const double t = transform.translation()(i);
    frame.translation[i] = std::abs(t) < 1e-12 ? 0.0 : t;
  }
  if (quarter_turn) {
    for (double& entry : frame.rotation) entry = std::round(entry) + 0.0;  // + 0.0: no -0
  }
  return frame;
}

// Position of an inertial parameter in standard_from_inertial's result, -1 for drive ones.
int inertial_slot(ParamKind kind) {
  switch (kind) {
    case ParamKind::kXX:
      return 0;
    case ParamKind::kXY:
      return 1;
    case ParamKind::kXZ:
      return 2;
    case ParamKind::kYY:
      return 3;
    case ParamKind::kYZ:
      return 4;
    case ParamKind::kZZ:
      return 5;
    case ParamKind::kMX:
      return 6;
    case ParamKind::kMY:
      return 7;
    case ParamKind::kMZ:
      return 8;
    case ParamKind::kM:
      return 9;
    default:
      return -1;
  }
}

// Walks the kinematic tree depth first from the base, making a body per moving joint.
class TreeBuilder {
 public:
  TreeBuilder(const std::string& path, const UrdfStructure& structure,
              const urdf::ModelInterface& urdf, const std::set<int>* kept_joints, RobotModel& model)
      : path_(path), structure_(structure), urdf_(urdf), kept_joints_(kept_joints), model_(model) {}

  void build(int base_link) { visit(base_link, -1, Eigen::Isometry3d::Identity()); }

  // The summed inertial parameters per body; nullopt for bodies none of whose links has an
  // <inertial>, so an absent inertial stays unknown rather than becoming zero.
  const std::vector<std::optional<std::array<double, 10>>>& inertials() const { return inertials_; }

 private:
  const urdf::Joint& joint(const JointEntry& entry) const {
    const urdf::JointConstSharedPtr joint = urdf_.getJoint(entry.name);
    if (!joint) throw std::logic_error("urdfdom lost joint '" + entry.name + "'");
    return *joint;
  }

  // Adds the link's inertial, the link frame being at `body_from_link` in the body frame.
  void add_inertial(const std::string& link_name, int body,
                    const Eigen::Isometry3d& body_from_link) {
    const urdf::LinkConstSharedPtr link = urdf_.getLink(link_name);
    if (!link) throw std::logic_error("urdfdom lost link '" + link_name + "'");
    if (!link->inertial) return;
    const urdf::Inertial& in = *link->inertial;
    const Eigen::Isometry3d body_from_inertial = body_from_link * to_isometry(in.origin);
    const Frame frame = to_frame(body_from_inertial);
    const std::array<double, 10> values =
        standard_from_inertial(in.mass, frame.translation, frame.rotation,
                               {in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz});
    auto& sum = inertials_[body];
    if (!sum) sum.emplace();
    // All ten are linear in the mass distribution, so merged links simply add up.
    for (std::size_t k = 0; k < values.size(); ++k) (*sum)[k] += values[k];
  }

  void visit(int link, int body, const Eigen::Isometry3d& body_from_link) {
    for (int j : structure_.child_joints[link]) {
      if (kept_joints_ != nullptr && !kept_joints_->count(j)) continue;
      const JointEntry& entry = structure_.joints[j];
      const urdf::Joint& urdf_joint = joint(entry);
      const int child = structure_.link_index.at(entry.child);
      // A URDF joint frame is its child link's frame; at q = 0 it sits at <origin>.
      const Eigen::Isometry3d body_from_child =
          body_from_link * to_isometry(urdf_joint.parent_to_joint_origin_transform);
      if (!is_moving(entry.type)) {
        // Mass fixed to the base never moves, so it has no effect on the dynamics.
        if (body >= 0) add_inertial(entry.child, body, body_from_child);
        visit(child, body, body_from_child);
        continue;
      }
      Body made;
      made.name = entry.child;
      made.parent = body;
      made.type = entry.type == "prismatic" ? JointType::kPrismatic : JointType::kRevolute;
      made.dof_index = model_.tree.dof++;
      made.fixed = to_frame(body_from_child);
      const Eigen::Vector3d axis =
          Eigen::Vector3d(urdf_joint.axis.x, urdf_joint.axis.y, urdf_joint.axis.z).normalized();
      made.axis = {axis.x(), axis.y(), axis.z()};

      JointDescription description;
      description.name = entry.name;
      description.parent_link = entry.parent;
      description.where = {path_, entry.line, 0};
      if (urdf_joint.limits) {
        const urdf::JointLimits& limits = *urdf_joint.limits;
        if (entry.type != "continuous") {
          if (entry.has_lower) description.limits.q_lower = limits.lower;
          if (entry.has_upper) description.limits.q_upper = limits.upper;
        }
        // URDF makes velocity and effort mandatory, so files write 0 where the value is
        // unknown (the KR150 URDF does); only a positive value limits anything.
        if (limits.velocity > 0) description.limits.dq = limits.velocity;
        if (limits.effort > 0) description.limits.effort = limits.effort;
      }

      const int index = static_cast<int>(model_.tree.bodies.size());
      model_.tree.bodies.push_back(std::move(made));
      model_.joints.push_back(std::move(description));
      inertials_.emplace_back();
      add_inertial(entry.child, index, Eigen::Isometry3d::Identity());
      visit(child, index, Eigen::Isometry3d::Identity());
    }
  }

  const std::string& path_;
  const UrdfStructure& structure_;
  const urdf::ModelInterface& urdf_;
  const std::set<int>* kept_joints_;
  RobotModel& model_;
  std::vector<std::optional<std::array<double, 10>>> inertials_;
};

int link_option(const std::string& path, const UrdfStructure& structure, const std::string& name,
                const char* role, const char* option) {
  const auto it = structure.link_index.find(name);
  if (it == structure.link_index.end()) {
    std::vector<std::string> names;
    for (const LinkEntry& link : structure.links) names.push_back(link.name);
    throw InputError({path}, std::string(role) + " link '" + name + "' (" + option +
                                 ") is not a link of this URDF" + did_you_mean(name, names));
  }
  return it->second;
}

}  // namespace

RobotModel load_urdf(const std::string& path, const std::string& text, const LoadOptions& options) {
  const UrdfStructure structure = StructureChecker(path).check(text);

  urdf::ModelInterfaceSharedPtr urdf;
  try {
    urdf = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    throw InputError({path}, std::string("urdfdom rejected the file: ") + e.what());
  }
  if (!urdf) {
    throw InputError({path},
                     "urdfdom rejected the file: see its messages above (the checks "
                     "with line numbers found nothing wrong)");
  }

  RobotModel model;
  model.format = DescriptionFormat::kUrdf;
  model.source_file = path;
  if (!options.name.empty()) {
    check_robot_name(options.name, {path});
    model.name = options.name;
  } else {
    try {
      check_robot_name(structure.robot_name, {path, structure.robot_line, 0});
    } catch (const InputError& e) {
      throw InputError(e.where(), e.message() + "; choose another name with --name");
    }
    model.name = structure.robot_name;
  }

  int base = -1;
  if (!options.base_link.empty()) {
    base = link_option(path, structure, options.base_link, "base", "--base");
  } else {
    for (std::size_t l = 0; l < structure.links.size() && base == -1; ++l) {
      if (structure.parent_joint[l] == -1) base = static_cast<int>(l);
    }
  }
  const std::string& base_name = structure.links[base].name;

  std::optional<std::set<int>> path_joints;
  if (!options.tip_link.empty()) {
    const int tip = link_option(path, structure, options.tip_link, "tip", "--tip");
    path_joints.emplace();
    int link = tip;
    while (link != base) {
      const int joint = structure.parent_joint[link];
      if (joint == -1) {
        throw InputError({path}, "no path from base link '" + base_name + "' to tip link '" +
                                     options.tip_link + "': the tip is not below the base");
      }
      path_joints->insert(joint);
      link = structure.link_index.at(structure.joints[joint].parent);
    }
  }

  TreeBuilder builder(path, structure, *urdf, path_joints ? &*path_joints : nullptr, model);
  builder.build(base);
  if (model.tree.dof == 0) {
    throw InputError({path}, "no moving joint below base link '" + base_name +
                                 (options.tip_link.empty()
                                      ? "'"
                                      : "' on the way to tip link '" + options.tip_link + "'") +
                                 "; nothing to identify");
  }

  // No drive ratios in URDF: motor and joint sides coincide.
  model.drives.motor_from_joint = Eigen::MatrixXd::Identity(model.tree.dof, model.tree.dof);
  model.drives.torque_constant.assign(model.tree.dof, 0.0);
  model.drives.joint_offset.assign(model.tree.dof, 0.0);
  build_standard_parameters(model);
  for (std::size_t k = 0; k < model.tree.params.size(); ++k) {
    const StandardParam& param = model.tree.params[k];
    const int slot = inertial_slot(param.kind);
    const auto& inertial = builder.inertials()[param.body];
    if (slot >= 0 && inertial) model.known_values[k] = (*inertial)[slot];
  }

  validate(model.tree);
  return model;
}

}  // namespace modelgen::gen
