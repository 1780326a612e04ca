// Symbolic partial derivatives on the expression DAG with respect to one symbol (a joint
// variable, a parameter), by the sum, product and chain rules, and the Jacobian of many
// expressions with respect to many symbols. Used for the state Jacobian of the inverse dynamics
// that maximum-likelihood estimation with errors in variables needs (Bona & Curatella eq. 15-16:
// B = d G / d x), never finite differences.
#pragma once

#include <vector>

#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

/// d e / d x for one symbol x, memoized per node: several expressions differentiated with the
/// same object share the work, and each node's derivative is built once. Rules:
/// - d x / d x = 1; every other symbol is independent of x (0), except the leaves derived from
///   x (Symbol::input equal to x's name): d sin x = cos x and d cos x = -sin x exactly (the
///   partner leaf must exist in the graph, as make_symbolic_inputs creates both), and
///   d sign x = d pos x = d neg x = 0.
/// - sign(e) (Op::kSign and the derived sign leaves) has derivative 0. It is piecewise
///   constant, so this is its derivative wherever it exists: everywhere except where its
///   argument changes sign (for friction, where a joint velocity crosses zero).
/// - d (1/e) = -(1/e)^2 d e, with the node 1/e itself as the factor (no new division).
/// - The derivative of share(e) is share(d e): derivatives of intermediate results stay
///   intermediate results, so generated code keeps the customized Newton-Euler structure.
/// - An expression not containing x has derivative graph.zero(), the constant 0 node.
class PartialDerivative {
 public:
  /// `variable` must be a symbol node of `graph` (std::invalid_argument otherwise). The graph
  /// grows as derivatives are built; it must outlive this object.
  PartialDerivative(ExprGraph& graph, ExprId variable);

  /// d e / d x. Throws std::logic_error if e contains sin x (cos x) but the graph has no cos x
  /// (sin x) leaf to express its derivative.
  ExprId operator()(ExprId e);

  /// d e / d x for each of `expressions`, in the same order, sharing the memo.
  std::vector<ExprId> operator()(const std::vector<ExprId>& expressions);

  ExprId variable() const { return variable_; }

 private:
  ExprId differentiate_node(ExprId e);
  ExprId differentiate_symbol(ExprId e);
  // The leaf of kind `kind` (sin or cos) computed from the same input as the leaf `of`.
  ExprId partner(SymbolKind kind, ExprId of);

  static constexpr ExprId kNotDone = ~ExprId{0};

  ExprGraph& graph_;
  ExprId variable_;
  std::vector<ExprId> done_;  // derivative of each node id, kNotDone before it is built
};

/// Jacobian of `expressions` (m) with respect to the symbols `variables` (n), row-major:
/// result[i * n + k] = d expressions[i] / d variables[k]. Entries that do not depend on a
/// variable are graph.zero(). Throws as PartialDerivative does.
std::vector<ExprId> jacobian(ExprGraph& graph, const std::vector<ExprId>& expressions,
                             const std::vector<ExprId>& variables);

}  // namespace modelgen::gen
