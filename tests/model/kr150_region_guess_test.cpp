// Issue 30, the guessed regions of the bundled KR 150 (robots/kr150.yaml: no `region:`, no
// a-priori link values) worked out by hand from its DH rows, and the illustrative truth of its
// example data (robots/data/kr150/true.json) inside them: every link's centre of mass, computed
// here from the first moments and masses, lies in its ellipsoid.
// Frame j from a(j): Rot_x(alpha) Trans_x(d) Rot_z(theta) Trans_z(r); a revolute link also
// reaches back along its own axis by r_j (to (0, 0, -r_j)); radius a quarter of the longest
// segment, at least 10 cm, a wrist link whose frame origin is its parent's at least its parent's;
// the ellipsoid through the box's corners has semi-axes sqrt(3) times the half sides. The URDF
// of the same arm (robots/urdf/kuka_kr150_2.urdf), whose link frames sit at the joints' URDF
// origins (A6's at the flange), gives its wrist links the same forearm ball.

#include <cmath>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

void expect_region(const std::optional<BodyRegion>& region, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& half_sides, const std::string& link) {
  ASSERT_TRUE(region.has_value()) << link;
  EXPECT_TRUE(region->guessed) << link;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(region->centre[k], centre[i], 1e-12) << link << " axis " << i;
    EXPECT_NEAR(region->semi_axes[k], std::sqrt(3.0) * half_sides[i], 1e-12) << link << " " << i;
  }
}

TEST(Kr150GuessedRegion, EachLinkSpansItsRowsAndTheWristSharesTheForearmsBall) {
  const RobotModel robot = load_robot(test::source_path("robots/kr150.yaml"));
  ASSERT_EQ(robot.body_regions.size(), 7u);
  // A1: alpha pi, r1 = -0.75 (z1 points down, frame 1 at A2's height): back to (0, 0, 0.75),
  // the base below; A2 at Rot_x(pi/2) (0.35, 0, 0) = (0.35, 0, 0). Radius 0.75 / 4 = 0.1875:
  // box x [-0.1875, 0.5375], y +-0.1875, z [-0.1875, 0.9375].
  expect_region(robot.body_regions[0], {0.175, 0, 0.375}, {0.3625, 0.1875, 0.5625}, "A1");
  // A2 (r2 = 0) to A3 at (1.25, 0, 0): radius 0.3125.
  expect_region(robot.body_regions[1], {0.625, 0, 0}, {0.9375, 0.3125, 0.3125}, "A2");
  // A3 (r3 = 0) to frame 4: Rot_x(-pi/2) (0.055, 0, -1.1) = (0.055, -1.1, 0); radius a
  // quarter of its length.
  const double r3 = std::hypot(0.055, 1.1) / 4;
  expect_region(robot.body_regions[2], {0.0275, -0.55, 0}, {0.0275 + r3, 0.55 + r3, r3}, "A3");
  // A4: frame 4 at the wrist centre, r4 = -1.1: its forearm reaches back to (0, 0, 1.1); A5
  // at its origin. Radius 0.275: box x, y +-0.275, z [-0.275, 1.375].
  expect_region(robot.body_regions[3], {0, 0, 0.55}, {0.275, 0.275, 0.825}, "A4");
  // A5 (frame at A4's origin, A6 at its own): the forearm's ball, radius 0.275.
  expect_region(robot.body_regions[4], {0, 0, 0}, {0.275, 0.275, 0.275}, "A5");
  // A6 (frame at A5's origin) to the flange at (0, 0, -0.23) with the ball's radius 0.275:
  // z [-0.505, 0.275].
  expect_region(robot.body_regions[5], {0, 0, -0.115}, {0.275, 0.275, 0.39}, "A6");
  EXPECT_FALSE(robot.body_regions[6].has_value());  // the flange carries the payload

  const nlohmann::json truth =
      nlohmann::json::parse(test::read_text(test::source_path("robots/data/kr150/true.json")));
  const nlohmann::json& standard = truth.at("standard");
  const auto value = [&](const std::string& name) {
    return standard.contains(name) ? standard[name].get<double>() : 0.0;
  };
  for (int j = 1; j <= 6; ++j) {
    const std::string n = std::to_string(j);
    const double m = value("M" + n);
    const Eigen::Vector3d com =
        Eigen::Vector3d(value("MX" + n), value("MY" + n), value("MZ" + n)) / m;
    const BodyRegion& region = *robot.body_regions[static_cast<std::size_t>(j - 1)];
    double level = 0;
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(i);
      level += std::pow((com[i] - region.centre[k]) / region.semi_axes[k], 2);
    }
    EXPECT_LT(level, 1.0) << "A" << j << " centre of mass " << com.transpose();
  }
}

TEST(Kr150GuessedRegion, TheUrdfWristSharesTheForearmsBallToo) {
  const RobotModel robot = load_robot(test::source_path("robots/urdf/kuka_kr150_2.urdf"));
  ASSERT_EQ(robot.body_regions.size(), 6u);
  // link_4 (frame at A4, axis x): joint_a5 1.1 m along x, radius 0.275.
  expect_region(robot.body_regions[3], {0.55, 0, 0}, {0.825, 0.275, 0.275}, "link_4");
  // link_5 (at the wrist centre, where A4's axis meets its own): joint_a6 0.23 m along x,
  // A4's radius 0.275: x [-0.275, 0.505].
  expect_region(robot.body_regions[4], {0.115, 0, 0}, {0.39, 0.275, 0.275}, "link_5");
  // link_6 (at the flange, axis x): back along x to the wrist centre, where A5's axis meets
  // its own: x [-0.505, 0.275].
  expect_region(robot.body_regions[5], {-0.115, 0, 0}, {0.39, 0.275, 0.275}, "link_6");
}

}  // namespace
}  // namespace modelgen
