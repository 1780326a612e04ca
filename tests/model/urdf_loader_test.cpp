// The URDF loader against facts taken from the files themselves (masses, origins, limits as
// written), transforms and inertias computed by hand or with Eigen independently of the loader,
// and the line a broken input's error carries.

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/model/urdf_loader.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

constexpr double kPi = std::numbers::pi;

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// 1-based line of the first occurrence of `needle`, found by plain text search.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) return -1;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::vector<std::string> body_names(const RobotModel& model) {
  std::vector<std::string> names;
  for (const Body& body : model.tree.bodies) names.push_back(body.name);
  return names;
}

double known(const RobotModel& model, const std::string& param) {
  const int k = model.param_index(param);
  EXPECT_GE(k, 0) << param;
  if (k < 0) return NAN;
  EXPECT_TRUE(model.known_values[k].has_value()) << param;
  return model.known_values[k].value_or(NAN);
}

Eigen::Matrix3d rotation(const Body& body) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(body.fixed.rotation.data());
}

Eigen::Vector3d translation(const Body& body) {
  return Eigen::Vector3d(body.fixed.translation[0], body.fixed.translation[1],
                         body.fixed.translation[2]);
}

Eigen::Vector3d axis(const Body& body) {
  return Eigen::Vector3d(body.axis[0], body.axis[1], body.axis[2]);
}

Eigen::Matrix3d rot_z(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix(); }

// ---------------------------------------------------------------------------------------------
// Shipped robots

TEST(UrdfLoader, Ur5ChainOfSixRevoluteJoints) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/ur5.urdf"));
  EXPECT_EQ(model.name, "ur5");
  EXPECT_EQ(model.format, DescriptionFormat::kUrdf);
  ASSERT_EQ(model.dof(), 6);
  EXPECT_EQ(body_names(model),
            (std::vector<std::string>{"shoulder_link", "upper_arm_link", "forearm_link",
                                      "wrist_1_link", "wrist_2_link", "wrist_3_link"}));
  // Per moving body: 10 inertial, Ia, Fv, Fc, OFF.
  EXPECT_EQ(model.tree.params.size(), 84u);
  EXPECT_EQ(model.known_values.size(), 84u);
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(model.tree.bodies[j].parent, j - 1);
    EXPECT_EQ(model.tree.bodies[j].dof_index, j);
    EXPECT_EQ(model.tree.bodies[j].type, JointType::kRevolute);
  }
  EXPECT_EQ(model.joints[0].name, "shoulder_pan_joint");
  EXPECT_EQ(model.joints[1].parent_link, "shoulder_link");
}

TEST(UrdfLoader, Ur5MassesAreThoseWrittenInTheFile) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/ur5.urdf"));
  // <mass value=...> of shoulder_link ... wrist_3_link as written in ur5.urdf.
  const std::vector<double> masses = {3.7, 8.393, 2.275, 1.219, 1.219, 0.1879};
  double total = 0;
  for (int j = 0; j < 6; ++j) {
    const std::string index = std::to_string(j + 1);
    EXPECT_DOUBLE_EQ(known(model, "M" + index), masses[j]);
    total += known(model, "M" + index);
  }
  // Links with a moving ancestor: the six above plus ee_link and tool0 (both 0 kg). base_link
  // (4 kg) hangs on the fixed world joint and must not count.
  EXPECT_NEAR(total, 3.7 + 8.393 + 2.275 + 1.219 + 1.219 + 0.1879 + 0 + 0, 1e-12);
  // The centres of mass of upper_arm_link and forearm_link are at z = 0.28 and 0.25.
  EXPECT_NEAR(known(model, "MZ2"), 8.393 * 0.28, 1e-12);
  EXPECT_NEAR(known(model, "MZ3"), 2.275 * 0.25, 1e-12);
  EXPECT_NEAR(known(model, "MX2"), 0.0, 1e-15);
  // Drive parameters are never in a URDF.
  EXPECT_FALSE(model.known_values[model.param_index("Ia1")].has_value());
  EXPECT_FALSE(model.known_values[model.param_index("Fv6")].has_value());
}

TEST(UrdfLoader, Ur5TransformsAndLimitsAsWritten) {
  const std::string path = test::source_path("robots/urdf/ur5.urdf");
  const RobotModel model = load_robot(path);
  ASSERT_EQ(model.dof(), 6);
  const Body& pan = model.tree.bodies[0];
  // world -> base_link is an identity fixed joint, then <origin xyz="0.0 0.0 0.089159"/>.
  EXPECT_TRUE(rotation(pan).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_TRUE(translation(pan).isApprox(Eigen::Vector3d(0, 0, 0.089159), 1e-12));
  EXPECT_TRUE(axis(pan).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  const Body& lift = model.tree.bodies[1];
  const Eigen::Matrix3d ry = Eigen::AngleAxisd(1.57079632679, Eigen::Vector3d::UnitY()).matrix();
  // 1.57079632679 is a rounded quarter turn: the loader snaps it to exact zeros and ones.
  EXPECT_TRUE(rotation(lift).isApprox(ry, 1e-9));
  for (double entry : lift.fixed.rotation) {
    EXPECT_TRUE(entry == 0.0 || entry == 1.0 || entry == -1.0) << entry;
  }
  EXPECT_TRUE(translation(lift).isApprox(Eigen::Vector3d(0, 0.13585, 0), 1e-12));
  EXPECT_TRUE(axis(lift).isApprox(Eigen::Vector3d::UnitY(), 1e-12));

  const JointLimits& limits = model.joints[0].limits;
  EXPECT_DOUBLE_EQ(limits.q_lower.value_or(0), -6.28318530718);
  EXPECT_DOUBLE_EQ(limits.q_upper.value_or(0), 6.28318530718);
  EXPECT_DOUBLE_EQ(limits.dq.value_or(0), 3.15);
  EXPECT_DOUBLE_EQ(limits.effort.value_or(0), 150.0);
  EXPECT_FALSE(limits.ddq.has_value());
  EXPECT_DOUBLE_EQ(model.joints[2].limits.q_lower.value_or(0), -3.14159265359);
  EXPECT_EQ(model.joints[0].where.file, path);
  EXPECT_EQ(model.joints[0].where.line,
            line_of(file_text(path), "<joint name=\"shoulder_pan_joint\""));
}

TEST(UrdfLoader, Ur5InertiaAboutEachCentreOfMassIsPositiveDefinite) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/ur5.urdf"));
  for (int j = 1; j <= model.dof(); ++j) {
    SCOPED_TRACE("body " + std::to_string(j));
    const std::string s = std::to_string(j);
    Eigen::Matrix3d J;
    J << known(model, "XX" + s), known(model, "XY" + s), known(model, "XZ" + s),
        known(model, "XY" + s), known(model, "YY" + s), known(model, "YZ" + s),
        known(model, "XZ" + s), known(model, "YZ" + s), known(model, "ZZ" + s);
    const double m = known(model, "M" + s);
    ASSERT_GT(m, 0);
    const Eigen::Vector3d c =
        Eigen::Vector3d(known(model, "MX" + s), known(model, "MY" + s), known(model, "MZ" + s)) / m;
    // Parallel-axis theorem backwards: I_c = J_O - m (|c|^2 1 - c c^T).
    const Eigen::Matrix3d Ic =
        J - m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    EXPECT_LT((Ic - Ic.transpose()).norm(), 1e-12);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(Ic);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 0) << Ic;
  }
}

TEST(UrdfLoader, PandaFingersBranchFromTheHand) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/franka_panda.urdf"));
  ASSERT_EQ(model.dof(), 9);
  ASSERT_EQ(model.tree.bodies.size(), 9u);
  const Body& left = model.tree.bodies[7];
  const Body& right = model.tree.bodies[8];
  EXPECT_EQ(left.name, "panda_leftfinger");
  EXPECT_EQ(right.name, "panda_rightfinger");
  EXPECT_EQ(left.type, JointType::kPrismatic);
  EXPECT_EQ(right.type, JointType::kPrismatic);
  EXPECT_EQ(left.parent, right.parent);
  EXPECT_EQ(left.parent, 6);
  EXPECT_EQ(model.tree.bodies[6].name, "panda_link7");
  EXPECT_TRUE(axis(right).isApprox(Eigen::Vector3d(0, -1, 0), 1e-12));
  // panda_joint8 (z 0.107), panda_hand_joint (yaw -pi/4), finger origin (z 0.0584).
  EXPECT_TRUE(translation(left).isApprox(Eigen::Vector3d(0, 0, 0.107 + 0.0584), 1e-12));
  EXPECT_TRUE(rotation(left).isApprox(rot_z(-kPi / 4), 1e-12));
  EXPECT_DOUBLE_EQ(model.joints[7].limits.q_upper.value_or(0), 0.04);
  EXPECT_DOUBLE_EQ(model.joints[7].limits.q_lower.value_or(1), 0.0);
}

TEST(UrdfLoader, PandaHandMergesIntoLink7) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/franka_panda.urdf"));
  ASSERT_EQ(model.dof(), 9);
  // panda_link7 0.735522 kg + panda_link8 0 + panda_hand 0.73 + panda_hand_tcp 0.
  EXPECT_NEAR(known(model, "M7"), 0.735522 + 0.73, 1e-12);
  // panda_hand's centre (-0.01, 0, 0.03) in its frame, which is yawed by -pi/4 and raised by
  // 0.107 from panda_link7: (-0.01 cos45, 0.01 sin45, 0.137).
  const double h = 0.01 * std::sqrt(0.5);
  EXPECT_NEAR(known(model, "MX7"), 0.735522 * 1.0517e-02 + 0.73 * -h, 1e-12);
  EXPECT_NEAR(known(model, "MY7"), 0.735522 * -4.252e-03 + 0.73 * h, 1e-12);
  EXPECT_NEAR(known(model, "MZ7"), 0.735522 * 6.1597e-02 + 0.73 * 0.137, 1e-12);
  EXPECT_NEAR(known(model, "M8"), 0.015, 1e-15);
}

TEST(UrdfLoader, IiwaDrakeExtensionsAreIgnored) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/kuka_iiwa14_drake.urdf"));
  EXPECT_EQ(model.name, "iiwa14");
  ASSERT_EQ(model.dof(), 7);
  EXPECT_EQ(model.tree.bodies.front().name, "iiwa_link_1");
  EXPECT_EQ(model.tree.bodies.back().name, "iiwa_link_7");
  EXPECT_DOUBLE_EQ(model.joints[0].limits.dq.value_or(0), 1.4835298641951802);
  EXPECT_DOUBLE_EQ(model.joints[0].limits.effort.value_or(0), 320);
  EXPECT_NEAR(known(model, "M2"), 6.35, 1e-12);
}

TEST(UrdfLoader, Kr150WithoutInertialsHasNoKnownValues) {
  const RobotModel model = load_robot(test::source_path("robots/urdf/kuka_kr150_2.urdf"));
  ASSERT_EQ(model.dof(), 6);
  for (const auto& value : model.known_values) EXPECT_FALSE(value.has_value());
  // effort="0" in the file means "not given", not "no torque allowed".
  EXPECT_FALSE(model.joints[0].limits.effort.has_value());
  EXPECT_DOUBLE_EQ(model.joints[0].limits.dq.value_or(0), 1.919862177194);
  EXPECT_TRUE(axis(model.tree.bodies[0]).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
}

// ---------------------------------------------------------------------------------------------
// --base and --tip

TEST(UrdfLoader, TipKeepsOnlyTheChainToIt) {
  LoadOptions options;
  options.tip_link = "panda_link7";
  const RobotModel model = load_robot(test::source_path("robots/urdf/franka_panda.urdf"), options);
  ASSERT_EQ(model.dof(), 7);
  EXPECT_EQ(model.tree.bodies.back().name, "panda_link7");
  EXPECT_EQ(model.tree.params.size(), 7u * 14u);
  // The hand is not on the chain, so its mass is not merged.
  EXPECT_NEAR(known(model, "M7"), 0.735522, 1e-12);
}

TEST(UrdfLoader, BaseKeepsTheSubtreeBelowIt) {
  LoadOptions options;
  options.base_link = "panda_link3";
  const RobotModel model = load_robot(test::source_path("robots/urdf/franka_panda.urdf"), options);
  // panda_joint4 ... panda_joint7 and the two fingers.
  ASSERT_EQ(model.dof(), 6);
  EXPECT_EQ(model.tree.bodies[0].name, "panda_link4");
  EXPECT_EQ(model.tree.bodies[0].parent, -1);
  EXPECT_TRUE(translation(model.tree.bodies[0]).isApprox(Eigen::Vector3d(0.0825, 0, 0), 1e-12));
}

TEST(UrdfLoader, UnknownTipSuggestsTheClosestLink) {
  LoadOptions options;
  options.tip_link = "panda_lnk7";
  try {
    load_robot(test::source_path("robots/urdf/franka_panda.urdf"), options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("panda_lnk7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'panda_link7'"), std::string::npos)
        << e.what();
  }
}

TEST(UrdfLoader, UnknownBaseSuggestsTheClosestLink) {
  LoadOptions options;
  options.base_link = "panda_lnk0";
  try {
    load_robot(test::source_path("robots/urdf/franka_panda.urdf"), options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'panda_link0'"), std::string::npos)
        << e.what();
  }
}

TEST(UrdfLoader, TipAboveBaseHasNoPath) {
  LoadOptions options;
  options.base_link = "panda_link3";
  options.tip_link = "panda_link1";
  try {
    load_robot(test::source_path("robots/urdf/franka_panda.urdf"), options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "no path from base link 'panda_link3' to tip link 'panda_link1'"),
              std::string::npos)
        << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Conventions, on small inline URDFs

// Two bodies: arm on revolute j1 (no inertial of its own) carrying `tool` through a fixed joint
// with a quarter turn about z; hand on continuous j2 below tool, with no inertial anywhere.
const char* const kMergeUrdf = R"(<?xml version="1.0"?>
<robot name="merge">
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="bolted">
    <inertial><mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="arm"/>
  <link name="tool">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/>
    </inertial>
  </link>
  <link name="hand"/>
  <joint name="bolt" type="fixed">
    <parent link="base"/>
    <child link="bolted"/>
  </joint>
  <joint name="j1" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <origin xyz="0 0 1"/>
    <axis xyz="0 0 2"/>
    <limit lower="-1" upper="2" velocity="3" effort="4"/>
  </joint>
  <joint name="tool_mount" type="fixed">
    <parent link="arm"/>
    <child link="tool"/>
    <origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/>
  </joint>
  <joint name="j2" type="continuous">
    <parent link="tool"/>
    <child link="hand"/>
    <origin xyz="0 1 0"/>
    <axis xyz="1 1 0"/>
    <limit velocity="2" effort="0"/>
  </joint>
</robot>
)";

TEST(UrdfLoader, FixedLinksFoldIntoTransformsAndInertia) {
  const RobotModel model = load_urdf("merge.urdf", kMergeUrdf, {});
  ASSERT_EQ(model.dof(), 2);
  EXPECT_EQ(body_names(model), (std::vector<std::string>{"arm", "hand"}));
  EXPECT_EQ(model.tree.params.size(), 28u);
  const Body& arm = model.tree.bodies[0];
  const Body& hand = model.tree.bodies[1];
  EXPECT_EQ(hand.parent, 0);
  EXPECT_TRUE(axis(arm).isApprox(Eigen::Vector3d::UnitZ(), 1e-15));
  EXPECT_TRUE(axis(hand).isApprox(Eigen::Vector3d(1, 1, 0) / std::sqrt(2.0), 1e-15));
  EXPECT_TRUE(translation(arm).isApprox(Eigen::Vector3d(0, 0, 1), 1e-15));
  // tool_mount then j2's origin: (0,0,0.5) + Rz(90 deg) (0,1,0) = (-1, 0, 0.5).
  EXPECT_TRUE(translation(hand).isApprox(Eigen::Vector3d(-1, 0, 0.5), 1e-12));
  EXPECT_TRUE(rotation(hand).isApprox(rot_z(kPi / 2), 1e-12));

  // tool's centre of mass lands at (0, 0.1, 0.5) in arm's frame, its principal inertia
  // diag(0.01, 0.02, 0.03) turns into diag(0.02, 0.01, 0.03); parallel axis with m = 2:
  // 2 (0.26 1 - c c^T) = [[0.52, 0, 0], [0, 0.5, -0.1], [0, -0.1, 0.02]].
  EXPECT_NEAR(known(model, "XX1"), 0.54, 1e-12);
  EXPECT_NEAR(known(model, "XY1"), 0.0, 1e-12);
  EXPECT_NEAR(known(model, "XZ1"), 0.0, 1e-12);
  EXPECT_NEAR(known(model, "YY1"), 0.51, 1e-12);
  EXPECT_NEAR(known(model, "YZ1"), -0.1, 1e-12);
  EXPECT_NEAR(known(model, "ZZ1"), 0.05, 1e-12);
  EXPECT_NEAR(known(model, "MX1"), 0.0, 1e-12);
  EXPECT_NEAR(known(model, "MY1"), 0.2, 1e-12);
  EXPECT_NEAR(known(model, "MZ1"), 1.0, 1e-12);
  EXPECT_NEAR(known(model, "M1"), 2.0, 1e-15);
  // hand has no inertial and nothing merges into it: unknown, not zero.
  for (const char* name : {"XX2", "MX2", "M2"}) {
    EXPECT_FALSE(model.known_values[model.param_index(name)].has_value()) << name;
  }

  EXPECT_DOUBLE_EQ(model.joints[0].limits.q_lower.value_or(0), -1);
  EXPECT_DOUBLE_EQ(model.joints[0].limits.q_upper.value_or(0), 2);
  EXPECT_DOUBLE_EQ(model.joints[0].limits.dq.value_or(0), 3);
  EXPECT_DOUBLE_EQ(model.joints[0].limits.effort.value_or(0), 4);
  EXPECT_FALSE(model.joints[1].limits.q_lower.has_value());
  EXPECT_FALSE(model.joints[1].limits.q_upper.has_value());
  EXPECT_DOUBLE_EQ(model.joints[1].limits.dq.value_or(0), 2);
  EXPECT_FALSE(model.joints[1].limits.effort.has_value());
  EXPECT_EQ(model.joints[1].parent_link, "tool");
  EXPECT_EQ(model.joints[1].where.line, line_of(kMergeUrdf, "<joint name=\"j2\""));
}

std::string one_joint_urdf(const std::string& robot_name, const std::string& origin) {
  return "<robot name=\"" + robot_name +
         "\">\n"
         "  <link name=\"base\"/>\n"
         "  <link name=\"arm\"/>\n"
         "  <joint name=\"j1\" type=\"continuous\">\n"
         "    <parent link=\"base\"/>\n"
         "    <child link=\"arm\"/>\n"
         "    " +
         origin +
         "\n"
         "  </joint>\n"
         "</robot>\n";
}

TEST(UrdfLoader, RpyIsYawPitchRollAboutFixedAxes) {
  const RobotModel model = load_urdf(
      "rpy.urdf", one_joint_urdf("rpy", "<origin xyz=\"0.1 0.2 0.3\" rpy=\"0.3 -0.5 1.1\"/>"), {});
  ASSERT_EQ(model.dof(), 1);
  // URDF: R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                       .matrix();
  EXPECT_TRUE(rotation(model.tree.bodies[0]).isApprox(expected, 1e-12));
  EXPECT_TRUE(translation(model.tree.bodies[0]).isApprox(Eigen::Vector3d(0.1, 0.2, 0.3), 1e-15));
  // No <axis>: URDF's default is x.
  EXPECT_TRUE(axis(model.tree.bodies[0]).isApprox(Eigen::Vector3d::UnitX(), 1e-15));
}

TEST(UrdfLoader, BranchesFollowFileOrderNotNameOrder) {
  const char* const text = R"(<robot name="branches">
  <link name="base"/>
  <link name="zeta"/>
  <link name="alpha"/>
  <link name="zeta_tip"/>
  <joint name="z_joint" type="continuous"><parent link="base"/><child link="zeta"/></joint>
  <joint name="a_joint" type="continuous"><parent link="base"/><child link="alpha"/></joint>
  <joint name="tip_joint" type="prismatic">
    <parent link="zeta"/><child link="zeta_tip"/>
    <limit lower="0" upper="0.1" velocity="1" effort="5"/>
  </joint>
</robot>
)";
  const RobotModel model = load_urdf("branches.urdf", text, {});
  // Depth first: zeta's subtree is complete before alpha, which is written after it.
  EXPECT_EQ(body_names(model), (std::vector<std::string>{"zeta", "zeta_tip", "alpha"}));
  ASSERT_EQ(model.dof(), 3);
  EXPECT_EQ(model.tree.bodies[1].parent, 0);
  EXPECT_EQ(model.tree.bodies[2].parent, -1);
  EXPECT_EQ(model.tree.bodies[2].dof_index, 2);
}

TEST(UrdfLoader, AVendorsRobotNameBecomesAnIdentifierWithANote) {
  const std::string text = one_joint_urdf("GEN3-6DOF_NO-VISION_URDF_ARM_V01", "");
  const RobotModel model = load_urdf("named.urdf", text, {});
  EXPECT_EQ(model.name, "gen3_6dof_no_vision_urdf_arm_v01");
  ASSERT_FALSE(model.notes.empty());
  const std::string note = model.notes.front().to_string();
  EXPECT_NE(note.find("named.urdf:1:"), std::string::npos) << note;
  EXPECT_NE(note.find("'GEN3-6DOF_NO-VISION_URDF_ARM_V01'"), std::string::npos) << note;
  EXPECT_NE(note.find("modelgen::gen3_6dof_no_vision_urdf_arm_v01"), std::string::npos) << note;
  EXPECT_NE(note.find("--name"), std::string::npos) << note;

  LoadOptions options;
  options.name = "my_robot";
  const RobotModel named = load_urdf("named.urdf", text, options);
  EXPECT_EQ(named.name, "my_robot");
  for (const DescriptionNote& n : named.notes) {
    EXPECT_EQ(n.message.find("robot name"), std::string::npos) << n.to_string();
  }
  // What the user chose must be an identifier already: nothing is made of it silently.
  options.name = "my-robot";
  EXPECT_THROW(load_urdf("named.urdf", text, options), InputError);
}

// ---------------------------------------------------------------------------------------------
// standard_from_inertial against closed forms

TEST(StandardFromInertial, BoxTurnedAQuarterAboutZAndOffset) {
  // Solid box, mass m, sides a (x), b (y), c (z): I_c = m/12 diag(b^2+c^2, a^2+c^2, a^2+b^2).
  const double m = 3, a = 0.4, b = 0.2, c = 0.1, x = 0.5, y = -0.3;
  const std::array<double, 6> box = {m / 12 * (b * b + c * c), 0, 0,
                                     m / 12 * (a * a + c * c), 0, m / 12 * (a * a + b * b)};
  // Rz(90 deg): the box's long side now lies along y, so XX and YY swap.
  const std::array<double, 9> rz90 = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  const auto p = standard_from_inertial(m, {x, y, 0}, rz90, box);
  EXPECT_NEAR(p[0], m / 12 * (a * a + c * c) + m * y * y, 1e-14);            // XX
  EXPECT_NEAR(p[1], -m * x * y, 1e-14);                                      // XY
  EXPECT_NEAR(p[2], 0, 1e-14);                                               // XZ
  EXPECT_NEAR(p[3], m / 12 * (b * b + c * c) + m * x * x, 1e-14);            // YY
  EXPECT_NEAR(p[4], 0, 1e-14);                                               // YZ
  EXPECT_NEAR(p[5], m / 12 * (a * a + b * b) + m * (x * x + y * y), 1e-14);  // ZZ
  EXPECT_NEAR(p[6], m * x, 1e-14);
  EXPECT_NEAR(p[7], m * y, 1e-14);
  EXPECT_NEAR(p[8], 0, 1e-14);
  EXPECT_EQ(p[9], m);
}

TEST(StandardFromInertial, RotationSenseShowsInTheProductOfInertia) {
  // diag(A, B, C) turned by +30 deg about z: XY = (A - B) sin cos (sign flips for -30 deg).
  const double A = 2, B = 0.5, C = 1, t = kPi / 6;
  const std::array<double, 9> rz = {
      std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1};
  const auto p = standard_from_inertial(1, {0, 0, 0}, rz, {A, 0, 0, B, 0, C});
  EXPECT_NEAR(p[0], A * std::cos(t) * std::cos(t) + B * std::sin(t) * std::sin(t), 1e-14);
  EXPECT_NEAR(p[1], (A - B) * std::sin(t) * std::cos(t), 1e-14);
  EXPECT_NEAR(p[3], A * std::sin(t) * std::sin(t) + B * std::cos(t) * std::cos(t), 1e-14);
  EXPECT_NEAR(p[5], C, 1e-14);
}

// ---------------------------------------------------------------------------------------------
// Broken inputs: tests/bad_inputs/bad_inputs_test.cpp runs modelgen on every file of
// tests/bad_inputs/urdf/ and compares the messages; here the position the error carries.

TEST(UrdfBadInput, ErrorCarriesFileAndLine) {
  const std::string path = test::source_path("tests/bad_inputs/urdf/zero_axis.urdf");
  try {
    load_robot(path);
    FAIL() << "expected InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 9) << e.what();
    EXPECT_EQ(std::string(e.what()), path + ":9: error: " + e.message());
  }
}

}  // namespace
}  // namespace modelgen::gen
