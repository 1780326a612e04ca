// RigidBodyTree + standard parameters -> KDL::Chain and a prepared ChainIdSolver_RNE. Same
// conversion as tests/support/kdl_oracle.cpp (frame j = parent * fixed * motion(q), inertia
// about the centre of mass from the standard parameters), written here so the chain outlives
// one call; kdl_oracle keeps its helpers private.

#include "tests/benchmarks/kdl_setup.hpp"

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/joint.hpp>
#include <kdl/rigidbodyinertia.hpp>
#include <kdl/rotationalinertia.hpp>
#include <kdl/segment.hpp>

#include "modelgen/model/rigid_body_tree.hpp"
#include "tests/support/kdl_oracle.hpp"

namespace modelgen::bench {
namespace {

// The ten inertial standard parameters of every body, summed over tree.params.
std::vector<std::array<double, 10>> standard_per_body(const RigidBodyTree& tree,
                                                      const Eigen::VectorXd& p) {
  std::vector<std::array<double, 10>> out(tree.bodies.size(), std::array<double, 10>{});
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const int slot = test::inertial_slot(tree.params[k].kind);
    if (slot >= 0) out[tree.params[k].body][slot] += p[static_cast<Eigen::Index>(k)];
  }
  return out;
}

// The standard parameters hold the tensor about the body frame origin; KDL wants mass, centre
// of mass c = MS / M and the tensor about c: I_c = J_O - M (|c|^2 1 - c c^T) (parallel axes).
KDL::RigidBodyInertia to_kdl_inertia(const std::array<double, 10>& s) {
  Eigen::Matrix3d J;
  J << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
  const Eigen::Vector3d MS(s[6], s[7], s[8]);
  const double M = s[9];
  if (M == 0.0) {
    if (!MS.isZero(0.0)) throw std::invalid_argument("a body has first moments but no mass");
    return KDL::RigidBodyInertia(
        0.0, KDL::Vector::Zero(),
        KDL::RotationalInertia(J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2)));
  }
  const Eigen::Vector3d c = MS / M;
  const Eigen::Matrix3d Ic =
      J - M * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  // KDL::RotationalInertia(Ixx, Iyy, Izz, Ixy, Ixz, Iyz) takes tensor entries.
  return KDL::RigidBodyInertia(
      M, KDL::Vector(c.x(), c.y(), c.z()),
      KDL::RotationalInertia(Ic(0, 0), Ic(1, 1), Ic(2, 2), Ic(0, 1), Ic(0, 2), Ic(1, 2)));
}

KDL::Frame to_kdl_frame(const Frame& f) {
  const auto& r = f.rotation;  // row-major, the order KDL::Rotation's constructor takes
  return KDL::Frame(KDL::Rotation(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]),
                    KDL::Vector(f.translation[0], f.translation[1], f.translation[2]));
}

KDL::Chain build_chain(const RigidBodyTree& tree, const Eigen::VectorXd& p, KdlChainShape shape) {
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    if (tree.bodies[j].parent != static_cast<int>(j) - 1) {
      throw std::invalid_argument("KDL chains need a serial tree; body " + tree.bodies[j].name +
                                  " does not follow its parent");
    }
  }
  if (p.size() != static_cast<Eigen::Index>(tree.params.size())) {
    throw std::invalid_argument("p needs " + std::to_string(tree.params.size()) + " entries");
  }
  const std::vector<std::array<double, 10>> standard = standard_per_body(tree, p);
  KDL::Chain chain;
  for (std::size_t j = 0; j < tree.bodies.size(); ++j) {
    const Body& body = tree.bodies[j];
    const KDL::RigidBodyInertia inertia = to_kdl_inertia(standard[j]);
    const KDL::Frame fixed = to_kdl_frame(body.fixed);
    if (body.type == JointType::kFixed) {
      chain.addSegment(
          KDL::Segment(body.name, KDL::Joint(body.name, KDL::Joint::Fixed), fixed, inertia));
      continue;
    }
    const KDL::Joint::JointType type =
        body.type == JointType::kRevolute ? KDL::Joint::RotAxis : KDL::Joint::TransAxis;
    const KDL::Vector axis(body.axis[0], body.axis[1], body.axis[2]);
    if (shape == KdlChainShape::kSegmentPerBody) {
      // In KDL a segment's pose is joint.pose(q) * f_tip, with f_tip stored relative to
      // joint.pose(0). A joint through fixed's origin about fixed's rotation of the axis,
      // with tip `fixed`, gives fixed * motion(q): the body frame, where its inertia lives.
      chain.addSegment(KDL::Segment(body.name, KDL::Joint(body.name, fixed.p, fixed.M * axis, type),
                                    fixed, inertia));
    } else {
      chain.addSegment(KDL::Segment(body.name + "_fixed",
                                    KDL::Joint(body.name + "_fixed", KDL::Joint::Fixed), fixed,
                                    KDL::RigidBodyInertia::Zero()));
      chain.addSegment(KDL::Segment(body.name,
                                    KDL::Joint(body.name, KDL::Vector::Zero(), axis, type),
                                    KDL::Frame::Identity(), inertia));
    }
  }
  return chain;
}

// KDL numbers joints in chain order, which is body order; modelgen numbers them by dof_index.
std::vector<int> kdl_joint_dofs(const RigidBodyTree& tree) {
  std::vector<int> out;
  for (const Body& body : tree.bodies) {
    if (body.type != JointType::kFixed) out.push_back(body.dof_index);
  }
  return out;
}

}  // namespace

KdlRne::KdlRne(const RigidBodyTree& tree, const Eigen::VectorXd& p, KdlChainShape shape)
    : chain_(build_chain(tree, p, shape)),
      dof_of_kdl_joint_(kdl_joint_dofs(tree)),
      solver_(chain_, KDL::Vector(tree.gravity[0], tree.gravity[1], tree.gravity[2])),
      no_external_(chain_.getNrOfSegments(), KDL::Wrench::Zero()) {}

KDL::JntArray KdlRne::to_kdl(const Eigen::VectorXd& v) const {
  KDL::JntArray out(num_joints());
  for (unsigned k = 0; k < num_joints(); ++k) out(k) = v[dof_of_kdl_joint_[k]];
  return out;
}

Eigen::VectorXd KdlRne::inverse_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                                         const Eigen::VectorXd& ddq) {
  KDL::JntArray tau(num_joints());
  const int status = solve(to_kdl(q), to_kdl(dq), to_kdl(ddq), tau);
  if (status < 0) {
    throw std::runtime_error("KDL ChainIdSolver_RNE failed: " + std::to_string(status));
  }
  Eigen::VectorXd out(static_cast<Eigen::Index>(num_joints()));
  for (unsigned k = 0; k < num_joints(); ++k) out[dof_of_kdl_joint_[k]] = tau(k);
  return out;
}

}  // namespace modelgen::bench
