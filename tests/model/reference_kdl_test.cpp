// Diff-tests the numeric reference (ReferenceDynamics::inverse_dynamics, recursive Newton-Euler)
// against Orocos KDL's ChainIdSolver_RNE: every shipped serial robot (and a synthetic chain with
// prismatic joints and skew axes), 1000 seeded random states each with random physical
// parameters, agreement to 1e-9 relative in the infinity norm. KDL has no drive model, so drive
// inertia, friction and offset are added to its torques here from the same parameter vector.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/robot_model.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr int kStates = 1000;
constexpr int kPerturbedStates = 20;
constexpr double kTolerance = 1e-9;

// ---------------------------------------------------------------------------------------------
// The comparison.

struct Comparison {
  double worst = 0;  // over kStates states, exact parameters
  int worst_state = -1;
  double perturbed = 0;  // over kPerturbedStates states, one body 1% heavier on the KDL side
};

int body_of_dof(const RigidBodyTree& tree, int dof_index) {
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    if (tree.bodies[j].dof_index == dof_index) return static_cast<int>(j);
  }
  return -1;
}

Comparison compare_with_kdl(const modelgen::RobotModel& model, std::uint64_t seed) {
  const RigidBodyTree& tree = model.tree;
  const ReferenceDynamics reference(tree);
  test::Random rng(seed);
  Comparison out;
  for (int k = 0; k < kStates; ++k) {
    const Eigen::VectorXd p = test::random_physical_parameters(tree, rng);
    const test::JointState s = test::random_state(model, rng);
    const Eigen::VectorXd tau_ref = reference.inverse_dynamics(s.q, s.dq, s.ddq, p);
    const Eigen::VectorXd tau_kdl = test::kdl_inverse_dynamics(tree, s.q, s.dq, s.ddq, p);
    const double err = test::relative_error(tau_ref, tau_kdl);
    if (!(err <= out.worst)) {  // also catches NaN
      out.worst = err;
      out.worst_state = k;
    }
  }
  // Not vacuous: the body on the second moving joint (the first one, for a single joint) made 1%
  // denser on the KDL side only must show. Denser, not just M + 1%: with MS and J held, M acts
  // only through the acceleration of the body's origin, and gives no torque when that origin
  // lies on every preceding axis (TX-40, iiwa and Panda body 2: M2 is not identifiable).
  const int body = body_of_dof(tree, tree.dof > 1 ? 1 : 0);
  std::vector<Eigen::Index> inertial_params;
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    if (tree.params[k].body == body && test::inertial_slot(tree.params[k].kind) >= 0) {
      inertial_params.push_back(static_cast<Eigen::Index>(k));
    }
  }
  for (int k = 0; k < kPerturbedStates; ++k) {
    const Eigen::VectorXd p = test::random_physical_parameters(tree, rng);
    Eigen::VectorXd p_perturbed = p;
    for (Eigen::Index i : inertial_params) p_perturbed[i] *= 1.01;
    const test::JointState s = test::random_state(model, rng);
    const Eigen::VectorXd tau_ref = reference.inverse_dynamics(s.q, s.dq, s.ddq, p);
    const Eigen::VectorXd tau_kdl = test::kdl_inverse_dynamics(tree, s.q, s.dq, s.ddq, p_perturbed);
    out.perturbed = std::max(out.perturbed, test::relative_error(tau_ref, tau_kdl));
  }
  return out;
}

std::string scientific(double x) {
  std::ostringstream text;
  text.precision(3);
  text << std::scientific << x;
  return text.str();
}

void report(const std::string& label, const Comparison& c) {
  std::cout << "[ KDL      ] " << label << ": worst relative error " << scientific(c.worst)
            << " over " << kStates << " states (state " << c.worst_state
            << "); one body 1% heavier: " << scientific(c.perturbed) << std::endl;
  ::testing::Test::RecordProperty("worst_relative_error", scientific(c.worst));
  ::testing::Test::RecordProperty("perturbed_mass_relative_error", scientific(c.perturbed));
}

void expect_agreement(const std::string& label, const Comparison& c) {
  report(label, c);
  EXPECT_LE(c.worst, kTolerance) << label << ": worst at state " << c.worst_state;
  EXPECT_GT(c.perturbed, 1e-5) << label << ": a 1% heavier body went unnoticed";
}

// ---------------------------------------------------------------------------------------------
// Shipped serial robots.

struct RobotCase {
  std::string label;
  std::string file;
  std::string tip_link;
  int dof;
  std::uint64_t seed;
};

void PrintTo(const RobotCase& c, std::ostream* os) { *os << c.file; }

const RobotCase kRobots[] = {
    {"tx40", "robots/tx40.yaml", "", 6, 0x4b444c01},
    {"kr150", "robots/kr150.yaml", "", 6, 0x4b444c02},
    {"ur5", "robots/urdf/ur5.urdf", "", 6, 0x4b444c03},
    {"kuka_iiwa14_drake", "robots/urdf/kuka_iiwa14_drake.urdf", "", 7, 0x4b444c04},
    {"kuka_kr150_2", "robots/urdf/kuka_kr150_2.urdf", "", 6, 0x4b444c05},
    // The full Panda is a tree (two finger joints); its arm up to link 7 is a chain.
    {"franka_panda_link7", "robots/urdf/franka_panda.urdf", "panda_link7", 7, 0x4b444c06},
};

class ReferenceKdlTest : public ::testing::TestWithParam<RobotCase> {};

TEST_P(ReferenceKdlTest, InverseDynamicsMatchesKdlRne) {
  const RobotCase& robot = GetParam();
  modelgen::LoadOptions options;
  options.tip_link = robot.tip_link;
  const modelgen::RobotModel model = modelgen::load_robot(test::source_path(robot.file), options);
  ASSERT_EQ(model.dof(), robot.dof);
  ASSERT_TRUE(test::is_serial(model.tree)) << robot.file << " is not a serial chain";
  expect_agreement(robot.label, compare_with_kdl(model, robot.seed));
}

INSTANTIATE_TEST_SUITE_P(ShippedSerialRobots, ReferenceKdlTest, ::testing::ValuesIn(kRobots),
                         [](const ::testing::TestParamInfo<RobotCase>& info) {
                           return info.param.label;
                         });

// ---------------------------------------------------------------------------------------------
// A synthetic chain the shipped robots do not cover: prismatic joints, skew axes, arbitrary fixed
// transforms, a fixed body mid-chain, tilted gravity and asymmetric friction.

TEST(ReferenceKdlSyntheticTest, PrismaticJointsSkewAxesAndAsymmetricFriction) {
  test::Random rng(0x4b444c10);
  const JointType kTypes[] = {JointType::kRevolute, JointType::kPrismatic, JointType::kRevolute,
                              JointType::kFixed,    JointType::kPrismatic, JointType::kRevolute,
                              JointType::kRevolute};
  modelgen::RobotModel model;
  model.name = "synthetic";
  model.tree.gravity = {1.5, -2.0, -9.3};
  for (JointType type : kTypes) {
    Body body;
    body.name = "b";
    body.name += std::to_string(model.tree.bodies.size() + 1);
    body.parent = static_cast<int>(model.tree.bodies.size()) - 1;
    body.type = type;
    const Eigen::Matrix3d R = test::random_rotation(rng);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) body.fixed.rotation[3 * r + c] = R(r, c);
      body.fixed.translation[r] = rng.uniform(-0.5, 0.5);
    }
    if (type != JointType::kFixed) {
      body.dof_index = model.tree.dof++;
      const Eigen::Vector3d axis = rng.vector(3, -1, 1).normalized();
      body.axis = {axis.x(), axis.y(), axis.z()};
    }
    model.tree.bodies.push_back(body);
  }
  model.joints.resize(model.tree.bodies.size());
  model.friction.asymmetric = true;
  modelgen::build_standard_parameters(model);
  expect_agreement("synthetic", compare_with_kdl(model, 0x4b444c11));
}

}  // namespace
}  // namespace modelgen
