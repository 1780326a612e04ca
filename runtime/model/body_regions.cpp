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
  return region;
}

}  // namespace modelgen
