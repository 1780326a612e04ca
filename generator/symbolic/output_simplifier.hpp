// The rewrites between the derivations and the emitter, on the expressions a generated function
// writes: exact cancellations removed, and every product and sum put in a sign-normal form so
// that an expression and its negation (or a constant multiple of a product) become one
// temporary. The derivations build the DAG with local rules only (expr.hpp); these rewrites
// need the whole expression.
#pragma once

#include <array>
#include <vector>

#include "generator/symbolic/expr.hpp"
#include "generator/symbolic/trig_polynomial.hpp"

namespace modelgen::gen {

/// Rewrites nodes of one graph, memoized per node: functions emitted from one graph share the
/// work. Every builder must have run before the first call: the rewrite probes the nodes that
/// exist when it is constructed.
/// - Exact zeros: a sum whose value at four random states (consistent sines, cosines and
///   signs) is below 1e-9 of the size of its terms is expanded into its canonical polynomial
///   (TrigPolynomials); if that is zero, the sum is replaced by the constant 0, and every
///   expression using it is rebuilt (a product with it vanishes, a sum loses the term). Two
///   terms of a longer sum that cancel each other are tested and removed the same way. A sum
///   too deep to expand within the budget is replaced only if it is round-off at every probe
///   (below 1e-13 of its terms): whatever it could hide is below the 1e-12 the generated code
///   is held to.
/// - Sign-normal form: a product c x1 ... xn (n >= 2) becomes c * share(x1 ... xn), and a sum
///   s becomes f * share(s / f), with f the coefficient of the term whose base (the term
///   without its coefficient) comes first canonically when every term's coefficient has its
///   magnitude, else that coefficient's sign. So -a b and a b, a - b and b - a, or 0.035 a -
///   0.035 b and a - b are one shared node, and the statement writer prints the other uses as a
///   negation folded into the enclosing sum or as one multiplication.
class OutputSimplifier {
 public:
  explicit OutputSimplifier(ExprGraph& graph);

  /// The rewritten form of `id` (a node that existed at construction).
  ExprId operator()(ExprId id);

  /// Sums proven identically zero, and sums over the expansion budget taken as zero because
  /// they were round-off at every probe.
  int exact_zeros() const { return exact_zeros_; }
  int numeric_zeros() const { return numeric_zeros_; }

 private:
  static constexpr int kProbes = 4;
  using Probe = std::array<double, kProbes>;
  static constexpr ExprId kNotDone = ~ExprId{0};

  ExprId rewrite(ExprId id);
  ExprId normal_form(ExprId id);
  // Value of an original node at the probe states, and the size of its terms (the same
  // expression with every sum of absolute values): a cancellation leaves the first far below
  // the second.
  const Probe& value(ExprId id);
  const Probe& magnitude(ExprId id);
  Probe leaf_value(const Symbol& symbol) const;
  bool evaluates_to_zero(ExprId id, double tolerance);
  // Whether a sum is zero for every input: probed, then proven (or round-off when too deep).
  bool is_zero_sum(ExprId sum);
  // Removes the pairs of terms of a sum that cancel (a - b with a = b in another form).
  void drop_cancelling_pairs(std::vector<ExprId>& terms);

  ExprGraph& graph_;
  std::size_t original_size_;
  TrigPolynomials forms_;
  std::vector<ExprId> done_;
  std::vector<Probe> value_, magnitude_;
  std::vector<bool> value_done_, magnitude_done_;
  int exact_zeros_ = 0;
  int numeric_zeros_ = 0;
};

}  // namespace modelgen::gen
