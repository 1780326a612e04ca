// Symbolic form of the Swevers et al. 2002 drive model F (eq. 7-12): the rigid-body torques of
// the symbolic Newton-Euler on the inertial parameters, mapped through the coupling, the
// inverted transmission efficiency and the motor inertia and friction (see drive_model.hpp).

#include "generator/dynamics/drive_model.hpp"

#include <stdexcept>
#include <string>

#include <Eigen/LU>

namespace modelgen::gen {

namespace {

bool is_inertial(ParamKind kind) {
  switch (kind) {
    case ParamKind::kXX:
    case ParamKind::kXY:
    case ParamKind::kXZ:
    case ParamKind::kYY:
    case ParamKind::kYZ:
    case ParamKind::kZZ:
    case ParamKind::kMX:
    case ParamKind::kMY:
    case ParamKind::kMZ:
    case ParamKind::kM:
      return true;
    default:
      return false;
  }
}

// sum_l row[l] x[l], shared: a motor velocity or acceleration used by several terms.
ExprId combination(ExprGraph& g, const Eigen::VectorXd& row, const std::vector<ExprId>& x) {
  std::vector<ExprId> terms;
  for (Eigen::Index l = 0; l < row.size(); ++l) {
    terms.push_back(g.mul(g.constant(row[l]), x[static_cast<std::size_t>(l)]));
  }
  return g.share(g.add(std::move(terms)));
}

// sign(e), as the derived leaf sign(dq[i]) when e is a constant multiple of dq[i] (the motor of
// an uncoupled joint), so the body declares it with the other leaves.
ExprId velocity_sign(ExprGraph& g, const SymbolicInputs& in, ExprId e) {
  const Node& n = g.node(e);
  double c = 1.0;
  ExprId x = e;
  if (n.op == Op::kMul && n.args.size() == 2 && g.is_constant(n.args[0])) {
    c = g.constant_value(n.args[0]);
    x = n.args[1];
  }
  for (std::size_t i = 0; i < in.dq.size(); ++i) {
    if (x == in.dq[i]) return c > 0 ? in.sign_dq[i] : g.neg(in.sign_dq[i]);
  }
  return g.sign(e);
}

}  // namespace

DriveModel derive_drive_model(ExprGraph& g, const RigidBodyTree& tree,
                              const Eigen::MatrixXd& motor_from_joint, const SymbolicInputs& in) {
  const int dof = tree.dof;
  const Eigen::MatrixXd& K = motor_from_joint;
  if (K.rows() != dof || K.cols() != dof) {
    throw std::logic_error("derive_drive_model: motor_from_joint is " + std::to_string(K.rows()) +
                           " x " + std::to_string(K.cols()) + ", expected " + std::to_string(dof) +
                           " x " + std::to_string(dof));
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  if (!lu.isInvertible())
    throw std::logic_error("derive_drive_model: motor_from_joint is singular");
  // Swevers eq. 9-10: q_G = V q_M with V = K^-1, and tau'_G = V^T tau_G.
  const Eigen::MatrixXd V = lu.inverse();

  DriveModel model;
  auto parameter = [&](const std::string& name) {
    const ExprId symbol =
        g.symbol({"theta[" + std::to_string(model.theta.size()) + "]", SymbolKind::kInput, ""});
    model.names.push_back(name);
    model.theta.push_back(symbol);
    return symbol;
  };

  // Rigid-body part (eq. 1) on the inertial parameters; the standard drive terms are zero.
  SymbolicInputs rigid = in;
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    rigid.p[k] = is_inertial(tree.params[k].kind) ? parameter(tree.params[k].name) : g.zero();
  }
  std::vector<ExprId> tau_G = derive_inverse_dynamics(g, tree, rigid);
  for (ExprId& t : tau_G) t = g.share(t);

  std::vector<std::string> suffix(static_cast<std::size_t>(dof));
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    if (tree.bodies[b].dof_index >= 0) suffix[tree.bodies[b].dof_index] = std::to_string(b + 1);
  }
  const ExprId half = g.constant(0.5);
  for (int i = 0; i < dof; ++i) {
    const ExprId JM = parameter("JM" + suffix[i]);
    const ExprId Rv = parameter("Rv" + suffix[i]);
    const ExprId Rc = parameter("Rc" + suffix[i]);
    const ExprId Rz = parameter("Rz" + suffix[i]);
    // Eq. 9: motor velocity and acceleration (link side).
    const ExprId dq_M = combination(g, K.row(i).transpose(), in.dq);
    const ExprId ddq_M = combination(g, K.row(i).transpose(), in.ddq);
    // Eq. 10: net actuator torque at the transmission output.
    const ExprId tau_G_out = combination(g, V.col(i), tau_G);
    // Eq. 8 inverted, branch by the sign of the power flow (see the header for s = 0).
    const ExprId s = g.sign(g.mul(tau_G_out, dq_M));
    const ExprId efficiency_factor = g.share(g.add(g.mul(g.add(half, g.mul(half, s)), g.inv(Rz)),
                                                   g.mul(g.sub(half, g.mul(half, s)), Rz)));
    const ExprId tau_T = g.mul(tau_G_out, efficiency_factor);
    // Eq. 5-7: rotor inertia, viscous and Coulomb friction of the motor.
    model.tau_M.push_back(
        g.add({tau_T, g.mul(JM, ddq_M), g.mul(Rv, dq_M), g.mul(Rc, velocity_sign(g, in, dq_M))}));
  }
  return model;
}

}  // namespace modelgen::gen
