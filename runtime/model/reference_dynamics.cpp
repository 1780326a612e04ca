// Recursive Newton-Euler on the RigidBodyTree, in body frames (Khalil & Kleinfinger's
// formulation with inertia about the frame origin and first moments MS, which keeps every force
// linear in the standard parameters; Gautier & Briot eq. 2-4). Written for clarity: it is the
// oracle, not the product.

#include "modelgen/model/reference_dynamics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Geometry>

namespace modelgen {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

struct BodyInertia {
  Matrix3d J = Matrix3d::Zero();  // inertia tensor about the frame origin
  Vector3d MS = Vector3d::Zero();
  double M = 0;
};

struct DriveTerms {
  double Ia = 0, Fv = 0, Fc = 0, Off = 0, Fvp = 0, Fvn = 0, Fcp = 0, Fcn = 0;
};

Matrix3d to_matrix(const std::array<double, 9>& r) {
  Matrix3d m;
  m << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  return m;
}

Vector3d to_vector(const std::array<double, 3>& v) { return Vector3d(v[0], v[1], v[2]); }

double sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

// Transform from the antecedent frame to frame j at joint position qj.
void joint_transform(const Body& body, double qj, Matrix3d& R, Vector3d& p) {
  const Matrix3d Rf = to_matrix(body.fixed.rotation);
  const Vector3d tf = to_vector(body.fixed.translation);
  const Vector3d u = to_vector(body.axis);
  switch (body.type) {
    case JointType::kRevolute:
      R = Rf * Eigen::AngleAxisd(qj, u).toRotationMatrix();
      p = tf;
      break;
    case JointType::kPrismatic:
      R = Rf;
      p = tf + Rf * (qj * u);
      break;
    case JointType::kFixed:
      R = Rf;
      p = tf;
      break;
  }
}

void check_size(const Eigen::VectorXd& v, int n, const char* what) {
  if (v.size() != n) {
    throw std::invalid_argument(std::string("ReferenceDynamics: ") + what + " has size " +
                                std::to_string(v.size()) + ", expected " + std::to_string(n));
  }
}

struct MotorTerms {
  const CoupledMotor* motor = nullptr;
  double Iam = 0, Fvm = 0, Fcm = 0;
};

struct Unpacked {
  std::vector<BodyInertia> inertia;
  std::vector<DriveTerms> drive;   // per dof
  std::vector<MotorTerms> motors;  // per tree.coupled_motors entry
};

// Every term at zero.
Unpacked zero_parameters(const RigidBodyTree& tree) {
  Unpacked u;
  u.inertia.resize(tree.bodies.size());
  u.drive.resize(tree.dof);
  u.motors.resize(tree.coupled_motors.size());
  for (std::size_t m = 0; m < tree.coupled_motors.size(); ++m) {
    u.motors[m].motor = &tree.coupled_motors[m];
  }
  return u;
}

// Adds v to the term standard parameter k stands for.
void add_parameter(const RigidBodyTree& tree, std::size_t k, double v, Unpacked& u) {
  auto motor_terms = [&](const StandardParam& param) -> MotorTerms& {
    const CoupledMotor* motor = coupled_motor_of(tree, param);
    return u.motors[static_cast<std::size_t>(motor - tree.coupled_motors.data())];
  };
  const StandardParam& param = tree.params[k];
  BodyInertia& b = u.inertia[param.body];
  const int dof = tree.bodies[param.body].dof_index;
  switch (param.kind) {
    case ParamKind::kXX:
      b.J(0, 0) += v;
      break;
    case ParamKind::kYY:
      b.J(1, 1) += v;
      break;
    case ParamKind::kZZ:
      b.J(2, 2) += v;
      break;
    case ParamKind::kXY:
      b.J(0, 1) += v;
      b.J(1, 0) += v;
      break;
    case ParamKind::kXZ:
      b.J(0, 2) += v;
      b.J(2, 0) += v;
      break;
    case ParamKind::kYZ:
      b.J(1, 2) += v;
      b.J(2, 1) += v;
      break;
    case ParamKind::kMX:
      b.MS.x() += v;
      break;
    case ParamKind::kMY:
      b.MS.y() += v;
      break;
    case ParamKind::kMZ:
      b.MS.z() += v;
      break;
    case ParamKind::kM:
      b.M += v;
      break;
    case ParamKind::kIa:
      u.drive[dof].Ia += v;
      break;
    case ParamKind::kFv:
      u.drive[dof].Fv += v;
      break;
    case ParamKind::kFc:
      u.drive[dof].Fc += v;
      break;
    case ParamKind::kOff:
      u.drive[dof].Off += v;
      break;
    case ParamKind::kFvPos:
      u.drive[dof].Fvp += v;
      break;
    case ParamKind::kFvNeg:
      u.drive[dof].Fvn += v;
      break;
    case ParamKind::kFcPos:
      u.drive[dof].Fcp += v;
      break;
    case ParamKind::kFcNeg:
      u.drive[dof].Fcn += v;
      break;
    case ParamKind::kIam:
      motor_terms(param).Iam += v;
      break;
    case ParamKind::kFvm:
      motor_terms(param).Fvm += v;
      break;
    case ParamKind::kFcm:
      motor_terms(param).Fcm += v;
      break;
  }
}

Unpacked unpack(const RigidBodyTree& tree, const Eigen::VectorXd& p) {
  Unpacked u = zero_parameters(tree);
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    add_parameter(tree, k, p[static_cast<Eigen::Index>(k)], u);
  }
  return u;
}

// Velocities and accelerations of every body frame, expressed in that frame.
struct Motion {
  std::vector<Matrix3d> R;  // antecedent <- body
  std::vector<Vector3d> p;  // body origin in antecedent frame
  std::vector<Vector3d> w, dw, v, dv;
};

Motion forward_recursion(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
                         const Vector3d& base_acceleration) {
  const std::size_t n = tree.bodies.size();
  Motion m;
  m.R.resize(n);
  m.p.resize(n);
  m.w.resize(n);
  m.dw.resize(n);
  m.v.resize(n);
  m.dv.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Body& body = tree.bodies[j];
    const bool moving = body.type != JointType::kFixed;
    const double qj = moving ? q[body.dof_index] : 0.0;
    const double dqj = moving ? dq[body.dof_index] : 0.0;
    const double ddqj = moving ? ddq[body.dof_index] : 0.0;
    joint_transform(body, qj, m.R[j], m.p[j]);
    const Vector3d u = to_vector(body.axis);
    Vector3d wa = Vector3d::Zero(), dwa = Vector3d::Zero(), va = Vector3d::Zero();
    Vector3d dva = base_acceleration;
    if (body.parent >= 0) {
      wa = m.w[body.parent];
      dwa = m.dw[body.parent];
      va = m.v[body.parent];
      dva = m.dv[body.parent];
    }
    const Matrix3d Rt = m.R[j].transpose();
    const Vector3d& p = m.p[j];
    const Vector3d w_in = Rt * wa;  // antecedent's angular velocity, in frame j
    m.w[j] = w_in;
    m.dw[j] = Rt * dwa;
    m.v[j] = Rt * (va + wa.cross(p));
    m.dv[j] = Rt * (dva + dwa.cross(p) + wa.cross(wa.cross(p)));
    if (body.type == JointType::kRevolute) {
      m.w[j] += dqj * u;
      m.dw[j] += ddqj * u + w_in.cross(dqj * u);
    } else if (body.type == JointType::kPrismatic) {
      m.v[j] += dqj * u;
      m.dv[j] += ddqj * u + 2.0 * m.w[j].cross(dqj * u);
    }
  }
  return m;
}

}  // namespace

ReferenceDynamics::ReferenceDynamics(RigidBodyTree tree) : tree_(std::move(tree)) {
  validate(tree_);
}

namespace {

// The backward recursion of Newton-Euler on a computed motion: the joint torques of the
// parameters `par`.
Eigen::VectorXd torques_on_motion(const RigidBodyTree& tree, const Motion& m,
                                  const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
                                  const Unpacked& par) {
  const std::size_t n = tree.bodies.size();
  std::vector<Vector3d> f(n, Vector3d::Zero()), moment(n, Vector3d::Zero());
  for (std::size_t j = 0; j < n; ++j) {
    const BodyInertia& b = par.inertia[j];
    const Vector3d& w = m.w[j];
    const Vector3d& dw = m.dw[j];
    // Newton-Euler equations about the frame origin with first moments MS.
    f[j] = b.M * m.dv[j] + dw.cross(b.MS) + w.cross(w.cross(b.MS));
    moment[j] = b.J * dw + w.cross(b.J * w) + b.MS.cross(m.dv[j]);
  }
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(tree.dof);
  for (std::size_t j = n; j-- > 0;) {
    const Body& body = tree.bodies[j];
    if (body.type != JointType::kFixed) {
      const Vector3d u = to_vector(body.axis);
      const int i = body.dof_index;
      const DriveTerms& d = par.drive[i];
      const double s = sign(dq[i]);
      const double pos = dq[i] > 0 ? 1.0 : 0.0;
      const double neg = dq[i] < 0 ? 1.0 : 0.0;
      tau[i] = (body.type == JointType::kRevolute ? moment[j] : f[j]).dot(u) + d.Ia * ddq[i] +
               d.Fv * dq[i] + d.Fc * s + d.Off + d.Fvp * pos * dq[i] + d.Fvn * neg * dq[i] +
               d.Fcp * pos - d.Fcn * neg;
    }
    if (body.parent >= 0) {
      const Vector3d f_parent = m.R[j] * f[j];
      f[body.parent] += f_parent;
      moment[body.parent] += m.R[j] * moment[j] + m.p[j].cross(f_parent);
    }
  }
  // Coupled motors: their inertia and friction act on the motor velocity u' = c . dq and
  // reach every joint they drive through c (Gautier & Briot eq. 26).
  for (const MotorTerms& terms : par.motors) {
    const Eigen::Map<const Eigen::VectorXd> c(terms.motor->coupling.data(), tree.dof);
    const double torque =
        terms.Iam * c.dot(ddq) + terms.Fvm * c.dot(dq) + terms.Fcm * sign(c.dot(dq));
    tau += torque * c;
  }
  return tau;
}

}  // namespace

Eigen::VectorXd ReferenceDynamics::inverse_dynamics(const Eigen::VectorXd& q,
                                                    const Eigen::VectorXd& dq,
                                                    const Eigen::VectorXd& ddq,
                                                    const Eigen::VectorXd& p) const {
  check_size(q, dof(), "q");
  check_size(dq, dof(), "dq");
  check_size(ddq, dof(), "ddq");
  check_size(p, num_params(), "p");
  // Gravity enters as an upward acceleration of the base (Khalil & Dombre, dv0 = -g).
  const Motion m = forward_recursion(tree_, q, dq, ddq, -to_vector(tree_.gravity));
  return torques_on_motion(tree_, m, dq, ddq, unpack(tree_, p));
}

Eigen::MatrixXd ReferenceDynamics::standard_regressor(const Eigen::VectorXd& q,
                                                      const Eigen::VectorXd& dq,
                                                      const Eigen::VectorXd& ddq) const {
  check_size(q, dof(), "q");
  check_size(dq, dof(), "dq");
  check_size(ddq, dof(), "ddq");
  // Column k: the torques of the unit parameter k, on one forward recursion (tau is linear in
  // p, Gautier & Briot eq. 2).
  const Motion m = forward_recursion(tree_, q, dq, ddq, -to_vector(tree_.gravity));
  Eigen::MatrixXd W(dof(), num_params());
  // One set of terms, parameter k set to 1 and back to 0 (exactly) around its column.
  Unpacked unit = zero_parameters(tree_);
  for (int k = 0; k < num_params(); ++k) {
    add_parameter(tree_, static_cast<std::size_t>(k), 1.0, unit);
    W.col(k) = torques_on_motion(tree_, m, dq, ddq, unit);
    add_parameter(tree_, static_cast<std::size_t>(k), -1.0, unit);
  }
  return W;
}

double ReferenceDynamics::kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                                         const Eigen::VectorXd& p) const {
  check_size(q, dof(), "q");
  check_size(dq, dof(), "dq");
  check_size(p, num_params(), "p");
  const Unpacked par = unpack(tree_, p);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(dof());
  const Motion m = forward_recursion(tree_, q, dq, zero, Vector3d::Zero());
  double energy = 0;
  for (std::size_t j = 0; j < tree_.bodies.size(); ++j) {
    const BodyInertia& b = par.inertia[j];
    // T = m v.v / 2 + v.(w x MS) + w.J w / 2 for a body with velocity v at the frame origin.
    energy += 0.5 * b.M * m.v[j].squaredNorm() + m.v[j].dot(m.w[j].cross(b.MS)) +
              0.5 * m.w[j].dot(b.J * m.w[j]);
  }
  for (int i = 0; i < dof(); ++i) energy += 0.5 * par.drive[i].Ia * dq[i] * dq[i];
  for (const MotorTerms& terms : par.motors) {
    const double u = Eigen::Map<const Eigen::VectorXd>(terms.motor->coupling.data(), dof()).dot(dq);
    energy += 0.5 * terms.Iam * u * u;
  }
  return energy;
}

double ReferenceDynamics::potential_energy(const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& p) const {
  check_size(p, num_params(), "p");
  const Unpacked par = unpack(tree_, p);
  const std::vector<Frame> poses = forward_kinematics(q);
  const Vector3d g = to_vector(tree_.gravity);
  double energy = 0;
  for (std::size_t j = 0; j < poses.size(); ++j) {
    const BodyInertia& b = par.inertia[j];
    const Matrix3d R = to_matrix(poses[j].rotation);
    const Vector3d origin = to_vector(poses[j].translation);
    energy -= g.dot(b.M * origin + R * b.MS);
  }
  return energy;
}

std::vector<Frame> ReferenceDynamics::forward_kinematics(const Eigen::VectorXd& q) const {
  check_size(q, dof(), "q");
  std::vector<Frame> poses(tree_.bodies.size());
  std::vector<Matrix3d> R(tree_.bodies.size());
  std::vector<Vector3d> t(tree_.bodies.size());
  for (std::size_t j = 0; j < tree_.bodies.size(); ++j) {
    const Body& body = tree_.bodies[j];
    Matrix3d Rj;
    Vector3d pj;
    joint_transform(body, body.dof_index >= 0 ? q[body.dof_index] : 0.0, Rj, pj);
    if (body.parent >= 0) {
      R[j] = R[body.parent] * Rj;
      t[j] = R[body.parent] * pj + t[body.parent];
    } else {
      R[j] = Rj;
      t[j] = pj;
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) poses[j].rotation[3 * r + c] = R[j](r, c);
      poses[j].translation[r] = t[j][r];
    }
  }
  return poses;
}

}  // namespace modelgen
