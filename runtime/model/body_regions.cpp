// Regions from geometry (body_regions.hpp).

#include "runtime/model/body_regions.hpp"

#include <algorithm>
#include <cmath>

namespace modelgen {

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

BodyRegion region_around_segments(const std::vector<Eigen::Vector3d>& ends) {
  double longest = 0;
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& end : ends) {
    longest = std::max(longest, end.norm());
    low = low.cwiseMin(end);
    high = high.cwiseMax(end);
  }
  // A capsule of radius r around each segment lies in the segments' box widened by r.
  const double r = std::max(kSegmentRadiusFraction * longest, kSegmentRadiusMin);
  BodyRegion region = region_around_box(low.array() - r, high.array() + r);
  region.guessed = true;
  region.at_joint = ends.empty();
  return region;
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

void guess_missing_regions(RobotModel& model,
                           const std::vector<std::vector<Eigen::Vector3d>>& ends) {
  std::vector<bool> a_priori(model.tree.bodies.size(), false);
  for (std::size_t k = 0; k < model.tree.params.size() && k < model.known_values.size(); ++k) {
    const StandardParam& param = model.tree.params[k];
    if (param.kind <= ParamKind::kM && model.known_values[k]) {
      a_priori[static_cast<std::size_t>(param.body)] = true;
    }
  }
  for (std::size_t b = 0; b < model.body_regions.size() && b < ends.size(); ++b) {
    if (model.body_regions[b] || a_priori[b] || static_cast<int>(b) == model.payload_body) continue;
    model.body_regions[b] = region_around_segments(ends[b]);
  }
}

}  // namespace modelgen
