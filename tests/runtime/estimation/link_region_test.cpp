// Issue 30, bounding regions from geometry: the loader's region per body against the shapes'
// boxes worked out by hand (a turned box, a cylinder along x, a sphere on a fixed child link, a
// mesh without size: a guessed region), and region_extent against closed forms (a point mass at the
// centre and on the surface, the solid ellipsoid that fills the region: sqrt(3/5)).

#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/estimation/link_summary.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// Link a: a 0.1 x 0.2 x 0.4 box centred 0.2 m up, turned a quarter about z (its x and y sides
// swap). Link b: a cylinder (radius 0.05, length 0.3) laid along x from 0 to 0.3, and on a
// fixed child 0.3 m along x a sphere of radius 0.05 centred 0.1 m further: x from 0 to 0.45,
// y and z within 0.05. Link c: a mesh only.
constexpr const char* kShapesArm = R"(<?xml version="1.0"?>
<robot name="shapes_arm">
  <link name="base"/>
  <link name="a">
    <collision><origin xyz="0 0 0.2" rpy="0 0 1.5707963267948966"/>
      <geometry><box size="0.1 0.2 0.4"/></geometry></collision>
  </link>
  <link name="b">
    <visual><origin xyz="0.15 0 0" rpy="0 1.5707963267948966 0"/>
      <geometry><cylinder radius="0.05" length="0.3"/></geometry></visual>
  </link>
  <link name="b_tip">
    <collision><origin xyz="0.1 0 0"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <link name="c">
    <visual><geometry><mesh filename="package://nowhere/c.stl"/></geometry></visual>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
  <joint name="tip" type="fixed"><parent link="b"/><child link="b_tip"/>
    <origin xyz="0.3 0 0"/></joint>
  <joint name="j3" type="revolute"><parent link="b_tip"/><child link="c"/>
    <origin xyz="0.1 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
</robot>
)";

void expect_region(const std::optional<BodyRegion>& region, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& half_sides) {
  ASSERT_TRUE(region.has_value());
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(region->centre[static_cast<std::size_t>(i)], centre[i], 1e-12) << i;
    EXPECT_NEAR(region->semi_axes[static_cast<std::size_t>(i)], std::sqrt(3.0) * half_sides[i],
                1e-12)
        << i;
  }
}

TEST(LinkRegion, TheLoaderBoundsEachBodyByItsShapes) {
  const std::string path = (test::test_folder("link_region") / "arm.urdf").string();
  test::write_text(path, kShapesArm);
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.tree.bodies.size(), 3u);
  ASSERT_EQ(robot.body_regions.size(), 3u);
  expect_region(robot.body_regions[0], {0, 0, 0.2}, {0.1, 0.05, 0.2});
  expect_region(robot.body_regions[1], {0.225, 0, 0}, {0.225, 0.05, 0.05});
  // A mesh has no size without its file: the last link, with nothing below it, gets the guess
  // along its axis x back to b's origin 0.4 m behind (where b's axis meets its own), radius
  // the minimum (b's, from its segments, is the minimum too): x in [-0.5, 0.1].
  ASSERT_TRUE(robot.body_regions[2].has_value());
  EXPECT_TRUE(robot.body_regions[2]->guessed);
  EXPECT_FALSE(robot.body_regions[0]->guessed);
  expect_region(robot.body_regions[2], {-0.2, 0, 0}, {0.3, 0.1, 0.1});
}

// A mesh-only link with an <inertial> keeps that as its a-priori model: no region is guessed
// (the shipped UR5's links are all so, and its vendor's wrist inertias reach 0.3 m from the
// joint, far outside any guess from the segments).
TEST(LinkRegion, AMeshOnlyLinkWithAnInertialGetsNoGuess) {
  std::string urdf = kShapesArm;
  const std::string mesh = R"(<visual><geometry><mesh filename="package://nowhere/c.stl"/>)";
  const std::size_t at = urdf.find(mesh);
  ASSERT_NE(at, std::string::npos);
  urdf.insert(at, R"(<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" )"
                  R"(ixy="0" ixz="0" iyz="0"/></inertial>)");
  const std::string path = (test::test_folder("link_region") / "arm_inertial.urdf").string();
  test::write_text(path, urdf);
  const RobotModel robot = load_robot(path);
  ASSERT_EQ(robot.body_regions.size(), 3u);
  EXPECT_FALSE(robot.body_regions[2].has_value());
  EXPECT_TRUE(robot.body_regions[0].has_value());  // shapes still give theirs
}

// Standard parameters (inertia about the frame origin) of mass m at com c with inertia Ic
// about it.
std::array<double, 10> body(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic) {
  const Eigen::Matrix3d I =
      Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2), m * c.x(), m * c.y(), m * c.z(), m};
}

TEST(LinkRegion, TheExtentOfClosedFormBodies) {
  BodyRegion region;
  region.centre = {0.1, -0.2, 0.3};
  region.semi_axes = {0.3, 0.2, 0.1};
  const Eigen::Vector3d c(0.1, -0.2, 0.3), s(0.3, 0.2, 0.1);
  const double m = 2.5;
  // A point mass at the centre: 0; on the surface: 1; beyond it by half an axis: 1.5.
  EXPECT_NEAR(region_extent(body(m, c, Eigen::Matrix3d::Zero()).data(), region), 0.0, 1e-6);
  EXPECT_NEAR(region_extent(body(m, c + Eigen::Vector3d(0, 0.2, 0), Eigen::Matrix3d::Zero()).data(),
                            region),
              1.0, 1e-12);
  EXPECT_NEAR(region_extent(
                  body(m, c + Eigen::Vector3d(0.45, 0, 0), Eigen::Matrix3d::Zero()).data(), region),
              1.5, 1e-12);
  // The solid ellipsoid filling the region: the mean of |u|^2 over the unit ball is 3/5.
  const Eigen::Matrix3d solid =
      m / 5 *
      Eigen::Vector3d(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                      s.x() * s.x() + s.y() * s.y())
          .asDiagonal();
  EXPECT_NEAR(region_extent(body(m, c, solid).data(), region), std::sqrt(0.6), 1e-12);
  // The same ellipsoid 1.5 times larger on every axis reaches outside: 1.5 sqrt(3/5) > 1.
  EXPECT_NEAR(region_extent(body(m, c, 2.25 * solid).data(), region), 1.5 * std::sqrt(0.6), 1e-12);
  const std::array<double, 10> massless{};
  EXPECT_TRUE(std::isinf(region_extent(massless.data(), region)));
}

}  // namespace
}  // namespace modelgen
