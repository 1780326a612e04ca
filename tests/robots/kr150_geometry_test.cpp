// robots/kr150.yaml is a hand conversion of the KR 150-2 URDF to modified DH. This checks it by
// forward kinematics against the URDF itself on random joint angles: every joint axis is the
// same line in space (same direction), and the flange has the same position and, up to a
// constant rotation between the two frame conventions, the same orientation.

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

Eigen::Matrix3d rotation(const Frame& f) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(f.rotation.data());
}
Eigen::Vector3d translation(const Frame& f) {
  return Eigen::Vector3d(f.translation[0], f.translation[1], f.translation[2]);
}

TEST(Kr150Geometry, MdhTableMatchesUrdfByForwardKinematics) {
  const modelgen::RobotModel mdh = modelgen::load_robot(test::source_path("robots/kr150.yaml"));
  const modelgen::RobotModel urdf = modelgen::load_robot(test::source_path("robots/urdf/kuka_kr150_2.urdf"));
  ASSERT_EQ(mdh.dof(), 6);
  ASSERT_EQ(urdf.dof(), 6);
  ASSERT_EQ(urdf.tree.bodies.size(), 6u);  // flange and tool0 are fixed, merged into link_6
  const ReferenceDynamics mdh_kinematics(mdh.tree), urdf_kinematics(urdf.tree);

  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  const Frame flange_mdh0 = mdh_kinematics.forward_kinematics(zero)[6];
  const Frame flange_urdf0 = urdf_kinematics.forward_kinematics(zero)[5];
  const Eigen::Matrix3d convention = rotation(flange_urdf0).transpose() * rotation(flange_mdh0);

  test::Random random(150);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::VectorXd q = random.vector(6, -3.2, 3.2);
    const std::vector<Frame> a = mdh_kinematics.forward_kinematics(q);
    const std::vector<Frame> b = urdf_kinematics.forward_kinematics(q);
    for (int j = 0; j < 6; ++j) {
      // MDH: the axis of joint j is z_j through the origin of frame j. URDF: the axis is the
      // joint's axis vector, through the child link's origin.
      const Eigen::Vector3d z_mdh = rotation(a[j]).col(2);
      const Eigen::Vector3d u = Eigen::Map<const Eigen::Vector3d>(urdf.tree.bodies[j].axis.data());
      const Eigen::Vector3d z_urdf = rotation(b[j]) * u;
      EXPECT_LT((z_mdh - z_urdf).norm(), 1e-12) << "axis direction of joint " << j + 1;
      const Eigen::Vector3d offset = translation(b[j]) - translation(a[j]);
      EXPECT_LT(offset.cross(z_mdh).norm(), 1e-12) << "axis line of joint " << j + 1;
    }
    EXPECT_LT((translation(a[6]) - translation(b[5])).norm(), 1e-12) << "flange position";
    EXPECT_LT((rotation(a[6]) - rotation(b[5]) * convention).norm(), 1e-12) << "flange orientation";
  }
  // At q = 0 the arm lies along x: 0.35 + 1.25 + 1.1 + 0.23
  // forward and 0.75 - 0.055 up, read off the URDF joint origins.
  EXPECT_NEAR(flange_mdh0.translation[0], 2.93, 1e-12);
  EXPECT_NEAR(flange_mdh0.translation[1], 0.0, 1e-12);
  EXPECT_NEAR(flange_mdh0.translation[2], 0.695, 1e-12);
}

}  // namespace
}  // namespace modelgen
