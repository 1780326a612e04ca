// The structure of a URDF as TinyXML2 reads it, checked with line numbers before urdfdom reads
// the values: names, file order and lines of links and joints, the tree they form. Private to
// the URDF loader.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/model/robot_model.hpp"

namespace modelgen {

// What the TinyXML2 pass keeps: names, file order and lines. urdfdom keeps joints in a map
// sorted by name, so the deterministic child order (file order) must come from here.
// An <origin> as written (urdfdom keeps only the quaternion, so rounded quarter turns in rpy
// can only be recognised here).
struct OriginEntry {
  std::array<double, 3> xyz{0, 0, 0};
  std::array<double, 3> rpy{0, 0, 0};
  int line = 0;  // 0 when the element has no <origin>
};

struct LinkEntry {
  std::string name;
  int line = 0;
  OriginEntry inertial_origin;  // of its <inertial>, if any
  double mass = 0;              // of its <inertial>, 0 if none
  double inertia_trace = 0;     // ixx + iyy + izz of its <inertia>, 0 if none
  int inertia_line = 0;         // line of its <inertia>, 0 if none
};

struct JointEntry {
  std::string name;
  std::string type;
  std::string parent;
  std::string child;
  int line = 0;
  bool has_lower = false;  // <limit lower=...> written; urdfdom reads a missing one as 0
  bool has_upper = false;
  OriginEntry origin;
  std::optional<std::array<double, 3>> axis;  // <axis xyz> of a moving joint, as written
  int axis_line = 0;
  std::string mimic_leader;  // <mimic joint=...>: the joint this one follows, empty if none
  int mimic_line = 0;
};

struct UrdfStructure {
  std::string robot_name;
  int robot_line = 0;
  std::vector<LinkEntry> links;
  std::map<std::string, int> link_index;
  std::vector<JointEntry> joints;
  std::vector<int> parent_joint;               // per link: index into joints, -1 for a root
  std::vector<std::vector<int>> child_joints;  // per link: indices into joints, file order
  std::vector<DescriptionNote> notes;          // likely unit slips (magnitude_checks.hpp)
};

inline bool is_moving(const std::string& type) {
  return type == "revolute" || type == "continuous" || type == "prismatic";
}

/// Parses `text` with TinyXML2 and checks what urdfdom would only print on the console or
/// accept silently: well-formed XML, a <robot>, link and joint names, numbers, parents and
/// children that exist, one tree without cycles. Throws InputError at the line of the problem.
UrdfStructure check_urdf_structure(const std::string& path, const std::string& text);

}  // namespace modelgen
