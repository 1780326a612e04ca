// Orocos KDL as an independent oracle: RigidBodyTree + standard parameters -> KDL::Chain, its
// inverse dynamics plus the drive terms KDL has no model for, and random physical parameters and
// states. The only file of the project that includes KDL.

#include "tests/support/kdl_oracle.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainfdsolver_recursive_newton_euler.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/joint.hpp>
#include <kdl/rigidbodyinertia.hpp>
#include <kdl/rotationalinertia.hpp>
#include <kdl/segment.hpp>

#include "modelgen/model/robot_model.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Inertial standard parameters of one body, about the origin of its frame, in its frame.
struct BodyInertial {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  Eigen::Vector3d MS = Eigen::Vector3d::Zero();
  double M = 0;
};

std::vector<BodyInertial> body_inertials(const RigidBodyTree& tree, const Eigen::VectorXd& p) {
  std::vector<std::array<double, 10>> standard(tree.bodies.size(), std::array<double, 10>{});
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const int slot = test::inertial_slot(tree.params[k].kind);
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
      case ParamKind::kIam:
      case ParamKind::kFvm:
      case ParamKind::kFcm: {
        // A motor driving several joints: its term on u' = c . dq reaches each joint through c
        // (Gautier & Briot eq. 26), written out here independently of the reference.
        const StandardParam& param = tree.params[k];
        const CoupledMotor* motor = coupled_motor_of(tree, param);
        double u = 0, du = 0;
        for (int l = 0; l < tree.dof; ++l) {
          u += motor->coupling[l] * dq[l];
          du += motor->coupling[l] * ddq[l];
        }
        const double term = param.kind == ParamKind::kIam   ? v * du
                            : param.kind == ParamKind::kFvm ? v * u
                                                            : v * sign(u);
        for (int l = 0; l < tree.dof; ++l) tau[l] += motor->coupling[l] * term;
        break;
      }
      default:
        break;  // inertial parameters: in the KDL chain
    }
  }
  return tau;
}

}  // namespace

bool is_serial(const RigidBodyTree& tree) {
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    if (tree.bodies[j].parent != static_cast<int>(j) - 1) return false;
  }
  return true;
}

int inertial_slot(ParamKind kind) {
  static constexpr ParamKind kOrder[] = {
      ParamKind::kXX, ParamKind::kXY, ParamKind::kXZ, ParamKind::kYY, ParamKind::kYZ,
      ParamKind::kZZ, ParamKind::kMX, ParamKind::kMY, ParamKind::kMZ, ParamKind::kM};
  for (int slot = 0; slot < 10; ++slot) {
    if (kOrder[slot] == kind) return slot;
  }
  return -1;
}

Eigen::VectorXd kdl_inverse_dynamics(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
                                     const Eigen::VectorXd& p) {
  if (q.size() != tree.dof || dq.size() != tree.dof || ddq.size() != tree.dof) {
    throw std::invalid_argument("q, dq and ddq need " + std::to_string(tree.dof) + " entries");
  }
  if (p.size() != static_cast<Eigen::Index>(tree.params.size())) {
    throw std::invalid_argument("p needs " + std::to_string(tree.params.size()) + " entries");
  }
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

Eigen::MatrixXd kdl_rigid_body_mass_matrix(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& p) {
  const KdlModel model = to_kdl_chain(tree, p);
  const unsigned n = model.chain.getNrOfJoints();
  if (static_cast<int>(n) != tree.dof || q.size() != tree.dof) {
    throw std::invalid_argument("q needs " + std::to_string(tree.dof) + " entries");
  }
  KDL::JntArray kq(n);
  for (unsigned k = 0; k < n; ++k) kq(k) = q[model.dof_of_kdl_joint[k]];
  KDL::ChainDynParam dynamics(model.chain, KDL::Vector::Zero());
  KDL::JntSpaceInertiaMatrix kM(n);
  if (dynamics.JntToMass(kq, kM) < 0) throw std::runtime_error("KDL ChainDynParam failed");
  Eigen::MatrixXd M(tree.dof, tree.dof);
  for (unsigned r = 0; r < n; ++r) {
    for (unsigned c = 0; c < n; ++c) {
      M(model.dof_of_kdl_joint[r], model.dof_of_kdl_joint[c]) = kM(r, c);
    }
  }
  return M;
}

Eigen::VectorXd kdl_rigid_body_forward_dynamics(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& dq,
                                                const Eigen::VectorXd& tau,
                                                const Eigen::VectorXd& p) {
  const KdlModel model = to_kdl_chain(tree, p);
  const unsigned n = model.chain.getNrOfJoints();
  if (static_cast<int>(n) != tree.dof || q.size() != tree.dof || dq.size() != tree.dof ||
      tau.size() != tree.dof) {
    throw std::invalid_argument("q, dq and tau need " + std::to_string(tree.dof) + " entries");
  }
  KDL::JntArray kq(n), kdq(n), ktau(n), kddq(n);
  for (unsigned k = 0; k < n; ++k) {
    kq(k) = q[model.dof_of_kdl_joint[k]];
    kdq(k) = dq[model.dof_of_kdl_joint[k]];
    ktau(k) = tau[model.dof_of_kdl_joint[k]];
  }
  KDL::ChainFdSolver_RNE solver(model.chain,
                                KDL::Vector(tree.gravity[0], tree.gravity[1], tree.gravity[2]));
  const KDL::Wrenches no_external(model.chain.getNrOfSegments(), KDL::Wrench::Zero());
  if (solver.CartToJnt(kq, kdq, ktau, no_external, kddq) < 0) {
    throw std::runtime_error("KDL ChainFdSolver_RNE failed");
  }
  Eigen::VectorXd ddq(tree.dof);
  for (unsigned k = 0; k < n; ++k) ddq[model.dof_of_kdl_joint[k]] = kddq(k);
  return ddq;
}

// Shoemake's uniform random unit quaternion.
Eigen::Matrix3d random_rotation(Random& rng) {
  const double u1 = rng.uniform(0, 1);
  const double u2 = rng.uniform(0, 2 * kPi);
  const double u3 = rng.uniform(0, 2 * kPi);
  const Eigen::Quaterniond quat(std::sqrt(u1) * std::cos(u3), std::sqrt(1 - u1) * std::sin(u2),
                                std::sqrt(1 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3));
  return quat.normalized().toRotationMatrix();
}

Eigen::VectorXd random_physical_parameters(const RigidBodyTree& tree, Random& rng) {
  std::vector<std::array<double, 10>> standard(tree.bodies.size());
  const std::array<double, 9> identity{1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (auto& s : standard) {
    const double mass = rng.uniform(0.5, 10);
    const std::array<double, 3> com{rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3),
                                    rng.uniform(-0.3, 0.3)};
    // Principal moments of a real body: each at most the sum of the other two.
    const double a = rng.uniform(0.01, 1);
    const double b = rng.uniform(0.01, 1);
    const double c = std::abs(a - b) + (a + b - std::abs(a - b)) * rng.uniform(0.05, 0.95);
    const Eigen::Matrix3d R = random_rotation(rng);
    const Eigen::Matrix3d I = R * Eigen::Vector3d(a, b, c).asDiagonal() * R.transpose();
    s = modelgen::standard_from_inertial(mass, com, identity,
                                    {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)});
  }
  Eigen::VectorXd p(tree.params.size());
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const int slot = test::inertial_slot(tree.params[k].kind);
    const double v = slot >= 0 ? standard[tree.params[k].body][slot] : rng.uniform(0, 2);
    p[static_cast<Eigen::Index>(k)] = v;
  }
  return p;
}

JointState random_state(const modelgen::RobotModel& model, Random& rng) {
  const RigidBodyTree& tree = model.tree;
  JointState s;
  s.q.resize(tree.dof);
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    if (body.type == JointType::kFixed) continue;
    const double range = body.type == JointType::kRevolute ? kPi : 0.5;
    double lo = -range, hi = range;
    if (j < model.joints.size()) {
      const modelgen::JointLimits& limits = model.joints[j].limits;
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

}  // namespace modelgen::test
