// What real descriptions hold that loads but needs a second look, or is refused: mimic joints
// (refused unless --mimic-as-joint), a joint's second <origin>, continuous joints (no position
// limit), and magnitudes that are likely unit slips (degrees, deg/s, grams), for URDF and MDH
// YAML alike.

#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/error.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// The notes of `model` that are warnings, as printed.
std::vector<std::string> warnings(const RobotModel& model) {
  std::vector<std::string> found;
  for (const DescriptionNote& note : model.notes) {
    if (note.warning) found.push_back(note.to_string());
  }
  return found;
}

// One link 'l1' of mass `mass` on joint 'j1' of type `type` with the given <limit> attributes.
std::string one_joint_urdf(const std::string& type, const std::string& limit,
                           const std::string& mass = "2") {
  return "<?xml version=\"1.0\"?>\n"  // line 1
         "<robot name=\"arm\">\n"     // 2
         "  <link name=\"base\"/>\n"  // 3
         "  <link name=\"l1\">\n"     // 4
         "    <inertial>\n"           // 5
         "      <mass value=\"" +
         mass +
         "\"/>\n"  // 6
         "      <inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/>\n"
         "    </inertial>\n"  // 8
         "  </link>\n"        // 9
         "  <joint name=\"j1\" type=\"" +
         type +
         "\">\n"                          // 10
         "    <parent link=\"base\"/>\n"  // 11
         "    <child link=\"l1\"/>\n"     // 12
         "    <axis xyz=\"0 0 1\"/>\n"    // 13
         "    <limit " +
         limit +
         "/>\n"  // 14
         "  </joint>\n"
         "</robot>\n";
}

// A hand on 'base' with two prismatic fingers, the second mimicking the first (as the Panda as
// published: tests/model/corpus/franka_panda.urdf).
std::string mimic_gripper_urdf() {
  return "<robot name=\"gripper\">\n"                           // 1
         "  <link name=\"base\"/>\n"                            // 2
         "  <link name=\"hand\"/>\n"                            // 3
         "  <link name=\"left\"/>\n"                            // 4
         "  <link name=\"right\"/>\n"                           // 5
         "  <joint name=\"wrist\" type=\"revolute\">\n"         // 6
         "    <parent link=\"base\"/><child link=\"hand\"/>\n"  // 7
         "    <axis xyz=\"0 0 1\"/>\n"                          // 8
         "    <limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/>\n"
         "  </joint>\n"                                         // 10
         "  <joint name=\"finger_1\" type=\"prismatic\">\n"     // 11
         "    <parent link=\"hand\"/><child link=\"left\"/>\n"  // 12
         "    <axis xyz=\"0 1 0\"/>\n"                          // 13
         "    <limit lower=\"0\" upper=\"0.04\" velocity=\"0.2\" effort=\"20\"/>\n"
         "  </joint>\n"                                          // 15
         "  <joint name=\"finger_2\" type=\"prismatic\">\n"      // 16
         "    <parent link=\"hand\"/><child link=\"right\"/>\n"  // 17
         "    <axis xyz=\"0 -1 0\"/>\n"                          // 18
         "    <limit lower=\"0\" upper=\"0.04\" velocity=\"0.2\" effort=\"20\"/>\n"
         "    <mimic joint=\"finger_1\" multiplier=\"1\" offset=\"0\"/>\n"  // 20
         "  </joint>\n"
         "</robot>\n";
}

TEST(DescriptionWarnings, MimicFollowerIsRefusedNamingItAndItsLeader) {
  try {
    load_robot_text("gripper.urdf", mimic_gripper_urdf());
    FAIL() << "a mimic follower loaded as a joint without --mimic-as-joint";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "gripper.urdf:20: error: joint 'finger_2' mimics joint 'finger_1' (moves with "
              "it), but modelgen has no mimic constraint and would model it as a degree of "
              "freedom the robot does not have; leave the part it moves out with --tip LINK, "
              "make 'finger_2' fixed in a copy of the file, or keep it as an independent joint "
              "with --mimic-as-joint (docs/commands/modelgen.md, Mimic joints)");
  }
}

TEST(DescriptionWarnings, MimicFollowerWaysOut) {
  // Cut at the hand: the fingers, and the follower with them, are not modelled.
  LoadOptions cut;
  cut.tip_link = "hand";
  const RobotModel arm = load_robot_text("gripper.urdf", mimic_gripper_urdf(), cut);
  EXPECT_EQ(arm.dof(), 1);
  EXPECT_TRUE(warnings(arm).empty());
  // Asked for: the follower is a joint of its own, with a warning at its <mimic>.
  LoadOptions as_joint;
  as_joint.mimic_as_joint = true;
  const RobotModel all = load_robot_text("gripper.urdf", mimic_gripper_urdf(), as_joint);
  EXPECT_EQ(all.dof(), 3);
  const std::vector<std::string> found = warnings(all);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0],
            "gripper.urdf:20: warning: joint 'finger_2' mimics joint 'finger_1' but is modelled "
            "as an independent degree of freedom, as --mimic-as-joint asks");
}

TEST(DescriptionWarnings, ShippedPandaHasTwoIndependentFingersWithoutWarning) {
  // robots/urdf/SOURCES.md: the shipped copy has its <mimic> replaced by a comment.
  const RobotModel model = load_robot(test::source_path("robots/urdf/franka_panda.urdf"));
  EXPECT_EQ(model.dof(), 9);
  EXPECT_TRUE(warnings(model).empty());
}

TEST(DescriptionWarnings, ContinuousJointHasNoPositionLimit) {
  // urdfdom drops lower and upper on a continuous joint; the velocity limit stays.
  const RobotModel model =
      load_robot_text("spin.urdf", one_joint_urdf("continuous",
                                                  "lower=\"-1\" upper=\"1\" velocity=\"2\" "
                                                  "effort=\"5\""));
  ASSERT_EQ(model.joints.size(), 1u);
  const JointLimits& limits = model.joints[0].limits;
  EXPECT_TRUE(limits.continuous);
  EXPECT_FALSE(limits.q_lower.has_value());
  EXPECT_FALSE(limits.q_upper.has_value());
  EXPECT_EQ(limits.dq.value_or(0), 2);
  EXPECT_EQ(limits.effort.value_or(0), 5);
  const RobotModel revolute =
      load_robot_text("arm.urdf", one_joint_urdf("revolute",
                                                 "lower=\"-1\" upper=\"1\" velocity=\"2\" "
                                                 "effort=\"5\""));
  EXPECT_FALSE(revolute.joints[0].limits.continuous);
  EXPECT_TRUE(warnings(revolute).empty());
}

TEST(DescriptionWarnings, UrdfLimitsInDegreesAndMassInGrams) {
  const RobotModel model = load_robot_text(
      "arm.urdf",
      one_joint_urdf("revolute", "lower=\"-128\" upper=\"6\" velocity=\"180\" effort=\"5\"",
                     "25000"));
  const std::vector<std::string> found = warnings(model);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0],
            "arm.urdf:6: warning: link 'l1': mass value is 25000 kg, above 10000 kg; "
            "masses are in kg: grams?");
  EXPECT_EQ(found[1],
            "arm.urdf:14: warning: joint 'j1': limit lower is -128 rad, more than one "
            "turn (2 pi) to that side; limits are in radians: degrees?");
  EXPECT_EQ(found[2],
            "arm.urdf:14: warning: joint 'j1': limit velocity is 180 rad/s, above 50 "
            "rad/s; velocity limits are in rad/s: degrees per second?");
  // 2 pi as UR writes it (6.28318530718, a little above), 50 rad/s and 10 t are plausible.
  EXPECT_TRUE(
      warnings(load_robot_text("arm.urdf", one_joint_urdf("revolute",
                                                          "lower=\"-6.28318530718\" upper=\"1\" "
                                                          "velocity=\"50\" effort=\"5\"",
                                                          "10000")))
          .empty());
  // A prismatic joint's limits are metres: no angle check.
  EXPECT_TRUE(warnings(load_robot_text("arm.urdf", one_joint_urdf("prismatic",
                                                                  "lower=\"0\" upper=\"7\" "
                                                                  "velocity=\"1\" effort=\"5\"")))
                  .empty());
}

// FloBaRoID's kuka_lwr4.urdf (robots-ref) has a joint with two <origin>: urdfdom takes the
// first, so modelgen does too, with a warning at the second naming the first's line.
TEST(DescriptionWarnings, SecondJointOriginIsIgnoredWithAWarning) {
  const std::string text =
      "<robot name=\"arm\">\n"                                               // 1
      "  <link name=\"base\"/>\n"                                            // 2
      "  <link name=\"l1\"/>\n"                                              // 3
      "  <joint name=\"j1\" type=\"revolute\">\n"                            // 4
      "    <origin xyz=\"-0.25 0 1\"/>\n"                                    // 5
      "    <origin xyz=\"0 0 0\"/>\n"                                        // 6
      "    <parent link=\"base\"/>\n"                                        // 7
      "    <child link=\"l1\"/>\n"                                           // 8
      "    <axis xyz=\"0 0 1\"/>\n"                                          // 9
      "    <limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/>\n"  // 10
      "  </joint>\n"
      "</robot>\n";
  const RobotModel model = load_robot_text("lwr.urdf", text);
  const std::vector<std::string> found = warnings(model);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0],
            "lwr.urdf:6: warning: joint 'j1' has a second <origin>; the first (line 5) is used "
            "and this one ignored, as urdfdom and ROS do; delete the one you did not mean");
  ASSERT_EQ(model.tree.bodies.size(), 1u);
  EXPECT_EQ(model.tree.bodies[0].fixed.translation, (std::array<double, 3>{-0.25, 0, 1}));
}

// Beyond one turn, a limit is flagged only when it reads as degrees: a whole or half number,
// or a value that is neither a converted whole number of degrees nor a multiple of pi/4.
TEST(DescriptionWarnings, MultiTurnRadiansAreNotTakenForDegrees) {
  // The value as the upper limit, or as the lower one when negative.
  const auto flagged = [](const std::string& value) {
    const bool negative = value.front() == '-';
    const std::string limit = "lower=\"" + (negative ? value : "-1") + "\" upper=\"" +
                              (negative ? "1" : value) + "\" velocity=\"2\" effort=\"5\"";
    return !warnings(load_robot_text("arm.urdf", one_joint_urdf("revolute", limit))).empty();
  };
  // 15 pi (2700 degrees, the COMAU Smart Six wrist, robots/comau_smart_six.yaml), 4 pi to 1e-9
  // and to two decimals, 2.5 pi to two decimals, 350 degrees in radians.
  for (const char* radians :
       {"47.1238898", "-47.1238898", "12.566370614", "12.57", "7.85", "6.10865238198"}) {
    EXPECT_FALSE(flagged(radians)) << radians;
  }
  // Whole and half numbers as degrees are written, and a value no radian limit has.
  for (const char* degrees : {"128", "-128", "170.5", "2700", "355", "7", "10.3"}) {
    EXPECT_TRUE(flagged(degrees)) << degrees;
  }
}

TEST(DescriptionWarnings, ShippedComauWristIsNotFlagged) {
  const RobotModel model = load_robot(test::source_path("robots/comau_smart_six.yaml"));
  EXPECT_TRUE(warnings(model).empty());
  EXPECT_NEAR(model.joints[5].limits.q_upper.value_or(0), 15 * 3.141592653589793, 1e-6);
}

// A 2 kg rod 0.5 m long along x, centre of mass at 0.25 m: about its centre iyy = izz =
// m l^2 / 12 = 0.0416667 kg m^2, ixx about 0. Its mass lies sqrt(trace / 2m) = 0.144 m from the
// centre (rms), 0.58 times its size 0.25 m. Written in g m^2 (x 1000) that is 4.56 m, 18 times;
// in kg mm^2 (x 1e6) 144 m.
std::string rod_urdf(const std::string& iyy) {
  return "<robot name=\"rod\">\n"              // 1
         "  <link name=\"base\"/>\n"           // 2
         "  <link name=\"l1\">\n"              // 3
         "    <inertial>\n"                    // 4
         "      <origin xyz=\"0.25 0 0\"/>\n"  // 5
         "      <mass value=\"2\"/>\n"         // 6
         "      <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"" +
         iyy + "\" iyz=\"0\" izz=\"" + iyy +
         "\"/>\n"  // 7
         "    </inertial>\n"
         "  </link>\n"
         "  <joint name=\"j1\" type=\"revolute\">\n"
         "    <parent link=\"base\"/><child link=\"l1\"/>\n"
         "    <axis xyz=\"0 0 1\"/>\n"
         "    <limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"1\"/>\n"
         "  </joint>\n"
         "</robot>\n";
}

TEST(DescriptionWarnings, InertiaTooLargeForTheLinkNamesTheLikelyUnit) {
  EXPECT_TRUE(warnings(load_robot_text("rod.urdf", rod_urdf("0.0416667"))).empty());
  const std::vector<std::string> grams = warnings(load_robot_text("rod.urdf", rod_urdf("41.6667")));
  ASSERT_EQ(grams.size(), 1u);
  EXPECT_EQ(grams[0],
            "rod.urdf:7: warning: link 'l1': moments of inertia about the centre of "
            "mass summing to 83.3 kg m^2 for a mass of 2 kg put its mass 4.56 m from its centre "
            "(rms), more than 10 times the link's size of 0.25 m (its farthest child joint or "
            "centre of mass, at least 0.1 m); inertias are in kg m^2: g m^2 or kg cm^2?");
  const std::vector<std::string> mm = warnings(load_robot_text("rod.urdf", rod_urdf("41666.7")));
  ASSERT_EQ(mm.size(), 1u);
  EXPECT_NE(mm[0].find("put its mass 144 m from its centre"), std::string::npos) << mm[0];
  EXPECT_NE(mm[0].find("inertias are in kg m^2: kg mm^2?"), std::string::npos) << mm[0];
}

// The same rod as MDH 'known' values about the frame origin: the parallel-axis theorem gives
// XX = 0, YY = ZZ = 0.0416667 + 2 * 0.25^2 = 0.1666667 kg m^2, MX = 0.5 kg m; in g m^2 the
// moments (not the first moments) are 1000 times larger: 166.6667, and about the centre of mass
// 166.6667 - 0.125 = 166.5417 each.
TEST(DescriptionWarnings, MdhInertiaTooLargeForTheLink) {
  const auto rod = [](const std::string& yy) {
    return load_robot_text("rod.yaml",
                           "name: rod\n"
                           "joints:\n"
                           "  - {name: J1, type: revolute, ant: 0, alpha: 0, d: 0, theta: 0, "
                           "r: 0}\n"
                           "known: {XX1: 0, XY1: 0, XZ1: 0, YY1: " +
                               yy + ", YZ1: 0, ZZ1: " + yy +
                               ", MX1: 0.5, MY1: 0, MZ1: 0, M1: 2}\n");
  };
  EXPECT_TRUE(warnings(rod("0.1666667")).empty());
  const std::vector<std::string> found = warnings(rod("166.6667"));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0],
            "rod.yaml:4:9: warning: link 1 in 'known' (XX1, YY1, ZZ1): moments of inertia about "
            "the centre of mass summing to 333 kg m^2 for a mass of 2 kg put its mass 9.13 m "
            "from its centre (rms), more than 10 times the link's size of 0.25 m (its farthest "
            "child joint or centre of mass, at least 0.1 m); inertias are in kg m^2: g m^2 or "
            "kg cm^2?");
}

TEST(DescriptionWarnings, MdhLimitsInDegreesAndMassInGrams) {
  const RobotModel model = load_robot_text("arm.yaml",
                                           "name: arm\n"
                                           "joints:\n"
                                           "  - {name: J1, type: revolute, ant: 0, alpha: 0, d: 0, "
                                           "theta: 0, r: 0,\n"
                                           "     limits: {q: [-170, 170], dq: 3}}\n"
                                           "  - {name: J2, type: revolute, alpha: 0, d: 0.5, "
                                           "theta: 0, r: 0,\n"
                                           "     limits: {q: [-1, 1], dq: 120}}\n"
                                           "known: {M2: 30000}\n");
  const std::vector<std::string> found = warnings(model);
  ASSERT_EQ(found.size(), 4u);
  EXPECT_EQ(found[0],
            "arm.yaml:4:18: warning: joint 1: limits.q lower is -170 rad, more than "
            "one turn (2 pi) to that side; limits are in radians: degrees?");
  EXPECT_EQ(found[1],
            "arm.yaml:4:18: warning: joint 1: limits.q upper is 170 rad, more than "
            "one turn (2 pi) to that side; limits are in radians: degrees?");
  EXPECT_EQ(found[2],
            "arm.yaml:6:31: warning: joint 2: limits.dq is 120 rad/s, above 50 rad/s; "
            "velocity limits are in rad/s: degrees per second?");
  EXPECT_EQ(found[3],
            "arm.yaml:7:13: warning: known.M2 is 30000 kg, above 10000 kg; masses are "
            "in kg: grams?");
}

}  // namespace
}  // namespace modelgen
