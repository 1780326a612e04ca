// Symbolic time derivative on the expression DAG, by the sum and product rules and the chain
// rule through the leaves (d q/dt = dq, d sin q/dt = cos q dq, ...). Used for the power model
// (Gautier & Briot eq. 9-10: dh = d h / dt), never finite differences.
#pragma once

#include <unordered_map>

#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

class TimeDerivative {
 public:
  /// `leaf_derivatives` maps symbol nodes to their time derivative; symbols not listed are
  /// constant in time (parameters).
  TimeDerivative(ExprGraph& graph, std::unordered_map<ExprId, ExprId> leaf_derivatives)
      : graph_(graph), leaves_(std::move(leaf_derivatives)) {}

  /// d e / dt, memoized: shared subexpressions are differentiated once.
  ExprId operator()(ExprId e);

 private:
  ExprGraph& graph_;
  std::unordered_map<ExprId, ExprId> leaves_;
  std::unordered_map<ExprId, ExprId> done_;
};

}  // namespace modelgen::gen
