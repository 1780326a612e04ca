// Khalil's regrouping rules applied from the last link to the first, with the coefficients kept
// as expressions of d_j and r_j on an ExprGraph so they print with symbols and evaluate with
// numbers. tests/generator/dynamics/closed_form_base_test.cpp checks them against the numeric method.

#include "generator/dynamics/closed_form_base.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "generator/describe.hpp"

namespace modelgen::gen {

namespace {

constexpr ParamKind kTensor[3][3] = {{ParamKind::kXX, ParamKind::kXY, ParamKind::kXZ},
                                     {ParamKind::kXY, ParamKind::kYY, ParamKind::kYZ},
                                     {ParamKind::kXZ, ParamKind::kYZ, ParamKind::kZZ}};
constexpr ParamKind kMoment[3] = {ParamKind::kMX, ParamKind::kMY, ParamKind::kMZ};

class Regrouper {
 public:
  Regrouper(const RobotModel& model, ClosedFormRelations& out)
      : model_(model), out_(out), g_(out.graph), relation_(model.tree.params.size()) {
    for (std::size_t k = 0; k < relation_.size(); ++k) relation_[k][static_cast<int>(k)] = g_.one();
  }

  void run() {
    const RigidBodyTree& tree = model_.tree;
    for (int j = static_cast<int>(tree.bodies.size()) - 1; j >= 0; --j) {
      switch (tree.bodies[j].type) {
        case JointType::kRevolute: revolute(j); break;
        case JointType::kPrismatic: prismatic(j); break;
        case JointType::kFixed: fixed(j); break;
      }
    }
    for (std::size_t k = 0; k < relation_.size(); ++k) {
      if (!relation_[k].empty()) out_.relations[static_cast<int>(k)] = relation_[k];
    }
  }

 private:
  int index(int body, ParamKind kind) const {
    if (body < 0) return -1;
    for (std::size_t k = 0; k < model_.tree.params.size(); ++k) {
      if (model_.tree.params[k].body == body && model_.tree.params[k].kind == kind) {
        return static_cast<int>(k);
      }
    }
    return -1;
  }

  // beta_into += c * (relation of `from`); nothing when `into` is the base (no effect there).
  void move(int from, int into, ExprId c) {
    if (from < 0 || into < 0 || g_.is_zero(c)) return;
    for (const auto& [l, coefficient] : relation_[from]) {
      auto [it, inserted] = relation_[into].emplace(l, g_.zero());
      it->second = g_.add(it->second, g_.mul(c, coefficient));
      static_cast<void>(inserted);
    }
  }
  void eliminate(int k) {
    if (k >= 0) relation_[k].clear();
  }

  // Geometric symbol d_j or r_j (1-based link number), or 0 when the value is 0.
  ExprId geometry(char letter, int body, double value) {
    if (value == 0.0) return g_.zero();
    const std::string name = letter + std::to_string(body + 1);
    out_.geometry[name] = value;
    return g_.symbol({name, SymbolKind::kInput, ""});
  }

  // Revolute joint j: YY_j, MZ_j, M_j regroup (Khalil & Dombre, eq. 14.x):
  // XXR_j = XX_j - YY_j, and into the antecedent a through alpha_j, d_j, r_j.
  void revolute(int j) {
    const int a = model_.tree.bodies[j].parent;
    const MdhParameters& mdh = *model_.joints[j].mdh;
    const ExprId d = geometry('d', j, mdh.d), r = geometry('r', j, mdh.r);
    const ExprId ca = g_.constant(mdh.alpha.cos()), sa = g_.constant(mdh.alpha.sin());
    const int XX = index(j, ParamKind::kXX), YY = index(j, ParamKind::kYY);
    const int MZ = index(j, ParamKind::kMZ), M = index(j, ParamKind::kM);
    auto at = [&](ParamKind kind) { return index(a, kind); };
    const ExprId two = g_.constant(2.0);
    const ExprId ca2 = g_.mul(ca, ca), sa2 = g_.mul(sa, sa), casa = g_.mul(ca, sa);
    const ExprId r2 = g_.mul(r, r), d2 = g_.mul(d, d);
    move(YY, XX, g_.constant(-1.0));
    move(YY, at(ParamKind::kXX), g_.one());
    move(MZ, at(ParamKind::kXX), g_.mul(two, r));
    move(M, at(ParamKind::kXX), r2);
    move(MZ, at(ParamKind::kXY), g_.mul(d, sa));
    move(M, at(ParamKind::kXY), g_.mul({d, sa, r}));
    move(MZ, at(ParamKind::kXZ), g_.neg(g_.mul(d, ca)));
    move(M, at(ParamKind::kXZ), g_.neg(g_.mul({d, ca, r})));
    move(YY, at(ParamKind::kYY), ca2);
    move(MZ, at(ParamKind::kYY), g_.mul({two, r, ca2}));
    move(M, at(ParamKind::kYY), g_.add(d2, g_.mul(r2, ca2)));
    move(YY, at(ParamKind::kYZ), casa);
    move(MZ, at(ParamKind::kYZ), g_.mul({two, r, casa}));
    move(M, at(ParamKind::kYZ), g_.mul(r2, casa));
    move(YY, at(ParamKind::kZZ), sa2);
    move(MZ, at(ParamKind::kZZ), g_.mul({two, r, sa2}));
    move(M, at(ParamKind::kZZ), g_.add(d2, g_.mul(r2, sa2)));
    move(M, at(ParamKind::kMX), d);
    move(MZ, at(ParamKind::kMY), g_.neg(sa));
    move(M, at(ParamKind::kMY), g_.neg(g_.mul(r, sa)));
    move(MZ, at(ParamKind::kMZ), ca);
    move(M, at(ParamKind::kMZ), g_.mul(r, ca));
    move(M, at(ParamKind::kM), g_.one());
    eliminate(YY);
    eliminate(MZ);
    eliminate(M);
  }

  // J_a += A J_j A^T for the constant rotation A = antecedent <- j.
  void move_tensor(int j, int a, const std::array<double, 9>& A) {
    for (int p = 0; p < 3; ++p) {
      for (int q = p; q < 3; ++q) {
        const int target = index(a, kTensor[p][q]);
        for (int k = 0; k < 3; ++k) {
          for (int l = k; l < 3; ++l) {
            double c = A[3 * p + k] * A[3 * q + l];
            if (k != l) c += A[3 * p + l] * A[3 * q + k];
            move(index(j, kTensor[k][l]), target, g_.constant(c));
          }
        }
      }
    }
  }

  // Prismatic joint j: link j does not rotate relative to its antecedent, so its inertia
  // tensor acts only through the antecedent's rotation.
  void prismatic(int j) {
    const int a = model_.tree.bodies[j].parent;
    move_tensor(j, a, model_.tree.bodies[j].fixed.rotation);
    for (int p = 0; p < 3; ++p) {
      for (int q = p; q < 3; ++q) eliminate(index(j, kTensor[p][q]));
    }
  }

  // Fixed link j: its ten parameters join the antecedent's (rotation A, translation P =
  // (d, -sin(alpha) r, cos(alpha) r)): M_a += M, MS_a += A MS + M P,
  // J_a += A J A^T + M (|P|^2 1 - P P^T) + 2 (P . A MS) 1 - P (A MS)^T - (A MS) P^T.
  void fixed(int j) {
    const int a = model_.tree.bodies[j].parent;
    const MdhParameters& mdh = *model_.joints[j].mdh;
    const std::array<double, 9>& A = model_.tree.bodies[j].fixed.rotation;
    const ExprId d = geometry('d', j, mdh.d), r = geometry('r', j, mdh.r);
    const std::array<ExprId, 3> P = {d, g_.neg(g_.mul(g_.constant(mdh.alpha.sin()), r)),
                                     g_.mul(g_.constant(mdh.alpha.cos()), r)};
    const int M = index(j, ParamKind::kM);
    move_tensor(j, a, A);
    const ExprId PP = g_.add({g_.mul(P[0], P[0]), g_.mul(P[1], P[1]), g_.mul(P[2], P[2])});
    for (int p = 0; p < 3; ++p) {
      for (int q = p; q < 3; ++q) {
        const int target = index(a, kTensor[p][q]);
        move(M, target, g_.sub(p == q ? PP : g_.zero(), g_.mul(P[p], P[q])));
        for (int k = 0; k < 3; ++k) {
          // The first moment k of link j, rotated: A[:, k] MS_k.
          const ExprId Ak_dot_P = g_.add({g_.mul(g_.constant(A[k]), P[0]),
                                          g_.mul(g_.constant(A[3 + k]), P[1]),
                                          g_.mul(g_.constant(A[6 + k]), P[2])});
          const ExprId c = g_.sub(p == q ? g_.mul(g_.constant(2.0), Ak_dot_P) : g_.zero(),
                                  g_.add(g_.mul(P[p], g_.constant(A[3 * q + k])),
                                         g_.mul(g_.constant(A[3 * p + k]), P[q])));
          move(index(j, kMoment[k]), target, c);
        }
      }
    }
    for (int p = 0; p < 3; ++p) {
      for (int k = 0; k < 3; ++k) {
        move(index(j, kMoment[k]), index(a, kMoment[p]), g_.constant(A[3 * p + k]));
      }
      move(M, index(a, kMoment[p]), P[p]);
    }
    move(M, index(a, ParamKind::kM), g_.one());
    for (int p = 0; p < 3; ++p) {
      for (int q = p; q < 3; ++q) eliminate(index(j, kTensor[p][q]));
      eliminate(index(j, kMoment[p]));
    }
    eliminate(M);
  }

  const RobotModel& model_;
  ClosedFormRelations& out_;
  ExprGraph& g_;
  std::vector<std::map<int, ExprId>> relation_;
};

// Prints a coefficient: products with repeated factors as powers, sums with signs.
std::string print(const ExprGraph& g, ExprId id) {
  const Node& n = g.node(id);
  switch (n.op) {
    case Op::kConstant: return format_number(n.value);
    case Op::kSymbol: return g.symbols()[n.symbol].name;
    case Op::kShare:
    case Op::kSign: return print(g, n.args[0]);
    case Op::kInv: return "1/(" + print(g, n.args[0]) + ")";
    case Op::kMul: {
      std::string out;
      std::size_t i = 0;
      if (g.is_constant(n.args[0])) {
        const double c = g.constant_value(n.args[0]);
        out = c == -1.0 ? "-" : format_number(c) + "*";
        i = 1;
      }
      while (i < n.args.size()) {
        std::size_t k = i;
        while (k < n.args.size() && n.args[k] == n.args[i]) ++k;
        const Node& factor = g.node(n.args[i]);
        std::string text = print(g, n.args[i]);
        if (factor.op == Op::kAdd) text = "(" + text + ")";
        if (k - i > 1) text += "^" + std::to_string(k - i);
        out += (out.empty() || out.back() == '-' || out.back() == '*' ? "" : "*") + text;
        i = k;
      }
      return out;
    }
    case Op::kAdd: {
      // Terms in alphabetical order (ignoring signs): "d3^2 + r3^2" reads like the books.
      std::vector<std::string> terms;
      for (ExprId term : n.args) terms.push_back(print(g, term));
      std::sort(terms.begin(), terms.end(), [](const std::string& x, const std::string& y) {
        return (x[0] == '-' ? x.substr(1) : x) < (y[0] == '-' ? y.substr(1) : y);
      });
      std::string out;
      for (const std::string& text : terms) {
        if (out.empty()) {
          out = text;
        } else if (!text.empty() && text[0] == '-') {
          out += " - " + text.substr(1);
        } else {
          out += " + " + text;
        }
      }
      return out;
    }
  }
  return "?";
}

}  // namespace

double ClosedFormRelations::value(ExprId coefficient) const {
  const std::vector<double> values = graph.evaluate([this](const Symbol& s) {
    auto found = geometry.find(s.name);
    return found == geometry.end() ? 0.0 : found->second;
  });
  return values[coefficient];
}

std::string ClosedFormRelations::text(ExprId coefficient) const {
  return print(graph, coefficient);
}

std::optional<ClosedFormRelations> derive_closed_form_relations(const RobotModel& model) {
  if (model.format != DescriptionFormat::kMdhYaml) return std::nullopt;
  ClosedFormRelations out;
  Regrouper(model, out).run();
  return out;
}

}  // namespace modelgen::gen
