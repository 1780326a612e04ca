// Checks of single URDF elements with their line numbers, for the TinyXML2 pass of the URDF
// loader (urdf_structure.cpp). Private to the URDF loader.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "runtime/model/urdf_structure.hpp"

namespace modelgen {

/// TinyXML2's error in `document`, in words (its error names are its enum identifiers).
std::string xml_error(const tinyxml2::XMLDocument& document);

/// Throws InputError at the line of the element that does not check, in the file `path`.
class UrdfElementChecker {
 public:
  explicit UrdfElementChecker(const std::string& path) : path_(path) {}

  [[noreturn]] void fail(const tinyxml2::XMLElement* element, const std::string& message) const;
  std::optional<std::vector<double>> numbers(const tinyxml2::XMLElement* element,
                                             const char* attribute, std::size_t count,
                                             const std::string& what, bool required,
                                             double limit = 0, const char* unit = "") const;
  void check_single(const tinyxml2::XMLElement* parent, const char* element,
                    const std::string& owner) const;
  void check_geometry_owner(const tinyxml2::XMLElement* element, const std::string& owner) const;
  OriginEntry check_origin(const tinyxml2::XMLElement* parent, const std::string& what) const;
  void check_inertia(const tinyxml2::XMLElement* inertia, const std::string& owner,
                     const std::array<double, 6>& I) const;
  void check_joint_axis(const tinyxml2::XMLElement* joint, const std::string& owner,
                        JointEntry& entry) const;
  void check_joint_limit(const tinyxml2::XMLElement* joint, const std::string& owner,
                         JointEntry& entry) const;

  const std::string& path() const { return path_; }

 private:
  const std::string& path_;
};

}  // namespace modelgen
