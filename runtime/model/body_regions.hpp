// The regions a body's mass must stay in (modelgen/model/robot_model.hpp, BodyRegion), from
// the description's geometry: the ellipsoid around a box of shapes, or, for a body without
// shapes, a guess from the segments to its child joints. Private to the loaders.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// The smallest axis-aligned ellipsoid through the corners of the box [low, high]: centre the
/// box's, semi-axes sqrt(3) times its half sides (each at least 1 mm, so a flat plate still
/// has a region).
BodyRegion region_around_box(const Eigen::Vector3d& low, const Eigen::Vector3d& high);

/// The guessed region of a body without shapes: the segments from its frame's origin (its
/// joint) to `ends` (its child joints' origins and the origins of links fixed to it, such as a
/// flange or a tool frame, in the body frame), thickened by the radius kSegmentRadiusFraction
/// times the longest segment, at least kSegmentRadiusMin; the box around that capsule (or, with
/// no segment, around the sphere of that radius at the origin), then region_around_box.
/// `guessed` is set, and `at_joint` when there is no segment.
BodyRegion region_around_segments(const std::vector<Eigen::Vector3d>& ends);

/// Per body of `tree`, the origins of its child bodies' frames in its own frame: where an MDH
/// description's rows put the next joints and the frames fixed to the body (a tool, a flange).
std::vector<std::vector<Eigen::Vector3d>> child_origins(const RigidBodyTree& tree);

/// Gives every body b of `model` without a region, without a-priori inertial values
/// (model.known_values: a body with them keeps them as its a-priori model, a guess would only
/// contradict it) and other than the payload body (whatever is attached) the guessed region
/// region_around_segments(ends[b]). model.body_regions must have a slot per body.
void guess_missing_regions(RobotModel& model,
                           const std::vector<std::vector<Eigen::Vector3d>>& ends);

inline constexpr double kSegmentRadiusFraction = 0.25;
inline constexpr double kSegmentRadiusMin = 0.1;  // m: a wrist with coincident joints

}  // namespace modelgen
