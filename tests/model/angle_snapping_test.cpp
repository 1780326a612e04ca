// Rounded quarter turns (1.5708, 1.57075, 3.14159 for pi/2 and pi) in descriptions: the loaders
// take them as exact within --angle-tolerance and say so, and base-parameter rank decisions
// ignore effects below the angles' precision. The reference is the same robot written with
// exact angles (tests/model/rounded_angles/exact_arm.urdf), not the loader's own output.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/load_robot.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "runtime/model/urdf_loader.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr const char* kRounded = "tests/model/rounded_angles/rounded_arm.urdf";
constexpr const char* kExact = "tests/model/rounded_angles/exact_arm.urdf";

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// 1-based line of the first occurrence of `needle` at or after the line holding `after`.
int line_of(const std::string& text, const std::string& needle, const std::string& after = "") {
  const std::size_t start = after.empty() ? 0 : text.find(after);
  const std::size_t at = text.find(needle, start);
  if (start == std::string::npos || at == std::string::npos) return -1;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

std::vector<std::string> base_names(const BaseParameterSet& base) {
  std::vector<std::string> names;
  for (const BaseParameter& b : base.params) names.push_back(b.name);
  return names;
}

RobotModel load_with_tolerance(const std::string& relative, double tolerance) {
  LoadOptions options;
  options.angle_tolerance = tolerance;
  return load_robot(test::source_path(relative), options);
}

TEST(AngleSnapping, RoundedUrdfGivesTheExactGeometry) {
  const RobotModel rounded = load_robot(test::source_path(kRounded));
  const RobotModel exact = load_robot(test::source_path(kExact));
  ASSERT_EQ(rounded.tree.bodies.size(), exact.tree.bodies.size());
  for (std::size_t j = 0; j < exact.tree.bodies.size(); ++j) {
    const Body& r = rounded.tree.bodies[j];
    const Body& e = exact.tree.bodies[j];
    SCOPED_TRACE(e.name);
    // Bit for bit: the snapped rotations are signed permutations, as the exact ones.
    EXPECT_EQ(r.fixed.rotation, e.fixed.rotation);
    EXPECT_EQ(r.fixed.translation, e.fixed.translation);
    EXPECT_EQ(r.axis, e.axis);
  }
  for (std::size_t k = 0; k < exact.known_values.size(); ++k) {
    ASSERT_EQ(rounded.known_values[k].has_value(), exact.known_values[k].has_value());
    if (exact.known_values[k]) {
      EXPECT_NEAR(*rounded.known_values[k], *exact.known_values[k], 1e-12)
          << exact.tree.params[k].name;
    }
  }
}

TEST(AngleSnapping, RoundedUrdfHasTheBaseParametersOfTheExactOne) {
  const BaseParameterSet exact = derive_base_parameters(load_robot(test::source_path(kExact)).tree);
  const BaseParameterSet rounded =
      derive_base_parameters(load_robot(test::source_path(kRounded)).tree);
  EXPECT_EQ(base_names(rounded), base_names(exact));
  ASSERT_EQ(rounded.K.rows(), exact.K.rows());
  EXPECT_EQ(rounded.K, exact.K);  // same geometry, same relations, digit for digit
}

TEST(AngleSnapping, NotesNameEveryRoundedValueWithItsLine) {
  const std::string path = test::source_path(kRounded);
  const std::string text = file_text(path);
  const RobotModel rounded = load_robot(path);
  // Written rounded: joint origins 3.14159 | 1.57075 1.57075 | -3.1416 -1.5708 | -1.5708 |
  // -1.57075 | 1.5708 | 3.14159, the axis 0 0.00003 1 of wrist_bend, and the inertial origin
  // 1.5708 of each of the seven links.
  ASSERT_EQ(rounded.notes.size(), 9u + 1u + 7u);
  auto count_with = [&](const std::string& part) {
    return std::count_if(rounded.notes.begin(), rounded.notes.end(),
                         [&](const DescriptionNote& n) { return n.message.find(part) != std::string::npos; });
  };
  EXPECT_EQ(count_with("inertial origin rpy roll 1.5708 taken as pi/2"), 7);
  EXPECT_EQ(count_with("joint 'upper_arm': origin rpy"), 2);
  EXPECT_EQ(count_with("joint 'elbow': origin rpy roll -3.1416 taken as -pi "), 1);
  EXPECT_EQ(count_with("joint 'tool_mount': origin rpy pitch 3.14159 taken as pi "), 1);
  EXPECT_EQ(count_with("joint 'wrist_bend': axis xyz 0 3e-05 1 taken as 0 0 1"), 1);
  for (const DescriptionNote& note : rounded.notes) {
    EXPECT_EQ(note.where.file, path);
    EXPECT_NE(note.message.find("--angle-tolerance"), std::string::npos) << note.message;
    if (note.message.find("joint 'forearm'") != std::string::npos) {
      EXPECT_EQ(note.where.line, line_of(text, "<origin", "name=\"forearm\""));
    }
    if (note.message.find("axis") != std::string::npos) {
      EXPECT_EQ(note.where.line, line_of(text, "<axis", "name=\"wrist_bend\""));
    }
  }
  // Lines in file order.
  EXPECT_TRUE(std::is_sorted(rounded.notes.begin(), rounded.notes.end(),
                             [](const DescriptionNote& a, const DescriptionNote& b) {
                               return a.where.line < b.where.line;
                             }));
  EXPECT_TRUE(load_robot(test::source_path(kExact)).notes.empty());
}

TEST(AngleSnapping, ZeroToleranceTakesEveryAngleAsWritten) {
  const RobotModel exact = load_robot(test::source_path(kExact));
  const RobotModel as_written = load_with_tolerance(kRounded, 0);
  EXPECT_TRUE(as_written.notes.empty());
  EXPECT_EQ(as_written.tree.angle_precision, 0);
  // The tilts are in the geometry: 1.57075 is 4.6e-5 rad short of pi/2.
  double largest_difference = 0;
  for (std::size_t j = 0; j < exact.tree.bodies.size(); ++j) {
    for (int i = 0; i < 9; ++i) {
      largest_difference =
          std::max(largest_difference, std::abs(as_written.tree.bodies[j].fixed.rotation[i] -
                                                exact.tree.bodies[j].fixed.rotation[i]));
    }
  }
  EXPECT_GT(largest_difference, 1e-5);
  EXPECT_LT(largest_difference, 1e-3);
  // And the tilts make parameters "identifiable" that the real arm cannot identify.
  EXPECT_GT(derive_base_parameters(as_written.tree).params.size(),
            derive_base_parameters(exact.tree).params.size());
}

TEST(AngleSnapping, AnglesBeyondTheToleranceStayAsWritten) {
  const RobotModel model = load_with_tolerance(kRounded, 1e-5);
  // 1.5708 (3.7e-6 off) and 3.14159 (2.7e-6 off) are snapped, 1.57075 (4.6e-5 off) and the
  // 3e-5 axis component are not.
  for (const DescriptionNote& note : model.notes) {
    EXPECT_EQ(note.message.find("1.57075"), std::string::npos) << note.message;
    EXPECT_EQ(note.message.find("axis"), std::string::npos) << note.message;
  }
  EXPECT_EQ(model.notes.size(), 7u + 6u);
}

// The MDH table has the same trap when alpha or theta are written as decimals.
TEST(AngleSnapping, MdhDecimalQuarterTurnsBecomeExactFractionsOfPi) {
  const std::string rows =
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0.4}\n"
      "  - {type: revolute, alpha: %A, d: 0.1, theta: %T, r: 0}\n"
      "  - {type: revolute, alpha: 0, d: 0.5, theta: 0, r: 0}\n";
  auto yaml = [&](const std::string& alpha, const std::string& theta) {
    std::string text = "name: arm\njoints:\n" + rows;
    text.replace(text.find("%A"), 2, alpha);
    text.replace(text.find("%T"), 2, theta);
    return text;
  };
  const RobotModel exact = load_mdh_yaml("exact.yaml", yaml("pi/2", "-pi/2"));
  const RobotModel rounded = load_mdh_yaml("rounded.yaml", yaml("1.5708", "-1.57075"));
  const MdhParameters& mdh = *rounded.joints[1].mdh;
  EXPECT_TRUE(mdh.alpha.is_pi_fraction);
  EXPECT_EQ(mdh.alpha.numerator, 1);
  EXPECT_EQ(mdh.alpha.denominator, 2);
  EXPECT_EQ(mdh.theta.numerator, -1);
  EXPECT_EQ(mdh.theta.denominator, 2);
  EXPECT_EQ(rounded.tree.bodies[1].fixed.rotation, exact.tree.bodies[1].fixed.rotation);
  ASSERT_EQ(rounded.notes.size(), 2u);
  EXPECT_EQ(rounded.notes[0].where.line, 4);
  EXPECT_NE(rounded.notes[0].message.find("joint 2: alpha 1.5708 taken as pi/2"), std::string::npos)
      << rounded.notes[0].message;
  EXPECT_NE(rounded.notes[1].message.find("joint 2: theta -1.57075 taken as -pi/2"),
            std::string::npos)
      << rounded.notes[1].message;
  EXPECT_EQ(base_names(derive_base_parameters(rounded.tree)),
            base_names(derive_base_parameters(exact.tree)));

  const RobotModel as_written = load_mdh_yaml("rounded.yaml", yaml("1.5708", "-1.57075"), 0);
  EXPECT_FALSE(as_written.joints[1].mdh->alpha.is_pi_fraction);
  EXPECT_TRUE(as_written.notes.empty());
}

// Rank decisions take the geometry as known to the angle precision: the rounded arm read with
// every tilt as written, but declared precise to 1e-4 rad, has the exact arm's base parameters
// (tilts of 3e-6..5e-5 rad move columns by that much relative to ordinary ones, which is not
// identifiable on a real robot); declared exact, it has more.
TEST(AngleSnapping, RankDecisionsIgnoreEffectsBelowTheAnglePrecision) {
  const BaseParameterSet exact = derive_base_parameters(load_robot(test::source_path(kExact)).tree);
  RobotModel tilted = load_with_tolerance(kRounded, 0);
  const std::size_t as_exact_geometry = derive_base_parameters(tilted.tree).params.size();
  EXPECT_GT(as_exact_geometry, exact.params.size());
  tilted.tree.angle_precision = 1e-4;
  // The same parameters are kept; their relations still carry the tilts (coefficients of
  // ~1e-6, hence more names with R): only snapping the angles removes those.
  auto built_on = [](const BaseParameterSet& base) {
    std::vector<int> indices;
    for (const BaseParameter& b : base.params) indices.push_back(b.standard_index);
    return indices;
  };
  EXPECT_EQ(built_on(derive_base_parameters(tilted.tree)), built_on(exact));
}

// ../shared/robots-ref/comau_smart_six.urdf (no license, so not in this project) writes rpy
// 1.57075 and 3.14159. Its kinematics are the COMAU Smart Six's: 58 base parameters.
TEST(AngleSnapping, ComauSmartSixHas58BaseParameters) {
  const std::string path = test::shared_path("robots-ref/comau_smart_six.urdf");
  if (!std::ifstream(path)) GTEST_SKIP() << "no " << path << " (../shared is not there)";
  const RobotModel model = load_robot(path);
  EXPECT_FALSE(model.notes.empty());
  EXPECT_EQ(derive_base_parameters(model.tree).params.size(), 58u);
  LoadOptions as_written;
  as_written.angle_tolerance = 0;
  EXPECT_EQ(derive_base_parameters(load_robot(path, as_written).tree).params.size(), 60u);
}

}  // namespace
}  // namespace modelgen
