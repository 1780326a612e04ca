// Symbolic form of the Swevers et al. 2002 drive model F (eq. 7-12): its parameters, and the
// rigid-body torques mapped through the coupling (eq. 9-10), the inverted transmission
// efficiency (eq. 8) and the motor inertia and friction (eq. 5-7); see drive_model.hpp.

#include "generator/dynamics/drive_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

namespace modelgen::gen {

namespace {

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

// The column of theta that holds `parameter` (one of parameters.theta).
std::size_t column_of(const DriveParameters& parameters, ExprId parameter) {
  return static_cast<std::size_t>(
      std::find(parameters.theta.begin(), parameters.theta.end(), parameter) -
      parameters.theta.begin());
}

}  // namespace

DriveParameters make_drive_parameters(ExprGraph& g, const RigidBodyTree& tree) {
  DriveParameters out;
  auto parameter = [&](const std::string& name) {
    const ExprId symbol =
        g.symbol({"theta[" + std::to_string(out.theta.size()) + "]", SymbolKind::kInput, ""});
    out.names.push_back(name);
    out.theta.push_back(symbol);
    return symbol;
  };
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    if (!is_inertial(tree.params[k].kind)) continue;
    parameter(tree.params[k].name);
    out.standard_index.push_back(static_cast<int>(k));
  }
  std::vector<std::string> suffix(static_cast<std::size_t>(tree.dof));
  for (std::size_t b = 0; b < tree.bodies.size(); ++b) {
    if (tree.bodies[b].dof_index >= 0) suffix[tree.bodies[b].dof_index] = std::to_string(b + 1);
  }
  for (int i = 0; i < tree.dof; ++i) {
    out.JM.push_back(parameter("JM" + suffix[i]));
    out.Rv.push_back(parameter("Rv" + suffix[i]));
    out.Rc.push_back(parameter("Rc" + suffix[i]));
    out.Rz.push_back(parameter("Rz" + suffix[i]));
  }
  return out;
}

std::vector<ExprId> rigid_body_parameters(ExprGraph& g, const RigidBodyTree& tree,
                                          const DriveParameters& parameters) {
  std::vector<ExprId> p(tree.params.size(), g.zero());
  for (std::size_t k = 0; k < parameters.standard_index.size(); ++k) {
    p[parameters.standard_index[k]] = parameters.theta[k];
  }
  return p;
}

Eigen::MatrixXd joint_from_motor(const Eigen::MatrixXd& K, int dof) {
  if (K.rows() != dof || K.cols() != dof) {
    throw std::logic_error("joint_from_motor: motor_from_joint is " + std::to_string(K.rows()) +
                           " x " + std::to_string(K.cols()) + ", expected " + std::to_string(dof) +
                           " x " + std::to_string(dof));
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  if (!lu.isInvertible()) throw std::logic_error("joint_from_motor: motor_from_joint is singular");
  return lu.inverse();
}

DriveTorques derive_drive_torques(ExprGraph& g, const Eigen::MatrixXd& K, const SymbolicInputs& in,
                                  const DriveParameters& parameters,
                                  const std::vector<ExprId>& tau_G) {
  const int dof = static_cast<int>(tau_G.size());
  // Swevers eq. 9-10: q_G = V q_M with V = K^-1, and tau'_G = V^T tau_G.
  const Eigen::MatrixXd V = joint_from_motor(K, dof);
  std::vector<ExprId> shared_tau_G;
  for (ExprId t : tau_G) shared_tau_G.push_back(g.share(t));
  DriveTorques out;
  for (int i = 0; i < dof; ++i) {
    // Eq. 9: motor velocity and acceleration (link side).
    const ExprId dq_M = combination(g, K.row(i).transpose(), in.dq);
    const ExprId ddq_M = combination(g, K.row(i).transpose(), in.ddq);
    // Eq. 10: net actuator torque at the transmission output.
    const ExprId tau_out = combination(g, V.col(i), shared_tau_G);
    ExprId c = 0;
    const ExprId tau_M =
        motor_torque(g, parameters, i, tau_out, dq_M, velocity_sign(g, in, dq_M), ddq_M, &c);
    out.tau_out.push_back(tau_out);
    out.efficiency.push_back(c);
    out.tau_M.push_back(tau_M);
  }
  return out;
}

ExprId motor_torque(ExprGraph& g, const DriveParameters& parameters, int i, ExprId tau_out,
                    ExprId dq_M, ExprId sign_dq_M, ExprId ddq_M, ExprId* efficiency) {
  // Eq. 8 inverted, branch by the sign of the power flow (see the header for s = 0).
  const ExprId half = g.constant(0.5);
  const ExprId s = g.sign(g.mul(tau_out, dq_M));
  const ExprId Rz = parameters.Rz[i];
  const ExprId c = g.share(
      g.add(g.mul(g.add(half, g.mul(half, s)), g.inv(Rz)), g.mul(g.sub(half, g.mul(half, s)), Rz)));
  *efficiency = c;
  // Eq. 5-7: rotor inertia, viscous and Coulomb friction of the motor.
  return g.add({g.mul(tau_out, c), g.mul(parameters.JM[i], ddq_M), g.mul(parameters.Rv[i], dq_M),
                g.mul(parameters.Rc[i], sign_dq_M)});
}

std::vector<ExprId> derive_drive_regressor(ExprGraph& g, const Eigen::MatrixXd& K,
                                           const SymbolicInputs& in,
                                           const DriveParameters& parameters,
                                           const std::vector<ExprId>& W) {
  const int dof = static_cast<int>(in.dq.size());
  const int columns = static_cast<int>(parameters.theta.size());
  const int standard = dof == 0 ? 0 : static_cast<int>(W.size()) / dof;
  const Eigen::MatrixXd V = joint_from_motor(K, dof);
  std::vector<ExprId> Y(static_cast<std::size_t>(dof) * columns, g.zero());
  for (int i = 0; i < dof; ++i) {
    ExprId* row = &Y[static_cast<std::size_t>(i) * columns];
    // Eq. 10: tau'_G = V^T W p, so column k of row i is sum_j V(j, i) W(j, k).
    for (std::size_t k = 0; k < parameters.standard_index.size(); ++k) {
      std::vector<ExprId> terms;
      for (int j = 0; j < dof; ++j) {
        terms.push_back(
            g.mul(g.constant(V(j, i)),
                  W[static_cast<std::size_t>(j) * standard + parameters.standard_index[k]]));
      }
      row[k] = g.add(std::move(terms));
    }
    // Eq. 5-7 and 9: the motor terms are linear in JM, Rv, Rc already.
    const ExprId dq_M = combination(g, K.row(i).transpose(), in.dq);
    row[column_of(parameters, parameters.JM[i])] = combination(g, K.row(i).transpose(), in.ddq);
    row[column_of(parameters, parameters.Rv[i])] = dq_M;
    row[column_of(parameters, parameters.Rc[i])] = velocity_sign(g, in, dq_M);
  }
  return Y;
}

std::vector<ExprId> drive_torques_from_regressor(ExprGraph& g, const DriveParameters& parameters,
                                                 const std::vector<ExprId>& Y) {
  const std::size_t columns = parameters.theta.size();
  std::vector<ExprId> tau_M;
  for (std::size_t i = 0; i < parameters.JM.size(); ++i) {
    const ExprId* row = &Y[i * columns];
    std::vector<ExprId> terms;
    for (std::size_t k = 0; k < parameters.standard_index.size(); ++k) {
      terms.push_back(g.mul(row[k], parameters.theta[k]));
    }
    const ExprId tau_out = g.share(g.add(std::move(terms)));
    ExprId c = 0;
    tau_M.push_back(motor_torque(g, parameters, static_cast<int>(i), tau_out,
                                 row[column_of(parameters, parameters.Rv[i])],
                                 row[column_of(parameters, parameters.Rc[i])],
                                 row[column_of(parameters, parameters.JM[i])], &c));
  }
  return tau_M;
}

}  // namespace modelgen::gen
