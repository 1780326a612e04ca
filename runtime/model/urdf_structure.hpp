// The structure of a URDF as TinyXML2 reads it, checked with line numbers before urdfdom reads
// the values: names, file order and lines of links and joints, the tree they form. Private to
// the URDF loader.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace modelgen {

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

inline bool is_moving(const std::string& type) {
  return type == "revolute" || type == "continuous" || type == "prismatic";
}

/// Parses `text` with TinyXML2 and checks what urdfdom would only print on the console or
/// accept silently: well-formed XML, a <robot>, link and joint names, numbers, parents and
/// children that exist, one tree without cycles. Throws InputError at the line of the problem.
UrdfStructure check_urdf_structure(const std::string& path, const std::string& text);

}  // namespace modelgen
