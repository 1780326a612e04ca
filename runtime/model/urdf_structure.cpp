// The TinyXML2 pass of the URDF loader: structure and numbers checked with line numbers (the
// checks of single elements are in urdf_xml_checks.cpp).

#include "runtime/model/urdf_structure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tinyxml2.h>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/error.hpp"
#include "runtime/model/magnitude_checks.hpp"
#include "runtime/model/urdf_xml_checks.hpp"

namespace modelgen {

namespace {

class StructureChecker : private UrdfElementChecker {
 public:
  explicit StructureChecker(const std::string& path) : UrdfElementChecker(path) {}

  UrdfStructure check(const std::string& text) {
    tinyxml2::XMLDocument document;
    document.Parse(text.data(), text.size());
    if (document.Error()) {
      throw InputError({path(), document.ErrorLineNum(), 0},
                       "malformed XML: " + xml_error(document));
    }
    const tinyxml2::XMLElement* robot = document.RootElement();
    if (robot == nullptr) throw InputError({path()}, "malformed XML: the file holds no element");
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
    check_inertia_sizes();
    return std::move(structure_);
  }

 private:
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
    check_mass({path(), mass->GetLineNum(), 0}, owner + ": mass value", (*m)[0], structure_.notes);
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
    LinkEntry& entry = structure_.links.back();
    entry.mass = (*m)[0];
    entry.inertia_trace = I[0] + I[3] + I[5];
    entry.inertia_line = inertia->GetLineNum();
  }

  // Inertias too large for the link's size (magnitude_checks.hpp): the size is what the file
  // says of it, the farthest child joint or centre of mass from the link frame (meshes are not
  // read).
  void check_inertia_sizes() {
    const auto norm = [](const std::array<double, 3>& v) {
      return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    };
    for (std::size_t l = 0; l < structure_.links.size(); ++l) {
      const LinkEntry& link = structure_.links[l];
      if (link.inertia_line == 0) continue;
      double size = norm(link.inertial_origin.xyz);
      for (const int j : structure_.child_joints[l]) {
        size = std::max(size, norm(structure_.joints[j].origin.xyz));
      }
      check_inertia_size({path(), link.inertia_line, 0}, "link '" + link.name + "'", link.mass,
                         link.inertia_trace, size, structure_.notes);
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

  // Revolute limits in degrees or deg/s load without error; flagged (magnitude_checks.hpp).
  // check_joint_limit has read the numbers already.
  void check_limit_magnitudes(const tinyxml2::XMLElement* limit, const std::string& owner,
                              const std::string& type) {
    if (limit == nullptr || (type != "revolute" && type != "continuous")) return;
    const SourceLocation where{path(), limit->GetLineNum(), 0};
    if (type == "revolute") {
      for (const char* side : {"lower", "upper"}) {
        if (limit->Attribute(side) != nullptr) {
          check_angle_limit(where, owner + ": limit " + side, limit->DoubleAttribute(side),
                            structure_.notes);
        }
      }
    }
    check_velocity_limit(where, owner + ": limit velocity", limit->DoubleAttribute("velocity"),
                         structure_.notes);
  }

  // Vendor files carry a joint with two <origin> (FloBaRoID's kuka_lwr4.urdf, line 55, a
  // placement left over from an edit). urdfdom, and so every ROS tool, uses the first and
  // ignores the rest; so does modelgen, with a warning naming both lines, so the model is the
  // one the user sees in RViz and the leftover is not missed.
  void note_second_origin(const tinyxml2::XMLElement* joint, const std::string& owner) {
    const tinyxml2::XMLElement* first = joint->FirstChildElement("origin");
    if (first == nullptr) return;
    for (const tinyxml2::XMLElement* other = first->NextSiblingElement("origin"); other != nullptr;
         other = other->NextSiblingElement("origin")) {
      structure_.notes.push_back(
          {{path(), other->GetLineNum(), 0},
           owner + " has a second <origin>; the first (line " +
               std::to_string(first->GetLineNum()) +
               ") is used and this one ignored, as urdfdom and ROS do; delete the one you did "
               "not mean",
           true});
    }
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

    for (const char* element : {"parent", "child", "axis", "limit", "mimic"}) {
      check_single(joint, element, owner);
    }
    note_second_origin(joint, owner);
    link_reference(joint, owner, "parent", entry.parent);
    link_reference(joint, owner, "child", entry.child);
    entry.origin = check_origin(joint, owner + ": origin");
    check_joint_axis(joint, owner, entry);
    check_joint_limit(joint, owner, entry);
    check_limit_magnitudes(joint->FirstChildElement("limit"), owner, entry.type);
    if (const tinyxml2::XMLElement* mimic = joint->FirstChildElement("mimic")) {
      const char* leader = mimic->Attribute("joint");
      if (leader == nullptr || *leader == '\0') {
        fail(mimic, owner + ": <mimic> has no joint attribute naming the joint it follows");
      }
      entry.mimic_leader = leader;
      entry.mimic_line = mimic->GetLineNum();
    }
    return entry;
  }

  void link_joint(JointEntry entry) {
    const int index = static_cast<int>(structure_.joints.size());
    const int child = structure_.link_index.at(entry.child);
    const int parent = structure_.link_index.at(entry.parent);
    if (const int other = structure_.parent_joint[child]; other != -1) {
      const JointEntry& first = structure_.joints[other];
      throw InputError({path(), entry.line, 0},
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
      throw InputError({path(), b.line, 0},
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
    throw InputError({path(), structure_.joints[cycle.front()].line, 0},
                     "joints " + names + " form a cycle; URDF describes trees only");
  }

  UrdfStructure structure_;
  std::vector<std::string> link_names_;
};

}  // namespace

UrdfStructure check_urdf_structure(const std::string& path, const std::string& text) {
  return StructureChecker(path).check(text);
}

}  // namespace modelgen
