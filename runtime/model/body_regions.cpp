// Regions from geometry (body_regions.hpp).

#include "runtime/model/body_regions.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace modelgen {

namespace {

double longest(const std::vector<Eigen::Vector3d>& ends) {
  double length = 0;
  for (const Eigen::Vector3d& end : ends) length = std::max(length, end.norm());
  return length;
}

Eigen::Matrix3d rotation(const Frame& frame) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(frame.rotation.data());
}

Eigen::Vector3d axis_of(const Body& body) {
  return Eigen::Vector3d(body.axis[0], body.axis[1], body.axis[2]).normalized();
}

// The parent's frame origin in body's frame (x_parent = R x + t).
Eigen::Vector3d parents_origin(const Body& body) {
  const auto& t = body.fixed.translation;
  return -rotation(body.fixed).transpose() * Eigen::Vector3d(t[0], t[1], t[2]);
}

// ends[b], and body b's axis foot and where its axis meets its parent's unless it starts at
// its joint: every segment its guess spans.
std::vector<Eigen::Vector3d> segments_of(const RigidBodyTree& tree,
                                         const std::vector<std::vector<Eigen::Vector3d>>& ends,
                                         std::size_t b) {
  const std::vector<Eigen::Vector3d> own =
      b < ends.size() ? ends[b] : std::vector<Eigen::Vector3d>{};
  std::vector<Eigen::Vector3d> all = own;
  std::vector<Eigen::Vector3d> behind;
  if (const auto foot = axis_foot(tree.bodies[b])) behind.push_back(*foot);
  if (const auto meet = axes_meet(tree, b); meet && meet->norm() > kCoincident) {
    behind.push_back(*meet);
  }
  for (const Eigen::Vector3d& point : behind) {
    if (!starts_at_its_joint(own, point)) all.push_back(point);
  }
  return all;
}

}  // namespace

BodyRegion region_around_box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  BodyRegion region;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    region.centre[k] = 0.5 * (low[i] + high[i]);
    // The ellipsoid through the box's corners holds the box: sqrt(3) times the half sides.
    region.semi_axes[k] = std::max(std::sqrt(3.0) * 0.5 * (high[i] - low[i]), 1e-3);
  }
  return region;
}

BodyRegion region_around_segments(const std::vector<Eigen::Vector3d>& ends, double radius) {
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& end : ends) {
    low = low.cwiseMin(end);
    high = high.cwiseMax(end);
  }
  // A capsule of radius r around each segment lies in the segments' box widened by r.
  BodyRegion region = region_around_box(low.array() - radius, high.array() + radius);
  region.guessed = true;
  region.at_joint = ends.empty();
  return region;
}

BodyRegion region_around_segments(const std::vector<Eigen::Vector3d>& ends) {
  return region_around_segments(
      ends, std::max(kSegmentRadiusFraction * longest(ends), kSegmentRadiusMin));
}

std::vector<std::vector<Eigen::Vector3d>> child_origins(const RigidBodyTree& tree) {
  std::vector<std::vector<Eigen::Vector3d>> ends(tree.bodies.size());
  for (const Body& body : tree.bodies) {
    if (body.parent < 0) continue;
    const auto& t = body.fixed.translation;
    ends[static_cast<std::size_t>(body.parent)].emplace_back(t[0], t[1], t[2]);
  }
  return ends;
}

std::optional<Eigen::Vector3d> axis_foot(const Body& body) {
  // A prismatic body slides along its axis (where it reaches depends on q); a fixed one is
  // carried by its parent, whose segments already reach it.
  if (body.type != JointType::kRevolute) return std::nullopt;
  const Eigen::Vector3d axis = axis_of(body);
  const Eigen::Vector3d foot = parents_origin(body).dot(axis) * axis;
  if (foot.norm() <= kCoincident) return std::nullopt;
  return foot;
}

bool starts_at_its_joint(const std::vector<Eigen::Vector3d>& ends, const Eigen::Vector3d& behind) {
  const Eigen::Vector3d away = -behind.normalized();
  return std::any_of(ends.begin(), ends.end(),
                     [&](const Eigen::Vector3d& end) { return end.dot(away) > kMeetTolerance; });
}

std::optional<Eigen::Vector3d> axes_meet(const RigidBodyTree& tree, std::size_t b) {
  const Body& body = tree.bodies[b];
  if (body.parent < 0 || body.type != JointType::kRevolute) return std::nullopt;
  const Body& parent = tree.bodies[static_cast<std::size_t>(body.parent)];
  if (parent.type != JointType::kRevolute) return std::nullopt;
  // Lines x = s u (this axis) and x = o + w v (the parent's, in this frame): the closest points
  // solve the 2x2 normal equations; parallel axes never meet.
  const Eigen::Vector3d u = axis_of(body), o = parents_origin(body);
  const Eigen::Vector3d v = rotation(body.fixed).transpose() * axis_of(parent);
  const double c = u.dot(v);
  if (1 - c * c < 1e-9) return std::nullopt;
  const double s = (u.dot(o) - c * v.dot(o)) / (1 - c * c);
  const double w = s * c - v.dot(o);
  const Eigen::Vector3d point = s * u;
  if ((point - (o + w * v)).norm() > kMeetTolerance) return std::nullopt;
  // Beyond the parent's origin the meeting point is no part of either body.
  if (point.norm() > o.norm() + kMeetTolerance) return std::nullopt;
  return point;
}

std::vector<double> segment_radii(const RigidBodyTree& tree,
                                  const std::vector<std::vector<Eigen::Vector3d>>& ends) {
  std::vector<double> radii(tree.bodies.size(), kSegmentRadiusMin);
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {  // parents come first
    const Body& body = tree.bodies[b];
    const double own = longest(segments_of(tree, ends, b));
    radii[b] = std::max(kSegmentRadiusFraction * own, kSegmentRadiusMin);
    if (body.parent >= 0 && (own <= kCoincident || axes_meet(tree, b))) {
      radii[b] = std::max(radii[b], radii[static_cast<std::size_t>(body.parent)]);
    }
  }
  return radii;
}

void guess_missing_regions(RobotModel& model,
                           const std::vector<std::vector<Eigen::Vector3d>>& ends) {
  std::vector<bool> a_priori(model.tree.bodies.size(), false);
  for (std::size_t k = 0; k < model.tree.params.size() && k < model.known_values.size(); ++k) {
    const StandardParam& param = model.tree.params[k];
    if (param.kind <= ParamKind::kM && model.known_values[k]) {
      a_priori[static_cast<std::size_t>(param.body)] = true;
    }
  }
  const std::vector<double> radii = segment_radii(model.tree, ends);
  for (std::size_t b = 0; b < model.body_regions.size() && b < model.tree.bodies.size(); ++b) {
    if (model.body_regions[b] || a_priori[b] || static_cast<int>(b) == model.payload_body) continue;
    model.body_regions[b] = region_around_segments(segments_of(model.tree, ends, b), radii[b]);
  }
}

}  // namespace modelgen
