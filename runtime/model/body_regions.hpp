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
/// joint) to `ends` (in the body frame), thickened by `radius`; the box around that capsule
/// (or, with no segment, around the sphere of that radius at the origin), then
/// region_around_box. `guessed` is set, and `at_joint` when there is no segment.
BodyRegion region_around_segments(const std::vector<Eigen::Vector3d>& ends, double radius);

/// The same with the radius of a lone body: kSegmentRadiusFraction times the longest segment,
/// at least kSegmentRadiusMin.
BodyRegion region_around_segments(const std::vector<Eigen::Vector3d>& ends);

/// Per body of `tree`, the origins of its child bodies' frames in its own frame: where an MDH
/// description's rows put the next joints and the frames fixed to the body (a tool, a flange).
std::vector<std::vector<Eigen::Vector3d>> child_origins(const RigidBodyTree& tree);

/// The foot of a revolute body's axis: the point of its joint axis nearest its parent's frame
/// origin (the base's for a first body), in its own frame; nullopt when that is the origin
/// itself or the joint is not revolute. What turns with the joint includes the shaft between
/// the parent's joint and this frame: an MDH row's r (offset along the link's own axis, as the
/// KR 150's forearm length on A4's row, which puts frame 4 at the wrist centre) gives the foot
/// (0, 0, -r); for a URDF joint it is the part of <origin>'s offset along the joint's axis.
/// A body that starts_at_its_joint does not reach back to it.
std::optional<Eigen::Vector3d> axis_foot(const Body& body);

/// Whether a revolute body whose own segments go to `ends` (its child joints and fixed frames,
/// in its frame) starts at its joint instead of reaching back to `behind` (its axis_foot or
/// axes_meet, a point of its axis behind its origin): it does when a segment goes on past its
/// origin along the axis, away from `behind` (more than kMeetTolerance). Its frame then sits
/// at its bearing, with its body ahead, as URDFs that put frames at the physical joints have it
/// (the iiwa's and LWR's rolls, at mid-arm between the previous joint and the next): the shaft
/// behind is the parent's, whose segment to this joint spans it already. Otherwise its frame
/// sits at the far end of its body (the Panda's upper arm at the elbow, an MDH forearm A4 at
/// the wrist centre, a flange link) and the shaft is its own.
bool starts_at_its_joint(const std::vector<Eigen::Vector3d>& ends, const Eigen::Vector3d& behind);

/// Where body b's joint axis meets its parent's (both revolute), in b's frame: the point of a
/// spherical wrist, or of a shoulder whose axes intersect; nullopt for parallel or skew axes
/// (off by more than kMeetTolerance), or a meeting point beyond the parent's origin.
std::optional<Eigen::Vector3d> axes_meet(const RigidBodyTree& tree, std::size_t b);

/// Per body, the capsule radius of its guess: kSegmentRadiusFraction times its longest segment
/// (to `ends[b]`, its axis_foot and axes_meet unless starts_at_its_joint), at least
/// kSegmentRadiusMin; and at least its parent's radius when it has no segment of its own or its
/// axis meets its parent's (the joints of a spherical wrist meet in one point: the wrist links
/// share the ball the forearm's capsule ends in there, rather than each a minimum sphere; with
/// URDF origins placed at the flange, as in KUKA's, the same ball about the point the axes
/// meet).
std::vector<double> segment_radii(const RigidBodyTree& tree,
                                  const std::vector<std::vector<Eigen::Vector3d>>& ends);

/// Gives every body b of `model` without a region, without a-priori inertial values
/// (model.known_values: a body with them keeps them as its a-priori model, a guess would only
/// contradict it) and other than the payload body (whatever is attached) the guessed region
/// around the segments to ends[b], its axis_foot and axes_meet (unless starts_at_its_joint),
/// of radius segment_radii.
/// model.body_regions must have a slot per body.
void guess_missing_regions(RobotModel& model,
                           const std::vector<std::vector<Eigen::Vector3d>>& ends);

inline constexpr double kSegmentRadiusFraction = 0.25;
inline constexpr double kSegmentRadiusMin = 0.1;  // m: the smallest link of an industrial arm
inline constexpr double kCoincident = 1e-9;       // m: frame origins this close are one point
inline constexpr double kMeetTolerance = 1e-6;    // m: axes this close meet (rounded URDF numbers)

}  // namespace modelgen
