// Issue 30, guessed regions of MDH YAML links: a link without `region:` and without a-priori
// inertial values gets the region around the segments from its joint to the next joints and
// tool frames its DH rows give, and back along its own axis by its row's r to the foot of the
// previous link's common normal (the shaft that turns with it). The expected centres and
// semi-axes are worked out by hand below from the rows (frame j from a(j): Rot_x(alpha)
// Trans_x(d) Rot_z(theta) Trans_z(r)), the segments thickened by a quarter of the longest, at
// least 10 cm (a link without a segment of its own, or whose frame origin is its parent's, at
// least its parent's radius), and the ellipsoid through the corners of that box (sqrt(3) times
// its half sides). A link given `region:` keeps it; a link with `known:` inertials or the
// payload link gets none; a last link without a tool frame gets the sphere about its joint,
// marked as such.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// The region through the corners of the box centre +- half_sides.
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

RobotModel load_text(const std::string& name, const std::string& text) {
  const std::string path = (test::test_folder("mdh_region") / name).string();
  test::write_text(path, text);
  return load_robot(path);
}

TEST(MdhGuessedRegion, EachLinkSpansTheSegmentToItsNextJointOrTool) {
  const RobotModel robot = load_text("arm.yaml", R"(name: arm
joints:
  - {name: J1, type: revolute, alpha: 0, d: 0, theta: 0, r: 0.3}
  - {name: J2, type: revolute, alpha: pi/2, d: 0.1, theta: 0, r: 0}
  - {name: J3, type: revolute, alpha: 0, d: 0.6, theta: 0, r: 0.05}
  - {name: tool, type: fixed, alpha: pi/2, d: 0.4, theta: 0, r: 0.2}
)");
  ASSERT_EQ(robot.body_regions.size(), 4u);
  // Link 1 to J2 at (0.1, 0, 0) and back along z1 by r1 = 0.3 to (0, 0, -0.3): radius
  // max(0.075, 0.1) = 0.1; box x [-0.1, 0.2], y +-0.1, z [-0.4, 0.1].
  expect_region(robot.body_regions[0], {0.05, 0, -0.15}, {0.15, 0.1, 0.25}, "link 1");
  // Link 2 (r2 = 0) to J3 at (0.6, 0, 0.05): radius sqrt(0.3625) / 4.
  const double r2 = std::sqrt(0.6 * 0.6 + 0.05 * 0.05) / 4;
  expect_region(robot.body_regions[1], {0.3, 0, 0.025}, {0.3 + r2, r2, 0.025 + r2}, "link 2");
  // Link 3 to the tool frame: Trans_x(0.4), then Rot_x(pi/2) turns the tool's z (r = 0.2) to
  // -y: (0.4, -0.2, 0); and back to (0, 0, -0.05) (r3); radius sqrt(0.2) / 4.
  const double r3 = std::sqrt(0.4 * 0.4 + 0.2 * 0.2) / 4;
  expect_region(robot.body_regions[2], {0.2, -0.1, -0.025}, {0.2 + r3, 0.1 + r3, 0.025 + r3},
                "link 3");
  EXPECT_FALSE(robot.body_regions[2]->at_joint);
  // The tool frame's own body: nothing beyond it (a fixed frame has no shaft of its own), so
  // the sphere of its parent's radius about its origin.
  expect_region(robot.body_regions[3], {0, 0, 0}, {r3, r3, r3}, "tool");
  EXPECT_TRUE(robot.body_regions[3]->at_joint);
}

TEST(MdhGuessedRegion, ABranchSpansBothChildren) {
  // Link 1 carries J2 at (0, 0, 0.5) (r) and J3 at (0.2, 0, 0) (d), both with ant 1.
  const RobotModel robot = load_text("branch.yaml", R"(name: branch
joints:
  - {name: J1, type: revolute, alpha: 0, d: 0, theta: 0, r: 0}
  - {name: J2, type: revolute, ant: 1, alpha: 0, d: 0, theta: 0, r: 0.5}
  - {name: J3, type: revolute, ant: 1, alpha: 0, d: 0.2, theta: 0, r: 0}
)");
  // Longest 0.5: radius 0.125; box x [-0.125, 0.325], y +-0.125, z [-0.125, 0.625].
  expect_region(robot.body_regions[0], {0.1, 0, 0.25}, {0.225, 0.125, 0.375}, "link 1");
  // Link 2 reaches back along z2 by r2 = 0.5 to link 1's origin: box x, y +-0.125,
  // z [-0.625, 0.125].
  expect_region(robot.body_regions[1], {0, 0, -0.25}, {0.125, 0.125, 0.375}, "link 2");
  EXPECT_FALSE(robot.body_regions[1]->at_joint);
  // Link 3 (r3 = 0) ends its chain without a segment: the sphere of link 1's radius about J3.
  expect_region(robot.body_regions[2], {0, 0, 0}, {0.125, 0.125, 0.125}, "link 3");
  EXPECT_TRUE(robot.body_regions[2]->at_joint);
}

TEST(MdhGuessedRegion, GivenRegionsAPrioriInertialsAndThePayloadGetNoGuess) {
  const RobotModel robot = load_text("given.yaml", R"(name: given
joints:
  - {name: J1, type: revolute, alpha: 0, d: 0, theta: 0, r: 0,
     region: {centre: [0.1, 0, 0], semi_axes: [0.3, 0.2, 0.2]}}
  - {name: J2, type: revolute, alpha: pi/2, d: 0.5, theta: 0, r: 0}
  - {name: J3, type: revolute, alpha: 0, d: 0.4, theta: 0, r: 0}
  - {name: load, type: fixed, alpha: 0, d: 0.1, theta: 0, r: 0}
payload: {link: 4}
known:
  M2: 3.0
)");
  ASSERT_EQ(robot.body_regions.size(), 4u);
  ASSERT_TRUE(robot.body_regions[0].has_value());
  EXPECT_FALSE(robot.body_regions[0]->guessed);
  EXPECT_DOUBLE_EQ(robot.body_regions[0]->semi_axes[0], 0.3);
  EXPECT_FALSE(robot.body_regions[1].has_value());  // its mass is a-priori: held by the prior
  // Link 3 to the load frame at (0.1, 0, 0): the minimum radius.
  expect_region(robot.body_regions[2], {0.05, 0, 0}, {0.15, 0.1, 0.1}, "link 3");
  EXPECT_FALSE(robot.body_regions[3].has_value());  // the payload: whatever is attached
}

TEST(MdhGuessedRegion, TheShippedTx40WristReachesBackToTheElbow) {
  // Link 3 (r3 = 0.035) reaches J4 at (0, -0.225, 0) (alpha pi/2, r4 0.225) and back to
  // (0, 0, -0.035): radius the minimum 0.1 > 0.225 / 4; box x +-0.1, y [-0.325, 0.1],
  // z [-0.135, 0.1].
  const RobotModel robot = load_robot(test::source_path("robots/tx40.yaml"));
  ASSERT_EQ(robot.body_regions.size(), 7u);
  expect_region(robot.body_regions[2], {0, -0.1125, -0.0175}, {0.1, 0.2125, 0.1175}, "link 3");
  // Link 4's frame is at the wrist centre, r4 = 0.225 along z4 from link 3's x axis: its
  // forearm reaches back to (0, 0, -0.225); J5 sits at its origin. Box z [-0.325, 0.1].
  expect_region(robot.body_regions[3], {0, 0, -0.1125}, {0.1, 0.1, 0.2125}, "link 4");
  // Joints 5 and 6 at link 4's origin: link 4's radius (0.1), a sphere about the wrist centre.
  for (std::size_t b : {4u, 5u}) {
    expect_region(robot.body_regions[b], {0, 0, 0}, {0.1, 0.1, 0.1},
                  "link " + std::to_string(b + 1));
  }
  EXPECT_FALSE(robot.body_regions[5]->at_joint);    // link 6 reaches its load frame (length 0)
  EXPECT_FALSE(robot.body_regions[6].has_value());  // the payload link
}

}  // namespace
}  // namespace modelgen
