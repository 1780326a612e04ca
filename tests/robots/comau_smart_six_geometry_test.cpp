// robots/comau_smart_six.yaml is a hand conversion of the Smart Six URDF of lar-lab-unibo/lar_comau
// to modified DH. That URDF has no license, so it is not in this repository; its joint origins
// (xyz, rpy, every axis z) are facts, written below, and this checks the MDH table against
// them by forward kinematics on random joint angles: every joint axis is the same line in
// space, with the same direction.

#include <cmath>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

struct UrdfJoint {
  Eigen::Vector3d xyz, rpy;
};

// The URDF's joint origins; its 1.57075 and 3.14159 are quarter and half turns.
std::vector<UrdfJoint> smart_six_joints() {
  const double h = M_PI / 2;
  return {{{0, 0, 0}, {-M_PI, 0, 0}},       {{0.15, 0, 0}, {h, h, 0}},
          {{0.59, 0, 0}, {-M_PI, 0, -h}},   {{0.13, -0.64707, 0}, {-h, 0, 0}},
          {{0, 0, 0}, {-h, 0, 0}},          {{0, 0, 0}, {h, 0, 0}}};
}

// URDF semantics: child = parent * Trans(xyz) * Rz(yaw) Ry(pitch) Rx(roll) * Rz(q about axis z).
std::vector<Eigen::Isometry3d> urdf_joint_frames(const Eigen::VectorXd& q) {
  std::vector<Eigen::Isometry3d> frames;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const std::vector<UrdfJoint> joints = smart_six_joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const UrdfJoint& joint = joints[j];
    t = t * Eigen::Translation3d(joint.xyz) *
        Eigen::AngleAxisd(joint.rpy[2], Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(joint.rpy[1], Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(joint.rpy[0], Eigen::Vector3d::UnitX());
    frames.push_back(t);  // the joint's frame: its axis is z through the origin
    t = t * Eigen::AngleAxisd(q[static_cast<Eigen::Index>(j)], Eigen::Vector3d::UnitZ());
  }
  return frames;
}

Eigen::Matrix3d rotation(const Frame& f) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(f.rotation.data());
}
Eigen::Vector3d translation(const Frame& f) {
  return Eigen::Vector3d(f.translation[0], f.translation[1], f.translation[2]);
}

TEST(ComauSmartSixGeometry, MdhTableMatchesTheUrdfJointOriginsByForwardKinematics) {
  const RobotModel mdh = load_robot(test::source_path("robots/comau_smart_six.yaml"));
  ASSERT_EQ(mdh.dof(), 6);
  const ReferenceDynamics kinematics(mdh.tree);
  test::Random random(6);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::VectorXd q = random.vector(6, -3.2, 3.2);
    const std::vector<Frame> a = kinematics.forward_kinematics(q);
    const std::vector<Eigen::Isometry3d> b = urdf_joint_frames(q);
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d z_mdh = rotation(a[j]).col(2);
      const Eigen::Vector3d z_urdf = b[j].linear().col(2);
      EXPECT_LT((z_mdh - z_urdf).norm(), 1e-12) << "axis direction of joint " << j + 1;
      const Eigen::Vector3d offset = b[j].translation() - translation(a[j]);
      EXPECT_LT(offset.cross(z_mdh).norm(), 1e-12) << "axis line of joint " << j + 1;
    }
    // The wrist centre, where axes 4 to 6 meet, is the load frame's origin.
    EXPECT_LT((translation(a[6]) - b[5].translation()).norm(), 1e-12) << "wrist centre";
  }
  // Straight up at q = 0: 0.59 + 0.64707 above the shoulder, 0.15 - 0.13 in front of axis 1.
  const Frame wrist0 = kinematics.forward_kinematics(Eigen::VectorXd::Zero(6))[6];
  EXPECT_NEAR(wrist0.translation[0], 0.02, 1e-12);
  EXPECT_NEAR(wrist0.translation[1], 0.0, 1e-12);
  EXPECT_NEAR(wrist0.translation[2], 1.23707, 1e-12);
}

}  // namespace
}  // namespace modelgen
