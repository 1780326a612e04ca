// robot_identifier: every description's robot name made a usable C++ namespace, good names kept,
// each change said in a note (issue 29).

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/robot_model.hpp"

namespace modelgen {
namespace {

TEST(RobotIdentifier, MakesEveryNameAUsableNamespaceAndKeepsGoodOnes) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"KR150", "KR150"},  // an identifier stays as written
      {"kuka_kr150_2", "kuka_kr150_2"},
      {"GEN3-6DOF_NO-VISION_URDF_ARM_V01", "gen3_6dof_no_vision_urdf_arm_v01"},
      {"6axis", "robot_6axis"},
      {"class", "class_robot"},
      {"std", "std_robot"},
      {"__x__y", "x_y"},
      {"my robot (v2)", "my_robot_v2"},
      {"-", "robot"},
      {"", "robot"},
      {"Roboter\xc3\x84rm", "roboter_rm"}};
  for (const auto& [name, expected] : cases) {
    std::vector<DescriptionNote> notes;
    const std::string id = robot_identifier(name, {"r.urdf", 1, 1}, notes);
    EXPECT_EQ(id, expected) << name;
    EXPECT_NO_THROW(check_robot_name(id, {"r.urdf"})) << name << " -> " << id;
    EXPECT_EQ(notes.size(), name == expected ? 0u : 1u) << name;
  }
}

}  // namespace
}  // namespace modelgen
