// Issue 30, the guessed region of a link without shapes: the segments from its joint to its
// child joints (and links fixed to it) thickened by a quarter of the longest, at least 10 cm,
// against the closed form of the box around that capsule and against points of the capsule's
// surface, which must all lie inside; and through the URDF loader, a mesh-only middle link
// (its segment to the next joint), a mesh-only last link with a fixed flange, and a joint whose
// <origin> is offset along its (rotated) axis, whose link reaches back along the axis unless its
// own next joint lies further along that axis (a roll at the far end of its parent's body: the
// shaft is the parent's, and the roll starts at its joint).

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/model/load_robot.hpp"
#include "runtime/model/body_regions.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

void expect_region(const BodyRegion& region, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& half_sides) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(region.centre[static_cast<std::size_t>(i)], centre[i], 1e-12) << i;
    EXPECT_NEAR(region.semi_axes[static_cast<std::size_t>(i)], std::sqrt(3.0) * half_sides[i],
                1e-12)
        << i;
  }
}

double level(const BodyRegion& region, const Eigen::Vector3d& x) {
  double sum = 0;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    sum += std::pow((x[i] - region.centre[k]) / region.semi_axes[k], 2);
  }
  return sum;
}

TEST(SegmentRegion, ALongSegmentGetsAQuarterOfItsLength) {
  // From the joint to (0, 0, 0.8): radius 0.2, box x, y in [-0.2, 0.2], z in [-0.2, 1.0].
  const BodyRegion region = region_around_segments({Eigen::Vector3d(0, 0, 0.8)});
  EXPECT_TRUE(region.guessed);
  expect_region(region, {0, 0, 0.4}, {0.2, 0.2, 0.6});
  // Every point of the capsule (radius 0.2 about the segment) is inside.
  for (int a = 0; a < 24; ++a) {
    const double phi = 2 * M_PI * a / 24;
    for (int k = 0; k <= 10; ++k) {
      const double z = 0.8 * k / 10;
      EXPECT_LE(level(region, {0.2 * std::cos(phi), 0.2 * std::sin(phi), z}), 1.0);
    }
    for (int k = 0; k <= 6; ++k) {  // the end caps
      const double theta = M_PI / 2 * k / 6;
      const double rho = 0.2 * std::cos(theta), h = 0.2 * std::sin(theta);
      EXPECT_LE(level(region, {rho * std::cos(phi), rho * std::sin(phi), 0.8 + h}), 1.0);
      EXPECT_LE(level(region, {rho * std::cos(phi), rho * std::sin(phi), -h}), 1.0);
    }
  }
}

TEST(SegmentRegion, ShortOrNoSegmentsGetTheMinimumRadius) {
  // 0.2 m: a quarter is 5 cm, below the 10 cm minimum.
  expect_region(region_around_segments({Eigen::Vector3d(0.2, 0, 0)}), {0.1, 0, 0}, {0.2, 0.1, 0.1});
  // No child: the sphere of 10 cm about the joint.
  expect_region(region_around_segments({}), {0, 0, 0}, {0.1, 0.1, 0.1});
  // Two ends, a child joint at (0.4, 0, 0.3) (0.5 m: radius 0.125) and a tool at (0, 0.1, 0).
  expect_region(region_around_segments({Eigen::Vector3d(0.4, 0, 0.3), Eigen::Vector3d(0, 0.1, 0)}),
                {0.2, 0.05, 0.15}, {0.325, 0.175, 0.275});
}

// Link a: mesh only, its child joint 0.6 m up. Link b: mesh only, last, a flange fixed 0.2 m
// along x.
constexpr const char* kMeshArm = R"(<?xml version="1.0"?>
<robot name="mesh_arm">
  <link name="base"/>
  <link name="a"><visual><geometry><mesh filename="package://x/a.stl"/></geometry></visual></link>
  <link name="b"><visual><geometry><mesh filename="package://x/b.stl"/></geometry></visual></link>
  <link name="flange"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.6"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="tool" type="fixed"><parent link="b"/><child link="flange"/>
    <origin xyz="0.2 0 0"/></joint>
</robot>
)";

TEST(SegmentRegion, TheUrdfLoaderGuessesForMeshOnlyLinks) {
  const std::string path = (test::test_folder("segment_region") / "arm.urdf").string();
  test::write_text(path, kMeshArm);
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.body_regions.size(), 2u);
  ASSERT_TRUE(robot.body_regions[0].has_value());
  ASSERT_TRUE(robot.body_regions[1].has_value());
  EXPECT_TRUE(robot.body_regions[0]->guessed);
  EXPECT_TRUE(robot.body_regions[1]->guessed);
  // a: 0.6 m up, radius 0.15: z in [-0.15, 0.75].
  expect_region(*robot.body_regions[0], {0, 0, 0.3}, {0.15, 0.15, 0.45});
  // b: to the flange, 0.2 m; j2's axis meets j1's at b's origin (a shoulder), so b's radius is
  // at least a's, 0.15: x in [-0.15, 0.35].
  expect_region(*robot.body_regions[1], {0.1, 0, 0}, {0.25, 0.15, 0.15});
}

// As kMeshArm, but j2 is offset 0.3 m along y and turned a quarter about x, so its axis z_b is
// the parent's -y: the parent's origin is 0.3 m along z_b from b's, b's shaft reaches there.
constexpr const char* kOffsetArm = R"(<?xml version="1.0"?>
<robot name="offset_arm">
  <link name="base"/>
  <link name="a"><visual><geometry><mesh filename="package://x/a.stl"/></geometry></visual></link>
  <link name="b"><visual><geometry><mesh filename="package://x/b.stl"/></geometry></visual></link>
  <link name="flange"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0.3 0.6" rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="tool" type="fixed"><parent link="b"/><child link="flange"/>
    <origin xyz="0.2 0 0"/></joint>
</robot>
)";

TEST(SegmentRegion, AUrdfLinkReachesBackAlongItsAxisToItsParentsJoint) {
  const std::string path = (test::test_folder("segment_region") / "offset.urdf").string();
  test::write_text(path, kOffsetArm);
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.body_regions.size(), 2u);
  ASSERT_TRUE(robot.body_regions[1].has_value());
  // a: to j2's origin (0, 0.3, 0.6), radius sqrt(0.45) / 4.
  const double r = std::sqrt(0.45) / 4;
  expect_region(*robot.body_regions[0], {0, 0.15, 0.3}, {r, 0.15 + r, 0.3 + r});
  // b: to the flange (0.2, 0, 0) and back to (0, 0, 0.3), where its axis meets j1's (a's z at
  // height 0.6), so at least a's radius r: x in [-r, 0.2 + r], y in [-r, r], z in
  // [-r, 0.3 + r].
  expect_region(*robot.body_regions[1], {0.1, 0, 0.15}, {0.1 + r, r, 0.15 + r});
}

TEST(SegmentRegion, ARollStartsAtItsJointWhenItsBodyGoesOnAlongItsAxis) {
  const Eigen::Vector3d behind(0, 0, -0.8);  // its parent's origin, 0.8 m back along its axis
  // The next joint 0.6 m further along the axis: the frame is at the roll's bearing.
  EXPECT_TRUE(starts_at_its_joint({Eigen::Vector3d(0, 0.1, 0.6)}, behind));
  // The next joint across the axis (a DH frame at the far end of the body), back towards the
  // parent, or none at all (a flange link): the shaft is the roll's own.
  EXPECT_FALSE(starts_at_its_joint({Eigen::Vector3d(0.3, 0, 0)}, behind));
  EXPECT_FALSE(starts_at_its_joint({Eigen::Vector3d(0.3, 0, -0.2)}, behind));
  EXPECT_FALSE(starts_at_its_joint({}, behind));
  EXPECT_FALSE(starts_at_its_joint({Eigen::Vector3d::Zero()}, behind));
}

// A shoulder a (pitch about y) whose roll joint j2 sits 0.8 m up its z, at the far end of its
// body, with the roll's axis along that offset; the roll b goes on 0.6 m along its axis to the
// elbow c (pitch about y), which carries a flange 0.2 m further. `elbow` replaces the elbow's
// origin to place b's frame at the far end of its body instead (the Panda's upper arm).
std::string roll_arm(const std::string& elbow) {
  return R"(<?xml version="1.0"?>
<robot name="roll_arm">
  <link name="base"/>
  <link name="a"/><link name="b"/><link name="c"/><link name="flange"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.8"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="j3" type="revolute"><parent link="b"/><child link="c"/>
    <origin xyz=")" +
         elbow +
         R"("/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="tool" type="fixed"><parent link="c"/><child link="flange"/>
    <origin xyz="0 0 0.2"/></joint>
</robot>
)";
}

TEST(SegmentRegion, ARollAtTheFarEndOfItsParentStartsAtItsJoint) {
  const std::string path = (test::test_folder("segment_region") / "roll.urdf").string();
  test::write_text(path, roll_arm("0 0 0.6"));
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.body_regions.size(), 3u);
  // a: to j2 (0, 0, 0.8), radius 0.2: z in [-0.2, 1.0].
  expect_region(*robot.body_regions[0], {0, 0, 0.4}, {0.2, 0.2, 0.6});
  // b: only to the elbow (0, 0, 0.6), not back to a's origin (0, 0, -0.8) where its axis meets
  // a's; a quarter of 0.6 is 0.15, but at least a's 0.2 (the axes meet): z in [-0.2, 0.8].
  // Reaching back it would span z in [-1.0, 0.8], all of a's body.
  expect_region(*robot.body_regions[1], {0, 0, 0.3}, {0.2, 0.2, 0.5});
  // c: to the flange (0, 0, 0.2); its axis meets b's at its origin: b's radius 0.2.
  expect_region(*robot.body_regions[2], {0, 0, 0.1}, {0.2, 0.2, 0.3});
}

TEST(SegmentRegion, ARollWhoseFrameEndsItsBodyStillReachesBack) {
  const std::string path = (test::test_folder("segment_region") / "elbow_frame.urdf").string();
  test::write_text(path, roll_arm("0.3 0 0"));
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.body_regions.size(), 3u);
  // b: to the elbow (0.3, 0, 0), across its axis, and back to (0, 0, -0.8): radius 0.2; box
  // x [-0.2, 0.5], y +-0.2, z [-1.0, 0.2].
  expect_region(*robot.body_regions[1], {0.15, 0, -0.4}, {0.35, 0.2, 0.6});
}

}  // namespace
}  // namespace modelgen
