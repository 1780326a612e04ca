// The `region` key of mdh_region.hpp.

#include "runtime/model/mdh_region.hpp"

#include <vector>

#include <Eigen/Core>

#include "runtime/model/body_regions.hpp"

namespace modelgen {

BodyRegion read_region(const YamlReader& in, const YAML::Node& node, const std::string& context) {
  const std::string where = "region of " + context;
  in.check_keys(node, {"centre", "semi_axes", "box"}, where);
  if (node["box"]) {
    if (node["centre"] || node["semi_axes"]) {
      in.fail(node["box"], where + ": give either 'box' or 'centre' and 'semi_axes', not both");
    }
    const YAML::Node box = node["box"];
    if (!box.IsSequence() || box.size() != 2) {
      in.fail(box, "'box' must be two corners [[x, y, z], [x, y, z]] (lowest, highest), in m");
    }
    std::vector<double> low(3), high(3);
    for (int i = 0; i < 3; ++i) {
      if (!box[0].IsSequence() || !box[1].IsSequence() || box[0].size() != 3 ||
          box[1].size() != 3) {
        in.fail(box, "'box' must be two corners [[x, y, z], [x, y, z]] (lowest, highest), in m");
      }
      low[static_cast<std::size_t>(i)] = in.length(box[0][i], "box");
      high[static_cast<std::size_t>(i)] = in.length(box[1][i], "box");
      if (!(low[static_cast<std::size_t>(i)] < high[static_cast<std::size_t>(i)])) {
        in.fail(box[1][i], where + ": 'box' corner " + std::string(1, "xyz"[i]) +
                               " must exceed the first corner's (lowest corner first)");
      }
    }
    return region_around_box(Eigen::Vector3d(low[0], low[1], low[2]),
                             Eigen::Vector3d(high[0], high[1], high[2]));
  }
  const YAML::Node centre = in.require(node, "centre", where);
  const YAML::Node semi_axes = in.require(node, "semi_axes", where);
  if (!centre.IsSequence() || centre.size() != 3) {
    in.fail(centre, "'centre' must be a list of 3 numbers (m)");
  }
  if (!semi_axes.IsSequence() || semi_axes.size() != 3) {
    in.fail(semi_axes, "'semi_axes' must be a list of 3 numbers (m)");
  }
  BodyRegion region;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    region.centre[k] = in.length(centre[i], "centre");
    region.semi_axes[k] = in.length(semi_axes[i], "semi_axes");
    if (!(region.semi_axes[k] > 0)) {
      in.fail(semi_axes[i], where + ": 'semi_axes' must be positive, got " + semi_axes[i].Scalar());
    }
  }
  return region;
}

}  // namespace modelgen
