// Entry point for reading any robot description: picks the loader from the file extension; and
// the raw bytes of a description, for its SHA-256.
#pragma once

#include <string>

#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// Default of LoadOptions::angle_tolerance: URDFs round pi/2 to 1.5708 (3.7e-6 rad off) or
/// 1.57075 (4.6e-5 rad off); 1e-4 rad (0.006 degree) is far below any tilt a robot is built
/// with and far above such rounding.
inline constexpr double kDefaultAngleTolerance = 1e-4;

struct LoadOptions {
  std::string base_link;  ///< URDF: root of the kinematic tree to model; empty = URDF root
  std::string tip_link;   ///< URDF: keep only the chain from base to this link; empty = all
  std::string name;       ///< overrides the robot name (URDF names need not be identifiers)
  /// Angles (URDF rpy, MDH alpha and theta) within this many radians of a multiple of pi/2 are
  /// taken as that multiple, and axis components within it of 0 as 0; each such change becomes
  /// a RobotModel note. Rank decisions on the geometry use it as its precision
  /// (RigidBodyTree::angle_precision). 0 takes every value as written.
  double angle_tolerance = kDefaultAngleTolerance;
  /// URDF: a joint with <mimic> in the modelled part is refused (InputError naming it and its
  /// leader: modelgen has no mimic constraint); true keeps it as an independent joint, with a
  /// warning note.
  bool mimic_as_joint = false;
};

/// Loads `path` (.yaml/.yml: MDH description; .urdf: URDF) into a validated RobotModel.
/// Throws InputError naming the file, line and field on any problem.
RobotModel load_robot(const std::string& path, const LoadOptions& options = {});

/// Loads the description `text` as load_robot loads the file `path`: the extension of `path`
/// says the format, and messages name `path` (a description written but not yet saved, as
/// modelid export checks its output).
RobotModel load_robot_text(const std::string& path, const std::string& text,
                           const LoadOptions& options = {});

/// The whole file as bytes; InputError if it cannot be read.
std::string read_source_file(const std::string& path);

}  // namespace modelgen
