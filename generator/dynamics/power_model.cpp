// Energy and power regressors (Gautier & Briot eq. 8-12). The energy of link j about its frame
// origin, T = M v.v / 2 + MS.(v x w) + w.J w / 2 and U = -g.(M p0 + R0 MS), is linear in the
// standard parameters; its time derivative comes from the DAG (TimeDerivative), not from
// finite differences.

#include "generator/dynamics/power_model.hpp"

#include <unordered_map>

#include "generator/dynamics/symbolic_vectors.hpp"
#include "generator/symbolic/time_derivative.hpp"

namespace modelgen::gen {

namespace {

// The velocity u' = c . dq of the coupled motor a kIam/kFvm/kFcm parameter belongs to.
ExprId motor_velocity(ExprGraph& g, const RigidBodyTree& tree, const StandardParam& param,
                      const SymbolicInputs& in) {
  const CoupledMotor& motor = *coupled_motor_of(tree, param);
  std::vector<ExprId> terms;
  for (int l = 0; l < tree.dof; ++l) terms.push_back(g.mul(g.constant(motor.coupling[l]), in.dq[l]));
  return g.share(g.add(std::move(terms)));
}

}  // namespace

std::vector<ExprId> derive_energy_regressor(ExprGraph& g, const RigidBodyTree& tree,
                                            const SymbolicInputs& in) {
  VectorAlgebra va(g);
  const SymbolicMotion m = derive_motion(g, tree, in);
  const std::size_t n = tree.bodies.size();
  // Gravity in each body frame, and g . (origin of the body in the base frame).
  std::vector<V3> gravity(n);
  std::vector<ExprId> height(n);
  const V3 g0 = va.vector(tree.gravity);
  for (std::size_t j = 0; j < n; ++j) {
    const int a = tree.bodies[j].parent;
    const V3& g_antecedent = a >= 0 ? gravity[a] : g0;
    gravity[j] = va.share(va.mul_transposed(m.R[j], g_antecedent));
    height[j] = g.share(g.add(a >= 0 ? height[a] : g.zero(), va.dot(g_antecedent, m.p[j])));
  }
  const ExprId half = g.constant(0.5);
  std::vector<ExprId> h(tree.params.size(), g.zero());
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const StandardParam& param = tree.params[k];
    const int j = param.body;
    const V3& w = m.w[j];
    const V3& v = m.v[j];
    const int i = tree.bodies[j].dof_index;
    switch (param.kind) {
      case ParamKind::kXX: h[k] = g.mul({half, w[0], w[0]}); break;
      case ParamKind::kYY: h[k] = g.mul({half, w[1], w[1]}); break;
      case ParamKind::kZZ: h[k] = g.mul({half, w[2], w[2]}); break;
      case ParamKind::kXY: h[k] = g.mul(w[0], w[1]); break;
      case ParamKind::kXZ: h[k] = g.mul(w[0], w[2]); break;
      case ParamKind::kYZ: h[k] = g.mul(w[1], w[2]); break;
      // MS.(v x w) - MS.g_j: kinetic coupling and potential energy of the first moments.
      case ParamKind::kMX: h[k] = g.sub(va.cross(v, w)[0], gravity[j][0]); break;
      case ParamKind::kMY: h[k] = g.sub(va.cross(v, w)[1], gravity[j][1]); break;
      case ParamKind::kMZ: h[k] = g.sub(va.cross(v, w)[2], gravity[j][2]); break;
      case ParamKind::kM: h[k] = g.sub(g.mul(half, va.dot(v, v)), height[j]); break;
      case ParamKind::kIa: h[k] = g.mul({half, in.dq[i], in.dq[i]}); break;
      case ParamKind::kIam: {
        // Rotor of a coupled motor: Iam u'^2 / 2 with u' = c . dq.
        const ExprId u = motor_velocity(g, tree, param, in);
        h[k] = g.mul({half, u, u});
        break;
      }
      default: break;  // friction and offsets store no energy
    }
  }
  return h;
}

std::vector<ExprId> derive_power_regressor(ExprGraph& g, const RigidBodyTree& tree,
                                           const SymbolicInputs& in,
                                           const std::vector<ExprId>& energy_regressor) {
  std::unordered_map<ExprId, ExprId> leaves;
  for (int i = 0; i < tree.dof; ++i) {
    leaves[in.q[i]] = in.dq[i];
    leaves[in.dq[i]] = in.ddq[i];
    leaves[in.sin_q[i]] = g.mul(in.cos_q[i], in.dq[i]);
    leaves[in.cos_q[i]] = g.neg(g.mul(in.sin_q[i], in.dq[i]));
  }
  TimeDerivative d_dt(g, std::move(leaves));
  std::vector<ExprId> dh(tree.params.size(), g.zero());
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const StandardParam& param = tree.params[k];
    const int i = tree.bodies[param.body].dof_index;
    // Power of the drive terms: dq times their torque (Gautier & Briot eq. 9).
    switch (param.kind) {
      case ParamKind::kFv: dh[k] = g.mul(in.dq[i], in.dq[i]); break;
      case ParamKind::kFc: dh[k] = g.mul(in.sign_dq[i], in.dq[i]); break;
      case ParamKind::kOff: dh[k] = in.dq[i]; break;
      case ParamKind::kFvPos: dh[k] = g.mul({in.positive_dq[i], in.dq[i], in.dq[i]}); break;
      case ParamKind::kFvNeg: dh[k] = g.mul({in.negative_dq[i], in.dq[i], in.dq[i]}); break;
      case ParamKind::kFcPos: dh[k] = g.mul(in.positive_dq[i], in.dq[i]); break;
      case ParamKind::kFcNeg: dh[k] = g.neg(g.mul(in.negative_dq[i], in.dq[i])); break;
      case ParamKind::kFvm: {
        const ExprId u = motor_velocity(g, tree, param, in);
        dh[k] = g.mul(u, u);
        break;
      }
      case ParamKind::kFcm: {
        const ExprId u = motor_velocity(g, tree, param, in);
        dh[k] = g.mul(g.sign(u), u);
        break;
      }
      default: dh[k] = d_dt(energy_regressor[k]); break;
    }
  }
  return dh;
}

}  // namespace modelgen::gen
