// modelid export for a URDF: the input URDF with the identified <inertial> of each link, the
// rest of the file kept (through an XML tree: elements, attributes and comments survive, the
// indentation is the printer's).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

struct UrdfExport {
  std::string text;                   ///< the identified URDF
  std::vector<std::string> warnings;  ///< "FILE:LINE: warning: ..." lines for standard error
};

/// The URDF `text` (read from `path`, loaded as `description` with `options`) with the
/// inertials of `standard` (one value per description parameter, physically consistent).
///
/// The loader made one body of each moving joint's child link and of the links fixed below it,
/// in that link's frame. Export undoes it: the fixed links keep their a-priori <inertial>, and
/// the moving link gets the identified body less them, as mass, centre of mass and inertia
/// about it in the frame of its inertial origin's rpy (kept; "0 0 0" for a new <inertial>).
/// When the identified body less the fixed links is no physical body (the data say the body is
/// lighter than its fixed links were thought to be), the moving link takes the whole body and
/// the fixed links' <inertial>s are removed, with a warning naming them. Drive parameters,
/// which URDF has no element for, are listed in a comment at the top of <robot>, `note` first.
UrdfExport identified_urdf(const std::string& path, const std::string& text,
                           const RobotModel& description, const Eigen::VectorXd& standard,
                           const LoadOptions& options, const std::string& note);

}  // namespace modelgen
