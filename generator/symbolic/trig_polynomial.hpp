// The canonical polynomial form of an expression in its leaves, with every joint's sine and
// cosine tied by s^2 + c^2 = 1: two expressions are equal as functions of the joint state
// exactly when their forms are equal. Used to prove that an expression which evaluates to zero
// at random states is identically zero (an exact cancellation the DAG's local rules miss, as
// c2 (dq2 (-dq1 s2)) - s2 (-dq2 (c2 dq1))), before the emitter drops it.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

/// A product of atoms with exponents, atoms ascending by node id. Atoms are symbol nodes and
/// the nodes the form does not look into: sign(e) and 1 / e.
using Monomial = std::vector<std::pair<ExprId, int>>;

/// Expands nodes of one graph into sums of monomials with every cos^2 replaced by 1 - sin^2 of
/// the same joint (the sin and cos leaves of one input, Symbol::input), memoized per node.
class TrigPolynomials {
 public:
  /// `max_terms` bounds every intermediate polynomial: a node whose expansion exceeds it has no
  /// form (deep Newton-Euler outputs expand to thousands of terms; only candidates that
  /// evaluated to zero are expanded).
  explicit TrigPolynomials(const ExprGraph& graph, std::size_t max_terms = 4000);

  /// True when `id` is identically zero: every coefficient of its form is below 1e-11 of the
  /// largest coefficient met while expanding it (geometry constants are rounded decimals, so
  /// an exact cancellation leaves round-off, not zero). False when a coefficient is larger;
  /// std::nullopt when the expansion is over budget.
  std::optional<bool> is_zero(ExprId id);

 private:
  struct Form {
    std::map<Monomial, double> terms;
    double scale = 0;  // the largest |coefficient| met building it
  };
  const Form* expand(ExprId id);
  void add_reduced(Form& out, Monomial monomial, double coefficient) const;
  static Monomial multiply(const Monomial& a, const Monomial& b);

  const ExprGraph& graph_;
  std::size_t max_terms_;
  std::unordered_map<ExprId, ExprId> sin_of_cos_;  // cos leaf -> sin leaf of the same input
  std::unordered_map<ExprId, std::optional<Form>> memo_;
};

}  // namespace modelgen::gen
