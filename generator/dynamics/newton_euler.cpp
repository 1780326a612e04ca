// Symbolic Newton-Euler over the expression DAG, so constant geometry (exact zeros and ones of
// quarter-turn MDH angles) folds away while the equations are built. The recursion of
// runtime/model/reference_dynamics.cpp in Khalil & Kleinfinger's customized form: the forces,
// the inertia moments and the children's accelerations go through U = [dw]x + [w]x[w]x and the
// products of w, where the reference keeps the cross products it is tested against.

#include "generator/dynamics/newton_euler.hpp"

#include <array>
#include <string>

#include "generator/dynamics/symbolic_vectors.hpp"

namespace modelgen::gen {

namespace {

// Rotation by q about the constant unit axis u (Rodrigues): c 1 + s [u]x + (1 - c) u u^T.
M3 axis_rotation(ExprGraph& g, const std::array<double, 3>& u, ExprId s, ExprId c) {
  const ExprId one_minus_c = g.sub(g.one(), c);
  M3 R;
  const double skew[9] = {0, -u[2], u[1], u[2], 0, -u[0], -u[1], u[0], 0};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      R[3 * r + k] = g.add({r == k ? c : g.zero(), g.mul(g.constant(skew[3 * r + k]), s),
                            g.mul(g.constant(u[r] * u[k]), one_minus_c)});
    }
  }
  return R;
}

// w0 w0, w1 w1, w2 w2, w0 w1, w0 w2, w1 w2, each shared: U, and the moments through it, read
// them several times, and an unshared product would flatten into the products that use it.
std::array<ExprId, 6> angular_velocity_products(ExprGraph& g, const V3& w) {
  return {g.share(g.mul(w[0], w[0])), g.share(g.mul(w[1], w[1])), g.share(g.mul(w[2], w[2])),
          g.share(g.mul(w[0], w[1])), g.share(g.mul(w[0], w[2])), g.share(g.mul(w[1], w[2]))};
}

// U = [dw]x + w w^T - |w|^2 I, entries shared (a constant times an unshared entry would
// distribute over its two terms).
M3 u_matrix(ExprGraph& g, const V3& dw, const std::array<ExprId, 6>& ww) {
  const ExprId p00 = ww[0], p11 = ww[1], p22 = ww[2], p01 = ww[3], p02 = ww[4], p12 = ww[5];
  return {g.share(g.neg(g.add(p11, p22))), g.share(g.sub(p01, dw[2])), g.share(g.add(p02, dw[1])),
          g.share(g.add(p01, dw[2])), g.share(g.neg(g.add(p00, p22))), g.share(g.sub(p12, dw[0])),
          g.share(g.sub(p02, dw[1])), g.share(g.add(p12, dw[0])), g.share(g.neg(g.add(p00, p11)))};
}

// J dw + w x (J w) for J the unit tensor of each inertia entry (XX, XY, XZ, YY, YZ, ZZ), from
// dw, U and the products of w: the moment a unit entry makes, with the differences of squares
// shared.
std::array<V3, 6> inertia_moment_columns(ExprGraph& g, const SymbolicMotion& m, std::size_t j) {
  const V3& dw = m.dw[j];
  const M3& U = m.U[j];
  const std::array<ExprId, 6>& ww = m.ww[j];
  const ExprId p00 = ww[0], p11 = ww[1], p22 = ww[2], p01 = ww[3], p02 = ww[4], p12 = ww[5];
  auto difference = [&](ExprId a, ExprId b) { return g.share(g.sub(a, b)); };
  return {V3{dw[0], p02, g.neg(p01)},                                  // XX
          V3{g.neg(U[6]), U[7], difference(p00, p11)},                 // XY
          V3{U[3], difference(p22, p00), g.neg(U[5])},                 // XZ
          V3{g.neg(p12), dw[1], p01},                                  // YY
          V3{difference(p11, p22), g.neg(U[1]), U[2]},                 // YZ
          V3{p12, g.neg(p02), dw[2]}};                                 // ZZ
}

}  // namespace

SymbolicMotion derive_motion(ExprGraph& g, const RigidBodyTree& tree, const SymbolicInputs& in) {
  VectorAlgebra va(g);
  const std::size_t n = tree.bodies.size();
  SymbolicMotion m;
  m.R.resize(n);
  m.p.resize(n);
  m.w.resize(n);
  m.dw.resize(n);
  m.dv.resize(n);
  m.v.resize(n);
  m.ww.resize(n);
  m.U.resize(n);
  // Gravity as an upward acceleration of the base (dv0 = -g).
  const V3 base_dv = va.vector({-tree.gravity[0], -tree.gravity[1], -tree.gravity[2]});
  for (std::size_t j = 0; j < n; ++j) {
    const Body& body = tree.bodies[j];
    const M3 Rf = va.matrix(body.fixed.rotation);
    const V3 tf = va.vector(body.fixed.translation);
    const V3 u = va.vector(body.axis);
    const int i = body.dof_index;
    switch (body.type) {
      case JointType::kRevolute:
        m.R[j] = va.mul(Rf, axis_rotation(g, body.axis, in.sin_q[i], in.cos_q[i]));
        m.p[j] = tf;
        break;
      case JointType::kPrismatic:
        m.R[j] = Rf;
        m.p[j] = va.add(tf, va.mul(Rf, va.scale(in.q[i], u)));
        break;
      case JointType::kFixed:
        m.R[j] = Rf;
        m.p[j] = tf;
        break;
    }
    V3 wa = va.zero(), dwa = va.zero(), dva = base_dv, va_ = va.zero();
    M3 Ua;
    Ua.fill(g.zero());
    if (body.parent >= 0) {
      wa = m.w[body.parent];
      dwa = m.dw[body.parent];
      dva = m.dv[body.parent];
      va_ = m.v[body.parent];
      Ua = m.U[body.parent];
    }
    const V3& p = m.p[j];
    // Shared: the joint's own terms multiply it, and a product would flatten into theirs.
    const V3 w_in = va.share(va.mul_transposed(m.R[j], wa));
    m.w[j] = w_in;
    m.dw[j] = va.mul_transposed(m.R[j], dwa);
    m.v[j] = va.mul_transposed(m.R[j], va.add(va_, va.cross(wa, p)));
    // dv_j = R_j^T (dv_a + U_a p_j) (Khalil & Kleinfinger): U_a is the antecedent's own.
    m.dv[j] = va.mul_transposed(m.R[j], va.add(dva, va.mul(Ua, p)));
    if (body.type == JointType::kRevolute) {
      const V3 dq_u = va.scale(in.dq[i], u);
      m.w[j] = va.add(m.w[j], dq_u);
      m.dw[j] = va.add(m.dw[j], va.add(va.scale(in.ddq[i], u), va.cross(w_in, dq_u)));
    } else if (body.type == JointType::kPrismatic) {
      const V3 dq_u = va.scale(in.dq[i], u);
      m.v[j] = va.add(m.v[j], dq_u);
      m.dv[j] = va.add(m.dv[j], va.add(va.scale(in.ddq[i], u),
                                       va.scale(g.constant(2.0), va.cross(m.w[j], dq_u))));
    }
    m.w[j] = va.share(m.w[j]);
    m.dw[j] = va.share(m.dw[j]);
    m.dv[j] = va.share(m.dv[j]);
    m.v[j] = va.share(m.v[j]);
    m.ww[j] = angular_velocity_products(g, m.w[j]);
    m.U[j] = u_matrix(g, m.dw[j], m.ww[j]);
  }
  return m;
}

namespace {

// Torque contribution of a joint's drive parameter (inertia, friction, offset).
ExprId drive_column(ExprGraph& g, ParamKind kind, int i, const SymbolicInputs& in) {
  switch (kind) {
    case ParamKind::kIa: return in.ddq[i];
    case ParamKind::kFv: return in.dq[i];
    case ParamKind::kFc: return in.sign_dq[i];
    case ParamKind::kOff: return g.one();
    case ParamKind::kFvPos: return g.mul(in.positive_dq[i], in.dq[i]);
    case ParamKind::kFvNeg: return g.mul(in.negative_dq[i], in.dq[i]);
    case ParamKind::kFcPos: return in.positive_dq[i];
    case ParamKind::kFcNeg: return g.neg(in.negative_dq[i]);
    default: return g.zero();
  }
}

// Torques of a coupled motor's parameter on every joint: c_l times the motor term, with the
// motor velocity u' = c . dq (Gautier & Briot eq. 26).
std::vector<ExprId> motor_columns(ExprGraph& g, const RigidBodyTree& tree, const StandardParam& param,
                                  const SymbolicInputs& in) {
  const CoupledMotor& motor = *coupled_motor_of(tree, param);
  std::vector<ExprId> velocity, acceleration;
  for (int l = 0; l < tree.dof; ++l) {
    if (motor.coupling[l] == 0.0) continue;
    velocity.push_back(g.mul(g.constant(motor.coupling[l]), in.dq[l]));
    acceleration.push_back(g.mul(g.constant(motor.coupling[l]), in.ddq[l]));
  }
  const ExprId u = g.share(g.add(velocity));
  ExprId term = g.zero();
  switch (param.kind) {
    case ParamKind::kIam: term = g.share(g.add(acceleration)); break;
    case ParamKind::kFvm: term = u; break;
    case ParamKind::kFcm: term = g.sign(u); break;
    default: break;
  }
  std::vector<ExprId> columns(tree.dof, g.zero());
  for (int l = 0; l < tree.dof; ++l) columns[l] = g.mul(g.constant(motor.coupling[l]), term);
  return columns;
}

// The axis of joint i as a screw expressed at body j (j at or below i): a torque about the
// joint from a wrench (f, n) at body j's origin, in frame j, is a . n + b . f, with
// a = R_ij^T u_i and b = R_ij^T (u_i x p_ij). Built outward once per (joint, body) pair,
// a_j = R_j^T a_a and b_j = R_j^T (b_a + a_a x p_j), instead of carrying every parameter's
// wrench down to the base: the regressor's columns then cost two dot products each.
struct JointScrew {
  V3 a, b;
};

class JointScrews {
 public:
  JointScrews(ExprGraph& g, const RigidBodyTree& tree, const SymbolicMotion& m)
      : n_(tree.bodies.size()), screws_(n_ * n_) {
    VectorAlgebra va(g);
    for (std::size_t i = 0; i < n_; ++i) {
      if (tree.bodies[i].type == JointType::kFixed) continue;
      at(i, i) = {va.vector(tree.bodies[i].axis), va.zero()};
      // Bodies are ordered parents first, so one pass reaches the whole subtree of i.
      std::vector<bool> below(n_, false);
      below[i] = true;
      for (std::size_t j = i + 1; j < n_; ++j) {
        const int a = tree.bodies[j].parent;
        if (a < 0 || !below[a]) continue;
        below[j] = true;
        const JointScrew& s = at(i, a);
        at(i, j) = {va.share(va.mul_transposed(m.R[j], s.a)),
                    va.share(va.mul_transposed(m.R[j], va.add(s.b, va.cross(s.a, m.p[j]))))};
      }
    }
  }
  const JointScrew& at(std::size_t joint, std::size_t body) const {
    return screws_[joint * n_ + body];
  }

 private:
  JointScrew& at(std::size_t joint, std::size_t body) { return screws_[joint * n_ + body]; }
  std::size_t n_;
  std::vector<JointScrew> screws_;
};

bool is_motor(ParamKind kind) {
  return kind == ParamKind::kIam || kind == ParamKind::kFvm || kind == ParamKind::kFcm;
}

}  // namespace

SymbolicInputs make_symbolic_inputs(ExprGraph& g, const RigidBodyTree& tree) {
  SymbolicInputs in;
  for (int i = 0; i < tree.dof; ++i) {
    const std::string k = std::to_string(i);
    const std::string j = std::to_string(i + 1);
    in.q.push_back(g.symbol({"q[" + k + "]", SymbolKind::kInput, ""}));
    in.dq.push_back(g.symbol({"dq[" + k + "]", SymbolKind::kInput, ""}));
    in.ddq.push_back(g.symbol({"ddq[" + k + "]", SymbolKind::kInput, ""}));
    in.sin_q.push_back(g.symbol({"s" + j, SymbolKind::kSin, "q[" + k + "]"}));
    in.cos_q.push_back(g.symbol({"c" + j, SymbolKind::kCos, "q[" + k + "]"}));
    in.sign_dq.push_back(g.symbol({"sg" + j, SymbolKind::kSign, "dq[" + k + "]"}));
    in.positive_dq.push_back(g.symbol({"pos" + j, SymbolKind::kPositive, "dq[" + k + "]"}));
    in.negative_dq.push_back(g.symbol({"neg" + j, SymbolKind::kNegative, "dq[" + k + "]"}));
  }
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    in.p.push_back(g.symbol({"p[" + std::to_string(k) + "]", SymbolKind::kInput, ""}));
  }
  return in;
}

std::vector<ExprId> derive_standard_regressor(ExprGraph& g, const RigidBodyTree& tree,
                                              const SymbolicInputs& in) {
  VectorAlgebra va(g);
  const SymbolicMotion m = derive_motion(g, tree, in);
  const std::size_t num_params = tree.params.size();
  std::vector<ExprId> W(tree.dof * num_params, g.zero());
  const V3 ex = va.vector({1, 0, 0}), ey = va.vector({0, 1, 0}), ez = va.vector({0, 0, 1});
  const JointScrews screws(g, tree, m);
  for (std::size_t k = 0; k < num_params; ++k) {
    const StandardParam& param = tree.params[k];
    const Body& owner = tree.bodies[param.body];
    if (is_motor(param.kind)) {
      const std::vector<ExprId> columns = motor_columns(g, tree, param, in);
      for (int l = 0; l < tree.dof; ++l) W[l * num_params + k] = columns[l];
      continue;
    }
    if (!is_inertial(param.kind)) {
      W[owner.dof_index * num_params + k] = drive_column(g, param.kind, owner.dof_index, in);
      continue;
    }
    // Wrench on the body about its origin per unit of this parameter (F = M dv + U MS,
    // N = J dw + w x (J w) + MS x dv): a unit inertia entry's moment, a unit first moment's
    // force U e (U's column) and moment e x dv, a unit mass's force dv.
    const std::size_t body = static_cast<std::size_t>(param.body);
    const V3& dv = m.dv[body];
    const M3& U = m.U[body];
    V3 f = va.zero(), nm = va.zero();
    auto inertia = [&](int entry) { nm = inertia_moment_columns(g, m, body)[entry]; };
    auto first_moment = [&](int axis) {
      f = {U[axis], U[3 + axis], U[6 + axis]};
      nm = va.cross(axis == 0 ? ex : (axis == 1 ? ey : ez), dv);
    };
    switch (param.kind) {
      case ParamKind::kXX: inertia(0); break;
      case ParamKind::kXY: inertia(1); break;
      case ParamKind::kXZ: inertia(2); break;
      case ParamKind::kYY: inertia(3); break;
      case ParamKind::kYZ: inertia(4); break;
      case ParamKind::kZZ: inertia(5); break;
      case ParamKind::kMX: first_moment(0); break;
      case ParamKind::kMY: first_moment(1); break;
      case ParamKind::kMZ: first_moment(2); break;
      case ParamKind::kM: f = dv; break;
      default: break;
    }
    // Each moving joint i at or below the body takes its torque through the joint's screw
    // expressed at this body: tau_i = a . n + b . f (revolute) or a . f (prismatic).
    f = va.share(f);
    nm = va.share(nm);
    for (int b = param.body; b >= 0; b = tree.bodies[b].parent) {
      const Body& joint = tree.bodies[b];
      if (joint.type == JointType::kFixed) continue;
      const JointScrew& screw = screws.at(b, param.body);
      W[joint.dof_index * num_params + k] =
          joint.type == JointType::kRevolute ? g.add(va.dot(screw.a, nm), va.dot(screw.b, f))
                                             : va.dot(screw.a, f);
    }
  }
  return W;
}

std::vector<ExprId> derive_inverse_dynamics(ExprGraph& g, const RigidBodyTree& tree,
                                            const SymbolicInputs& in) {
  VectorAlgebra va(g);
  const SymbolicMotion m = derive_motion(g, tree, in);
  const std::size_t n = tree.bodies.size();
  std::vector<std::array<ExprId, 6>> J(n);
  std::vector<V3> MS(n, va.zero());
  std::vector<ExprId> M(n, g.zero());
  std::vector<ExprId> drive(tree.dof, g.zero());
  for (auto& j : J) j.fill(g.zero());
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const StandardParam& param = tree.params[k];
    const ExprId p = in.p[k];
    const int b = param.body;
    switch (param.kind) {
      case ParamKind::kXX: J[b][0] = g.add(J[b][0], p); break;
      case ParamKind::kXY: J[b][1] = g.add(J[b][1], p); break;
      case ParamKind::kXZ: J[b][2] = g.add(J[b][2], p); break;
      case ParamKind::kYY: J[b][3] = g.add(J[b][3], p); break;
      case ParamKind::kYZ: J[b][4] = g.add(J[b][4], p); break;
      case ParamKind::kZZ: J[b][5] = g.add(J[b][5], p); break;
      case ParamKind::kMX: MS[b][0] = g.add(MS[b][0], p); break;
      case ParamKind::kMY: MS[b][1] = g.add(MS[b][1], p); break;
      case ParamKind::kMZ: MS[b][2] = g.add(MS[b][2], p); break;
      case ParamKind::kM: M[b] = g.add(M[b], p); break;
      default: {
        const int i = tree.bodies[b].dof_index;
        if (is_motor(param.kind)) {
          const std::vector<ExprId> columns = motor_columns(g, tree, param, in);
          for (int l = 0; l < tree.dof; ++l) drive[l] = g.add(drive[l], g.mul(columns[l], p));
          break;
        }
        drive[i] = g.add(drive[i], g.mul(drive_column(g, param.kind, i, in), p));
      }
    }
  }
  std::vector<V3> f(n), nm(n);
  for (std::size_t j = 0; j < n; ++j) {
    // F = M dv + U MS, N = J dw + w x (J w) + MS x dv (Khalil & Kleinfinger's customized
    // model): J's moment term entry by entry from dw, U and the products of w, with the
    // diagonal entries' gyroscopic parts paired, (ZZ - YY) w1 w2 and so on, one product each.
    f[j] = va.add(va.scale(M[j], m.dv[j]), va.mul(m.U[j], MS[j]));
    const std::array<V3, 6> K = inertia_moment_columns(g, m, j);
    const std::array<ExprId, 6>& ww = m.ww[j];
    const ExprId xx = J[j][0], xy = J[j][1], xz = J[j][2], yy = J[j][3], yz = J[j][4], zz = J[j][5];
    V3 inertia_moment;
    for (int c = 0; c < 3; ++c) {
      inertia_moment[c] = g.add({g.mul(xy, K[1][c]), g.mul(xz, K[2][c]), g.mul(yz, K[4][c])});
    }
    inertia_moment[0] = g.add({inertia_moment[0], g.mul(xx, m.dw[j][0]), g.mul(g.sub(zz, yy), ww[5])});
    inertia_moment[1] = g.add({inertia_moment[1], g.mul(yy, m.dw[j][1]), g.mul(g.sub(xx, zz), ww[4])});
    inertia_moment[2] = g.add({inertia_moment[2], g.mul(zz, m.dw[j][2]), g.mul(g.sub(yy, xx), ww[3])});
    nm[j] = va.add(inertia_moment, va.cross(MS[j], m.dv[j]));
  }
  std::vector<ExprId> tau(tree.dof, g.zero());
  for (std::size_t j = n; j-- > 0;) {
    const Body& body = tree.bodies[j];
    // The joint torque and the antecedent's wrench both read this wrench: compute it once.
    f[j] = va.share(f[j]);
    nm[j] = va.share(nm[j]);
    if (body.type != JointType::kFixed) {
      const V3 u = va.vector(body.axis);
      tau[body.dof_index] =
          g.add(va.dot(body.type == JointType::kRevolute ? nm[j] : f[j], u), drive[body.dof_index]);
    }
    if (body.parent >= 0) {
      // The wrench this body exerts on its antecedent, in the antecedent's frame.
      const V3 f_parent = va.share(va.mul(m.R[j], f[j]));
      const V3 n_parent = va.add(va.mul(m.R[j], nm[j]), va.cross(m.p[j], f_parent));
      f[body.parent] = va.add(f[body.parent], f_parent);
      nm[body.parent] = va.add(nm[body.parent], n_parent);
    }
  }
  return tau;
}

}  // namespace modelgen::gen
