// The rewrites between the derivations and the emitter, on the expressions a generated function
// writes: exact cancellations removed, and every product and sum put in a sign-normal form so
// that an expression and its negation (or a constant multiple of a product) become one
// temporary. The derivations build the DAG with local rules only (expr.hpp); these rewrites
// need the whole expression.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "generator/symbolic/expr.hpp"
#include "generator/symbolic/trig_polynomial.hpp"

namespace modelgen::gen {

/// Rewrites nodes of one graph, memoized per node: functions emitted from one graph share the
/// work.
/// - Exact zeros: a sum whose value at four random states (consistent sines, cosines and
///   signs) is below 1e-9 of the size of its terms is expanded into its canonical polynomial
///   (TrigPolynomials); if that is zero, the sum is replaced by the constant 0, and every
///   expression using it is rebuilt (a product with it vanishes, a sum loses the term). Two
///   terms of a longer sum that cancel each other are tested and removed the same way. A sum
///   too deep to expand within the budget is replaced only if it is round-off at every probe
///   (below 1e-13 of its terms) and reads no sign (the probes never stop a joint): whatever it
///   could hide is below the 1e-12 the generated code is held to.
/// - Sign-normal form: a product c x1 ... xn (n >= 2) becomes c * share(x1 ... xn), and a sum
///   becomes share(s) or -share(-s), whichever makes the term with the canonically first base
///   (the term without its coefficient) positive. So -a b and a b, or a - b and b - a, are one
///   shared node, and the statement writer prints the other use as a negation folded into the
///   enclosing sum.
class OutputSimplifier {
 public:
  explicit OutputSimplifier(ExprGraph& graph);

  /// The rewritten form of `id`.
  ExprId operator()(ExprId id);
  /// The rewritten forms of `ids` (already rewritten) with the symbol nodes `leaves` replaced
  /// by 0: the entries of an array that the function writing it never writes.
  std::vector<ExprId> with_zero_leaves(const std::vector<ExprId>& ids,
                                       const std::vector<ExprId>& leaves);

  /// Sums proven identically zero, and sums over the expansion budget taken as zero because
  /// they were round-off at every probe.
  int exact_zeros() const { return exact_zeros_; }
  int numeric_zeros() const { return numeric_zeros_; }

 private:
  static constexpr int kProbes = 4;
  using Probe = std::array<double, kProbes>;
  static constexpr ExprId kNotDone = ~ExprId{0};

  ExprId rewrite(ExprId id);
  ExprId substitute_zero(ExprId id, const std::vector<bool>& is_zero_leaf,
                         std::unordered_map<ExprId, ExprId>& memo);
  ExprId normal_form(ExprId id);
  // Value of an original node at the probe states, and the size of its terms (the same
  // expression with every sum of absolute values): a cancellation leaves the first far below
  // the second. The reference is valid until the next call.
  const Probe& value(ExprId id);
  const Probe& magnitude(ExprId id);
  Probe leaf_value(const Symbol& symbol) const;
  bool evaluates_to_zero(ExprId id, double tolerance);
  // Whether a node depends on a sign (Op::kSign or a sign, positive or negative leaf).
  bool reads_a_sign(ExprId id);
  // Whether a sum is zero for every input: probed, then proven (or round-off when too deep).
  bool is_zero_sum(ExprId sum);
  // Removes the pairs of terms of a sum that cancel (a - b with a = b in another form).
  void drop_cancelling_pairs(std::vector<ExprId>& terms);

  ExprGraph& graph_;
  TrigPolynomials forms_;
  std::vector<ExprId> done_;
  // The probes of the nodes probed so far (a small part of the graph), and per node 0 or
  // 1 + the index of its probe.
  std::vector<Probe> values_, magnitudes_;
  std::vector<std::uint32_t> value_slot_, magnitude_slot_;
  std::vector<signed char> reads_sign_;  // per node: -1 not known yet, 0 or 1
  int exact_zeros_ = 0;
  int numeric_zeros_ = 0;
};

}  // namespace modelgen::gen
