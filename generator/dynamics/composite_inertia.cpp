// Composite rigid bodies over the expression DAG. A body's ten inertial parameters about its
// frame origin (J, MS, M: Khalil & Kleinfinger's, linear in the standard parameters) move to
// the antecedent's frame as J' = R J R^T + M (|p|^2 1 - p p^T) + 2 (p . MS') 1 - p MS'^T -
// MS' p^T, MS' = R MS, MS_a += MS' + M p (the parallel-axis theorem about a shifted origin).
// With the rotations' exact zeros and ones folded, a quarter-turn MDH step costs a few products.

#include "generator/dynamics/composite_inertia.hpp"

#include <array>

#include "generator/dynamics/symbolic_vectors.hpp"

namespace modelgen::gen {

namespace {

// Inertial parameters about a body's frame origin, in its frame. J row-major and symmetric.
struct Inertia {
  M3 J;
  V3 MS;
  ExprId M;
};

Inertia own_inertia(ExprGraph& g, const RigidBodyTree& tree, const SymbolicInputs& in, int body) {
  Inertia out;
  out.J.fill(g.zero());
  out.MS = {g.zero(), g.zero(), g.zero()};
  out.M = g.zero();
  // Entry of J per inertia kind, in ParamKind order XX, XY, XZ, YY, YZ, ZZ.
  const int entries[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  for (std::size_t k = 0; k < tree.params.size(); ++k) {
    const StandardParam& param = tree.params[k];
    if (param.body != body || !is_inertial(param.kind)) continue;
    const int slot = inertial_slot(param.kind);
    const ExprId p = in.p[k];
    if (slot < 6) {
      const int r = entries[slot][0], c = entries[slot][1];
      out.J[3 * r + c] = g.add(out.J[3 * r + c], p);
      if (r != c) out.J[3 * c + r] = out.J[3 * r + c];
    } else if (slot < 9) {
      out.MS[slot - 6] = g.add(out.MS[slot - 6], p);
    } else {
      out.M = g.add(out.M, p);
    }
  }
  return out;
}

// `child` (about its origin, in its frame) in the frame of its antecedent, about its origin:
// R rotates child to antecedent, p is the child's origin in the antecedent.
Inertia to_antecedent(ExprGraph& g, const Inertia& child, const M3& R, const V3& p) {
  VectorAlgebra va(g);
  Inertia out;
  const V3 ms = va.share(va.mul(R, child.MS));  // MS' = R MS
  M3 RJ;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      RJ[3 * r + c] =
          g.share(g.add({g.mul(R[3 * r], child.J[c]), g.mul(R[3 * r + 1], child.J[3 + c]),
                         g.mul(R[3 * r + 2], child.J[6 + c])}));
    }
  }
  const ExprId p_ms = g.mul(g.constant(2.0), va.dot(p, ms));
  const ExprId pp = va.dot(p, p);
  for (int r = 0; r < 3; ++r) {
    for (int c = r; c < 3; ++c) {
      std::vector<ExprId> terms = {
          g.mul(RJ[3 * r], R[3 * c]),         g.mul(RJ[3 * r + 1], R[3 * c + 1]),
          g.mul(RJ[3 * r + 2], R[3 * c + 2]), g.neg(g.mul(child.M, g.mul(p[r], p[c]))),
          g.neg(g.mul(p[r], ms[c])),          g.neg(g.mul(ms[r], p[c]))};
      if (r == c) {
        terms.push_back(g.mul(child.M, pp));
        terms.push_back(p_ms);
      }
      out.J[3 * r + c] = g.add(std::move(terms));
      out.J[3 * c + r] = out.J[3 * r + c];
    }
  }
  out.MS = va.add(ms, va.scale(child.M, p));
  out.M = child.M;
  return out;
}

}  // namespace

std::vector<ExprId> derive_rigid_body_mass_matrix(ExprGraph& g, const RigidBodyTree& tree,
                                                  const SymbolicInputs& in) {
  VectorAlgebra va(g);
  const SymbolicMotion m = derive_motion(g, tree, in);
  const std::size_t n = tree.bodies.size();
  std::vector<Inertia> composite(n);
  for (std::size_t j = 0; j < n; ++j) composite[j] = own_inertia(g, tree, in, static_cast<int>(j));
  // Children after parents: from the last body back, each composite is complete when it is
  // added to its antecedent's.
  for (std::size_t j = n; j-- > 0;) {
    Inertia& c = composite[j];
    for (ExprId& e : c.J) e = g.share(e);
    c.MS = va.share(c.MS);
    c.M = g.share(c.M);
    const int a = tree.bodies[j].parent;
    if (a < 0) continue;
    const Inertia moved = to_antecedent(g, c, m.R[j], m.p[j]);
    Inertia& parent = composite[a];
    for (int e = 0; e < 9; ++e) parent.J[e] = g.add(parent.J[e], moved.J[e]);
    parent.MS = va.add(parent.MS, moved.MS);
    parent.M = g.add(parent.M, moved.M);
  }
  const int dof = tree.dof;
  std::vector<ExprId> M(dof * dof, g.zero());
  for (std::size_t j = 0; j < n; ++j) {
    const Body& body = tree.bodies[j];
    if (body.type == JointType::kFixed) continue;
    // Wrench (f, nm) about body j's origin that a unit acceleration of its joint asks of the
    // composite body at rest: revolute dw = u, dv = 0 (the axis through the origin) gives
    // f = u x MS, nm = J u; prismatic dv = u gives f = M u, nm = MS x u.
    const Inertia& c = composite[j];
    const V3 u = va.vector(body.axis);
    V3 f, nm;
    if (body.type == JointType::kRevolute) {
      f = va.cross(u, c.MS);
      nm = va.mul(c.J, u);
    } else {
      f = va.scale(c.M, u);
      nm = va.cross(c.MS, u);
    }
    const int k = body.dof_index;
    // Carried to each antecedent's frame, f_a = R f, nm_a = R nm + p x f_a; a moving joint on
    // the way takes its component along its axis.
    for (int b = static_cast<int>(j);;) {
      f = va.share(f);
      nm = va.share(nm);
      const Body& at = tree.bodies[b];
      if (at.type != JointType::kFixed) {
        const int i = at.dof_index;
        const ExprId value = va.dot(va.vector(at.axis), at.type == JointType::kRevolute ? nm : f);
        M[i * dof + k] = value;
        M[k * dof + i] = value;
      }
      if (at.parent < 0) break;
      const V3 f_a = va.share(va.mul(m.R[b], f));
      nm = va.add(va.mul(m.R[b], nm), va.cross(m.p[b], f_a));
      f = f_a;
      b = at.parent;
    }
  }
  return M;
}

}  // namespace modelgen::gen
