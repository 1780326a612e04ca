// Diff-tests the numeric reference (ReferenceDynamics::inverse_dynamics, recursive Newton-Euler)
// against Orocos KDL's ChainIdSolver_RNE: every shipped serial robot (and a synthetic chain with
// prismatic joints and skew axes), 1000 seeded random states each with random physical
// parameters, agreement to 1e-9 relative in the infinity norm. KDL has no drive model, so drive
// inertia, friction and offset are added to its torques here from the same parameter vector.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <kdl/chain.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/joint.hpp>
#include <kdl/rigidbodyinertia.hpp>
#include <kdl/rotationalinertia.hpp>
#include <kdl/segment.hpp>

#include "generator/description/load_robot.hpp"
#include "generator/description/robot_model.hpp"
#include "modelgen/reference_dynamics.hpp"
#include "modelgen/rigid_body_tree.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr int kStates = 1000;
constexpr int kPerturbedStates = 20;
constexpr double kTolerance = 1e-9;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// RigidBodyTree + standard parameters -> KDL::Chain.

// Inertial standard parameters of one body, about the origin of its frame, in its frame.
struct BodyInertial {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  Eigen::Vector3d MS = Eigen::Vector3d::Zero();
  double M = 0;
};

// Position of an inertial parameter in standard_from_inertial's order (XX XY XZ YY YZ ZZ MX MY MZ
// M), or -1 for a drive parameter.
int inertial_slot(ParamKind kind) {
  static constexpr ParamKind kOrder[] = {
      ParamKind::kXX, ParamKind::kXY, ParamKind::kXZ, ParamKind::kYY, ParamKind::kYZ,
      ParamKind::kZZ, ParamKind::kMX, ParamKind::kMY, ParamKind::kMZ, ParamKind::kM};
  for (int slot = 0; slot < 10; ++slot) {
    if (kOrder[slot] == kind) return slot;
  }
  return -1;
}

std::vector<BodyInertial> body_inertials(const RigidBodyTree& tree, const Eigen::VectorXd& p) {
  std::vector<std::array<double, 10>> standard(tree.bodies.size(), std::array<double, 10>{});
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const int slot = inertial_slot(tree.params[k].kind);
    if (slot >= 0) standard[tree.params[k].body][slot] += p[static_cast<Eigen::Index>(k)];
  }
  std::vector<BodyInertial> out(tree.bodies.size());
  for (std::size_t j = 0; j < out.size(); ++j) {
    const std::array<double, 10>& s = standard[j];
    out[j].J << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
    out[j].MS << s[6], s[7], s[8];
    out[j].M = s[9];
  }
  return out;
}

KDL::Frame to_kdl(const Frame& f) {
  const auto& r = f.rotation;  // row-major, as KDL::Rotation's constructor takes it
  return KDL::Frame(KDL::Rotation(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]),
                    KDL::Vector(f.translation[0], f.translation[1], f.translation[2]));
}

// KDL wants mass, centre of mass and the tensor about the centre of mass; the standard
// parameters hold the tensor about the frame origin: parallel-axis theorem backwards,
// I_c = J_O - m (|c|^2 1 - c c^T) with c = MS / m.
KDL::RigidBodyInertia to_kdl(const BodyInertial& b) {
  if (b.M == 0.0) {
    if (!b.MS.isZero(0.0)) throw std::invalid_argument("first moments without mass");
    return KDL::RigidBodyInertia(
        0.0, KDL::Vector::Zero(),
        KDL::RotationalInertia(b.J(0, 0), b.J(1, 1), b.J(2, 2), b.J(0, 1), b.J(0, 2), b.J(1, 2)));
  }
  const Eigen::Vector3d c = b.MS / b.M;
  const Eigen::Matrix3d Ic =
      b.J - b.M * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  // KDL::RotationalInertia(Ixx, Iyy, Izz, Ixy, Ixz, Iyz), tensor entries.
  return KDL::RigidBodyInertia(
      b.M, KDL::Vector(c.x(), c.y(), c.z()),
      KDL::RotationalInertia(Ic(0, 0), Ic(1, 1), Ic(2, 2), Ic(0, 1), Ic(0, 2), Ic(1, 2)));
}

bool is_serial(const RigidBodyTree& tree) {
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    if (tree.bodies[j].parent != static_cast<int>(j) - 1) return false;
  }
  return true;
}

struct KdlModel {
  KDL::Chain chain;
  std::vector<int> dof_of_kdl_joint;  // modelgen dof index of each KDL joint, in chain order
};

// Frame j = parent * fixed * motion(q): in KDL a segment's pose is joint.pose(q) * f_tip and its
// inertia lives in the tip frame. So each moving body becomes a fixed segment (f_tip = fixed, no
// inertia) followed by a jointed segment (joint through the origin along the axis, identity tip,
// the body's inertia); a fixed body becomes one fixed segment carrying its inertia.
KdlModel to_kdl_chain(const RigidBodyTree& tree, const Eigen::VectorXd& p) {
  if (!is_serial(tree)) throw std::invalid_argument("KDL chains need a serial tree");
  const std::vector<BodyInertial> inertials = body_inertials(tree, p);
  KdlModel out;
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    const KDL::RigidBodyInertia inertia = to_kdl(inertials[j]);
    if (body.type == JointType::kFixed) {
      out.chain.addSegment(KDL::Segment(body.name, KDL::Joint(body.name, KDL::Joint::Fixed),
                                        to_kdl(body.fixed), inertia));
      continue;
    }
    out.chain.addSegment(KDL::Segment(body.name + "_fixed",
                                      KDL::Joint(body.name + "_fixed", KDL::Joint::Fixed),
                                      to_kdl(body.fixed), KDL::RigidBodyInertia::Zero()));
    const KDL::Joint::JointType type =
        body.type == JointType::kRevolute ? KDL::Joint::RotAxis : KDL::Joint::TransAxis;
    const KDL::Vector axis(body.axis[0], body.axis[1], body.axis[2]);
    out.chain.addSegment(KDL::Segment(body.name,
                                      KDL::Joint(body.name, KDL::Vector::Zero(), axis, type),
                                      KDL::Frame::Identity(), inertia));
    out.dof_of_kdl_joint.push_back(body.dof_index);
  }
  return out;
}

double sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

// Drive inertia, friction and offset per joint (Gautier & Briot eq. 3; asymmetric friction
// Bona & Curatella eq. 2: Fv+ dq + Fc+ for dq > 0, Fv- dq - Fc- for dq < 0).
Eigen::VectorXd drive_torques(const RigidBodyTree& tree, const Eigen::VectorXd& p,
                              const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq) {
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(tree.dof);
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const int i = tree.bodies[tree.params[k].body].dof_index;
    const double v = p[static_cast<Eigen::Index>(k)];
    switch (tree.params[k].kind) {
      case ParamKind::kIa:
        tau[i] += v * ddq[i];
        break;
      case ParamKind::kFv:
        tau[i] += v * dq[i];
        break;
      case ParamKind::kFc:
        tau[i] += v * sign(dq[i]);
        break;
      case ParamKind::kOff:
        tau[i] += v;
        break;
      case ParamKind::kFvPos:
        tau[i] += dq[i] > 0 ? v * dq[i] : 0.0;
        break;
      case ParamKind::kFvNeg:
        tau[i] += dq[i] < 0 ? v * dq[i] : 0.0;
        break;
      case ParamKind::kFcPos:
        tau[i] += dq[i] > 0 ? v : 0.0;
        break;
      case ParamKind::kFcNeg:
        tau[i] -= dq[i] < 0 ? v : 0.0;
        break;
      default:
        break;  // inertial parameters: in the KDL chain
    }
  }
  return tau;
}

// KDL's inverse dynamics plus the drive terms, in modelgen's dof order.
Eigen::VectorXd kdl_inverse_dynamics(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
                                     const Eigen::VectorXd& p) {
  const KdlModel model = to_kdl_chain(tree, p);
  const unsigned n = model.chain.getNrOfJoints();
  if (static_cast<int>(n) != tree.dof) throw std::logic_error("KDL chain has the wrong dof");
  KDL::JntArray kq(n), kdq(n), kddq(n), ktau(n);
  for (unsigned k = 0; k < n; ++k) {
    kq(k) = q[model.dof_of_kdl_joint[k]];
    kdq(k) = dq[model.dof_of_kdl_joint[k]];
    kddq(k) = ddq[model.dof_of_kdl_joint[k]];
  }
  const KDL::Vector gravity(tree.gravity[0], tree.gravity[1], tree.gravity[2]);
  KDL::ChainIdSolver_RNE solver(model.chain, gravity);
  const KDL::Wrenches no_external(model.chain.getNrOfSegments(), KDL::Wrench::Zero());
  const int status = solver.CartToJnt(kq, kdq, kddq, no_external, ktau);
  if (status < 0) {
    throw std::runtime_error("KDL ChainIdSolver_RNE failed: " + std::to_string(status));
  }
  Eigen::VectorXd tau(tree.dof);
  for (unsigned k = 0; k < n; ++k) tau[model.dof_of_kdl_joint[k]] = ktau(k);
  return tau + drive_torques(tree, p, dq, ddq);
}

// ---------------------------------------------------------------------------------------------
// Random parameters and states.

// Shoemake's uniform random unit quaternion.
Eigen::Matrix3d random_rotation(test::Random& rng) {
  const double u1 = rng.uniform(0, 1);
  const double u2 = rng.uniform(0, 2 * kPi);
  const double u3 = rng.uniform(0, 2 * kPi);
  const Eigen::Quaterniond quat(std::sqrt(u1) * std::cos(u3), std::sqrt(1 - u1) * std::sin(u2),
                                std::sqrt(1 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3));
  return quat.normalized().toRotationMatrix();
}

// A physically meaningful rigid body per tree body (mass in [0.5, 10] kg, centre of mass in
// [-0.3, 0.3]^3 m, inertia about it R diag(a, b, c) R^T with a, b, c > 0 strictly satisfying the
// triangle inequality), drive parameters in [0, 2].
Eigen::VectorXd random_parameters(const RigidBodyTree& tree, test::Random& rng) {
  std::vector<std::array<double, 10>> standard(tree.bodies.size());
  const std::array<double, 9> identity{1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (auto& s : standard) {
    const double mass = rng.uniform(0.5, 10);
    const std::array<double, 3> com{rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3),
                                    rng.uniform(-0.3, 0.3)};
    const double a = rng.uniform(0.01, 1);
    const double b = rng.uniform(0.01, 1);
    const double c = std::abs(a - b) + (a + b - std::abs(a - b)) * rng.uniform(0.05, 0.95);
    const Eigen::Matrix3d R = random_rotation(rng);
    const Eigen::Matrix3d I = R * Eigen::Vector3d(a, b, c).asDiagonal() * R.transpose();
    s = gen::standard_from_inertial(mass, com, identity,
                                    {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)});
  }
  Eigen::VectorXd p(tree.params.size());
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const int slot = inertial_slot(tree.params[k].kind);
    const double v = slot >= 0 ? standard[tree.params[k].body][slot] : rng.uniform(0, 2);
    p[static_cast<Eigen::Index>(k)] = v;
  }
  return p;
}

struct State {
  Eigen::VectorXd q, dq, ddq;
};

// q within the joint limits where both are given, else [-pi, pi] rad or [-0.5, 0.5] m.
State random_state(const gen::RobotModel& model, test::Random& rng) {
  const RigidBodyTree& tree = model.tree;
  State s;
  s.q.resize(tree.dof);
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    if (body.type == JointType::kFixed) continue;
    const double range = body.type == JointType::kRevolute ? kPi : 0.5;
    double lo = -range, hi = range;
    if (j < model.joints.size()) {
      const gen::JointLimits& limits = model.joints[j].limits;
      if (limits.q_lower && limits.q_upper) {
        lo = *limits.q_lower;
        hi = *limits.q_upper;
      }
    }
    s.q[body.dof_index] = rng.uniform(lo, hi);
  }
  s.dq = rng.vector(tree.dof, -3, 3);
  s.ddq = rng.vector(tree.dof, -10, 10);
  return s;
}

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

Comparison compare_with_kdl(const gen::RobotModel& model, std::uint64_t seed) {
  const RigidBodyTree& tree = model.tree;
  const ReferenceDynamics reference(tree);
  test::Random rng(seed);
  Comparison out;
  for (int k = 0; k < kStates; ++k) {
    const Eigen::VectorXd p = random_parameters(tree, rng);
    const State s = random_state(model, rng);
    const Eigen::VectorXd tau_ref = reference.inverse_dynamics(s.q, s.dq, s.ddq, p);
    const Eigen::VectorXd tau_kdl = kdl_inverse_dynamics(tree, s.q, s.dq, s.ddq, p);
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
    if (tree.params[k].body == body && inertial_slot(tree.params[k].kind) >= 0) {
      inertial_params.push_back(static_cast<Eigen::Index>(k));
    }
  }
  for (int k = 0; k < kPerturbedStates; ++k) {
    const Eigen::VectorXd p = random_parameters(tree, rng);
    Eigen::VectorXd p_perturbed = p;
    for (Eigen::Index i : inertial_params) p_perturbed[i] *= 1.01;
    const State s = random_state(model, rng);
    const Eigen::VectorXd tau_ref = reference.inverse_dynamics(s.q, s.dq, s.ddq, p);
    const Eigen::VectorXd tau_kdl = kdl_inverse_dynamics(tree, s.q, s.dq, s.ddq, p_perturbed);
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
  gen::LoadOptions options;
  options.tip_link = robot.tip_link;
  const gen::RobotModel model = gen::load_robot(test::source_path(robot.file), options);
  ASSERT_EQ(model.dof(), robot.dof);
  ASSERT_TRUE(is_serial(model.tree)) << robot.file << " is not a serial chain";
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
  gen::RobotModel model;
  model.name = "synthetic";
  model.tree.gravity = {1.5, -2.0, -9.3};
  for (JointType type : kTypes) {
    Body body;
    body.name = "b";
    body.name += std::to_string(model.tree.bodies.size() + 1);
    body.parent = static_cast<int>(model.tree.bodies.size()) - 1;
    body.type = type;
    const Eigen::Matrix3d R = random_rotation(rng);
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
  gen::build_standard_parameters(model);
  expect_agreement("synthetic", compare_with_kdl(model, 0x4b444c11));
}

}  // namespace
}  // namespace modelgen
