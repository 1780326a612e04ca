// The MDH YAML loader against facts written independently of it: Table I of Gautier & Briot
// turned into homogeneous matrices by hand, the coupling matrices of Gautier eq. 25 and
// Swevers eq. 11, and the parameter naming of DESIGN.md.

#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

using Eigen::Matrix4d;

Matrix4d rot_x(double a) {
  Matrix4d T = Matrix4d::Identity();
  T(1, 1) = std::cos(a), T(1, 2) = -std::sin(a), T(2, 1) = std::sin(a), T(2, 2) = std::cos(a);
  return T;
}
Matrix4d rot_z(double a) {
  Matrix4d T = Matrix4d::Identity();
  T(0, 0) = std::cos(a), T(0, 1) = -std::sin(a), T(1, 0) = std::sin(a), T(1, 1) = std::cos(a);
  return T;
}
Matrix4d trans(double x, double y, double z) {
  Matrix4d T = Matrix4d::Identity();
  T(0, 3) = x, T(1, 3) = y, T(2, 3) = z;
  return T;
}

TEST(MdhYamlLoader, Tx40ForwardKinematicsMatchesTableI) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  ASSERT_EQ(model.dof(), 6);
  ASSERT_EQ(model.tree.bodies.size(), 7u);
  const ReferenceDynamics dynamics(model.tree);
  // Table I, typed in again here: alpha, d, theta offset, r.
  const double pi = std::numbers::pi;
  const double table[7][4] = {{0, 0, 0, 0},          {-pi / 2, 0, -pi / 2, 0},
                              {0, 0.225, pi / 2, 0.035}, {pi / 2, 0, 0, 0.225},
                              {-pi / 2, 0, 0, 0},     {pi / 2, 0, 0, 0},
                              {0, 0, 0, 0}};
  test::Random random(7);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::VectorXd q = random.vector(6, -pi, pi);
    const std::vector<Frame> poses = dynamics.forward_kinematics(q);
    Matrix4d T = Matrix4d::Identity();
    for (int j = 0; j < 7; ++j) {
      const double qj = j < 6 ? q[j] : 0.0;
      T = T * rot_x(table[j][0]) * trans(table[j][1], 0, 0) * rot_z(table[j][2] + qj) *
          trans(0, 0, table[j][3]);
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(poses[j].translation[r], T(r, 3), 1e-12);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(poses[j].rotation[3 * r + c], T(r, c), 1e-12);
      }
    }
  }
}

TEST(MdhYamlLoader, QuarterTurnsGiveExactZerosAndOnes) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  // Frame 2: Rot_x(-pi/2) Rot_z(-pi/2) has only entries 0 and +-1, exactly.
  for (double entry : model.tree.bodies[1].fixed.rotation) {
    EXPECT_TRUE(entry == 0.0 || entry == 1.0 || entry == -1.0) << entry;
  }
}

TEST(MdhYamlLoader, Tx40CouplingIsGautierEq25) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const Eigen::MatrixXd& K = model.drives.motor_from_joint;
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(6, 6);
  expected.diagonal() << 32, 32, 45, -48, 45, 32;
  expected(5, 4) = 32;  // dq_m6 = N6 dq5 + N6 dq6
  EXPECT_EQ(K, expected);
}

TEST(MdhYamlLoader, Kr150CouplingInvertsSweversEq11) {
  const RobotModel model = load_robot(test::source_path("robots/kr150.yaml"));
  Eigen::MatrixXd V = Eigen::MatrixXd::Identity(6, 6);
  V(4, 3) = 0.0093;  // V2
  V(5, 3) = 0.0138;  // V0
  V(5, 4) = -0.0140; // V1
  // No gear ratios given: motor_from_joint is V^-1, so V K = 1.
  EXPECT_TRUE((V * model.drives.motor_from_joint).isApprox(Eigen::MatrixXd::Identity(6, 6), 1e-14));
}

TEST(MdhYamlLoader, StandardParametersFollowDesignOrder) {
  const RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  const std::vector<std::string> names = model.param_names();
  // 14 per joint, the rotor and friction of motor 6 that turns with dq5 + dq6 (Gautier & Briot
  // eq. 25-26), 10 for the fixed payload frame.
  ASSERT_EQ(names.size(), 6u * 14 + 3 + 10);
  EXPECT_EQ(std::vector<std::string>(names.begin() + 84, names.begin() + 87),
            (std::vector<std::string>{"Iam6", "Fvm6", "Fcm6"}));
  ASSERT_EQ(model.tree.coupled_motors.size(), 1u);
  EXPECT_EQ(model.tree.coupled_motors[0].dof_index, 5);
  EXPECT_EQ(model.tree.coupled_motors[0].coupling, (std::vector<double>{0, 0, 0, 0, 1, 1}));
  const std::vector<std::string> first = {"XX1", "XY1", "XZ1", "YY1", "YZ1", "ZZ1", "MX1",
                                          "MY1", "MZ1", "M1",  "Ia1", "Fv1", "Fc1", "OFF1"};
  EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 14), first);
  EXPECT_EQ(names.back(), "M7");  // the fixed payload frame has inertial parameters only
  EXPECT_EQ(model.payload_body, 6);
  EXPECT_EQ(*model.known_values[model.param_index("Fv1")], 8.05);
  EXPECT_FALSE(model.known_values[model.param_index("M1")].has_value());
}

TEST(MdhYamlLoader, ANameThatIsNoNamespaceBecomesOneWithANote) {
  const std::string text =
      "name: class\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n";
  const RobotModel model = load_mdh_yaml("inline.yaml", text);
  EXPECT_EQ(model.name, "class_robot");
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(model.notes[0].where.line, 1);
  EXPECT_NE(model.notes[0].message.find("modelgen::class_robot"), std::string::npos);
}

TEST(MdhYamlLoader, FrictionOptionsShapeTheParameterList) {
  const std::string text =
      "name: arm\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n"
      "  - {type: prismatic, alpha: pi/2, d: 0.1, theta: 0, r: 0.2}\n"
      "friction: {viscous: true, coulomb: true, offset: false, asymmetric: true}\n"
      "rotor_inertia: false\n";
  const RobotModel model = load_mdh_yaml("inline.yaml", text);
  const std::vector<std::string> names = model.param_names();
  const std::vector<std::string> drive(names.begin() + 10, names.begin() + 14);
  EXPECT_EQ(drive, (std::vector<std::string>{"Fvp1", "Fvn1", "Fcp1", "Fcn1"}));
  EXPECT_EQ(names.size(), 2u * 14);
  EXPECT_EQ(model.tree.bodies[1].type, JointType::kPrismatic);
}

TEST(MdhYamlLoader, AntecedentsMakeTrees) {
  const std::string text =
      "name: two_fingers\n"
      "joints:\n"
      "  - {name: palm, type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n"
      "  - {name: left, type: prismatic, ant: palm, alpha: pi/2, d: 0.05, theta: 0, r: 0}\n"
      "  - {name: right, type: prismatic, ant: 1, alpha: -pi/2, d: -0.05, theta: 0, r: 0}\n";
  const RobotModel model = load_mdh_yaml("inline.yaml", text);
  EXPECT_EQ(model.tree.bodies[1].parent, 0);
  EXPECT_EQ(model.tree.bodies[2].parent, 0);
}

TEST(ParseAngle, AcceptsNumbersAndFractionsOfPi) {
  const double pi = std::numbers::pi;
  struct Case {
    const char* text;
    double value;
    bool exact;
  };
  const Case cases[] = {{"0", 0, true},          {"0.5", 0.5, false},  {"pi", pi, true},
                        {"-pi/2", -pi / 2, true}, {"3*pi/4", 3 * pi / 4, true},
                        {"2 * pi / 3", 2 * pi / 3, true}, {"0.5*pi", pi / 2, false},
                        {"+pi/2", pi / 2, true}};
  for (const Case& c : cases) {
    const auto angle = parse_angle(c.text);
    ASSERT_TRUE(angle.has_value()) << c.text;
    EXPECT_DOUBLE_EQ(angle->value, c.value) << c.text;
    EXPECT_EQ(angle->is_pi_fraction, c.exact) << c.text;
  }
  for (const char* bad : {"pie", "pi/0", "2pi", "pi*2", "", "1e", "nan", "inf"}) {
    EXPECT_FALSE(parse_angle(bad).has_value()) << bad;
  }
  EXPECT_EQ(parse_angle("-pi/2")->sin(), -1.0);
  EXPECT_EQ(parse_angle("-pi/2")->cos(), 0.0);
  EXPECT_EQ(parse_angle("3*pi/2")->cos(), 0.0);
}

}  // namespace
}  // namespace modelgen::gen
