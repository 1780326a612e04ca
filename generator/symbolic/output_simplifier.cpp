// Post-order rewrite of the original nodes: each node's arguments are rewritten first, the node
// rebuilt from them through ExprGraph's constructors (so a zero argument folds its parents),
// then put in sign-normal form.

#include "generator/symbolic/output_simplifier.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace modelgen::gen {

namespace {

// Pseudo-random value in +-[0.3, 2] for an input name and probe: a function of the name alone
// (FNV-1a, then splitmix64), so the generated code never depends on the order nodes are visited.
double probe_input(const std::string& name, int probe) {
  std::uint64_t h = 1469598103934665603ull;
  for (char ch : name) h = (h ^ static_cast<unsigned char>(ch)) * 1099511628211ull;
  h += 0x9e3779b97f4a7c15ull * static_cast<std::uint64_t>(probe + 1);
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
  h ^= h >> 31;
  const double unit = static_cast<double>(h >> 11) * 0x1.0p-53;  // [0, 1)
  const double magnitude = 0.3 + 1.7 * unit;
  return (h & 1) ? -magnitude : magnitude;
}

}  // namespace

OutputSimplifier::OutputSimplifier(ExprGraph& graph)
    : graph_(graph),
      forms_(graph),
      done_(graph.size(), kNotDone),
      value_slot_(graph.size(), 0),
      magnitude_slot_(graph.size(), 0) {}

ExprId OutputSimplifier::operator()(ExprId id) { return rewrite(id); }

ExprId OutputSimplifier::substitute_zero(ExprId id, const std::vector<bool>& is_zero_leaf,
                                         std::unordered_map<ExprId, ExprId>& memo) {
  if (const auto found = memo.find(id); found != memo.end()) return found->second;
  const Node n = graph_.node(id);  // a copy: rebuilding grows the graph
  ExprId result = id;
  if (n.op == Op::kSymbol) {
    if (id < is_zero_leaf.size() && is_zero_leaf[id]) result = graph_.zero();
  } else if (n.op != Op::kConstant) {
    std::vector<ExprId> args;
    bool changed = false;
    for (ExprId a : n.args) {
      args.push_back(substitute_zero(a, is_zero_leaf, memo));
      changed = changed || args.back() != a;
    }
    if (changed) {
      switch (n.op) {
        case Op::kAdd: result = graph_.add(std::move(args)); break;
        case Op::kMul: result = graph_.mul(std::move(args)); break;
        case Op::kShare: result = graph_.share(args[0]); break;
        case Op::kSign: result = graph_.sign(args[0]); break;
        case Op::kInv:
          if (graph_.is_zero(args[0])) {
            throw std::logic_error("OutputSimplifier: a divisor reads only zero entries");
          }
          result = graph_.inv(args[0]);
          break;
        default: break;
      }
    }
  }
  memo.emplace(id, result);
  return result;
}

std::vector<ExprId> OutputSimplifier::with_zero_leaves(const std::vector<ExprId>& ids,
                                                       const std::vector<ExprId>& leaves) {
  if (leaves.empty()) return ids;
  std::vector<bool> is_zero_leaf(graph_.size(), false);
  for (ExprId leaf : leaves) is_zero_leaf[leaf] = true;
  std::unordered_map<ExprId, ExprId> memo;
  std::vector<ExprId> result;
  for (ExprId id : ids) result.push_back(rewrite(substitute_zero(id, is_zero_leaf, memo)));
  return result;
}

OutputSimplifier::Probe OutputSimplifier::leaf_value(const Symbol& symbol) const {
  Probe out{};
  for (int k = 0; k < kProbes; ++k) {
    const double x = probe_input(symbol.kind == SymbolKind::kInput ? symbol.name : symbol.input, k);
    switch (symbol.kind) {
      case SymbolKind::kInput: out[k] = x; break;
      case SymbolKind::kSin: out[k] = std::sin(x); break;
      case SymbolKind::kCos: out[k] = std::cos(x); break;
      case SymbolKind::kSign: out[k] = x > 0 ? 1.0 : -1.0; break;  // probes are never 0
      case SymbolKind::kPositive: out[k] = x > 0 ? 1.0 : 0.0; break;
      case SymbolKind::kNegative: out[k] = x < 0 ? 1.0 : 0.0; break;
    }
  }
  return out;
}

const OutputSimplifier::Probe& OutputSimplifier::value(ExprId id) {
  if (id >= value_slot_.size()) value_slot_.resize(graph_.size(), 0);  // a node the rewrite made
  if (value_slot_[id] != 0) return values_[value_slot_[id] - 1];
  const Node n = graph_.node(id);  // a copy: nothing here grows the graph, but stay safe
  Probe out{};
  switch (n.op) {
    case Op::kConstant: out.fill(n.value); break;
    case Op::kSymbol: out = leaf_value(graph_.symbols()[n.symbol]); break;
    case Op::kAdd:
      out.fill(0.0);
      for (ExprId a : n.args) {
        const Probe& v = value(a);
        for (int k = 0; k < kProbes; ++k) out[k] += v[k];
      }
      break;
    case Op::kMul:
      out.fill(1.0);
      for (ExprId a : n.args) {
        const Probe& v = value(a);
        for (int k = 0; k < kProbes; ++k) out[k] *= v[k];
      }
      break;
    case Op::kShare: out = value(n.args[0]); break;
    case Op::kSign: {
      const Probe& v = value(n.args[0]);
      for (int k = 0; k < kProbes; ++k) out[k] = v[k] > 0 ? 1.0 : (v[k] < 0 ? -1.0 : 0.0);
      break;
    }
    case Op::kInv: {
      const Probe& v = value(n.args[0]);
      for (int k = 0; k < kProbes; ++k) out[k] = 1.0 / v[k];
      break;
    }
  }
  values_.push_back(out);
  value_slot_[id] = static_cast<std::uint32_t>(values_.size());
  return values_.back();
}

const OutputSimplifier::Probe& OutputSimplifier::magnitude(ExprId id) {
  if (id >= magnitude_slot_.size()) magnitude_slot_.resize(graph_.size(), 0);
  if (magnitude_slot_[id] != 0) return magnitudes_[magnitude_slot_[id] - 1];
  const Node n = graph_.node(id);
  Probe out{};
  switch (n.op) {
    case Op::kAdd:
      out.fill(0.0);
      for (ExprId a : n.args) {
        const Probe& m = magnitude(a);
        for (int k = 0; k < kProbes; ++k) out[k] += m[k];
      }
      break;
    case Op::kMul:
      out.fill(1.0);
      for (ExprId a : n.args) {
        const Probe& m = magnitude(a);
        for (int k = 0; k < kProbes; ++k) out[k] *= m[k];
      }
      break;
    case Op::kShare: out = magnitude(n.args[0]); break;
    default: {  // leaves, signs and reciprocals: their own size
      const Probe& v = value(id);
      for (int k = 0; k < kProbes; ++k) out[k] = std::abs(v[k]);
    }
  }
  magnitudes_.push_back(out);
  magnitude_slot_[id] = static_cast<std::uint32_t>(magnitudes_.size());
  return magnitudes_.back();
}

bool OutputSimplifier::evaluates_to_zero(ExprId id, double tolerance) {
  const Probe m = magnitude(id);  // copies: probing may grow the tables
  const Probe v = value(id);
  for (int k = 0; k < kProbes; ++k) {
    if (!(std::abs(v[k]) <= tolerance * m[k])) return false;
  }
  return true;
}

ExprId OutputSimplifier::rewrite(ExprId id) {
  if (id >= done_.size()) done_.resize(graph_.size(), kNotDone);  // a node made since
  if (done_[id] != kNotDone) return done_[id];
  const Node n = graph_.node(id);  // a copy: rebuilding grows the graph
  ExprId result = id;
  switch (n.op) {
    case Op::kConstant:
    case Op::kSymbol: break;
    case Op::kAdd: {
      std::vector<ExprId> terms;
      for (ExprId a : n.args) terms.push_back(rewrite(a));
      drop_cancelling_pairs(terms);
      const ExprId sum = graph_.add(std::move(terms));
      // Only a sum can cancel: a product is zero only through a zero factor. The rebuilt sum
      // is tested, as its terms may cancel only once theirs are rewritten.
      result = graph_.node(sum).op == Op::kAdd && is_zero_sum(sum) ? graph_.zero()
                                                                    : normal_form(sum);
      break;
    }
    case Op::kMul: {
      std::vector<ExprId> factors;
      for (ExprId a : n.args) factors.push_back(rewrite(a));
      result = normal_form(graph_.mul(std::move(factors)));
      break;
    }
    case Op::kShare: result = graph_.share(rewrite(n.args[0])); break;
    case Op::kSign: result = graph_.sign(rewrite(n.args[0])); break;
    case Op::kInv: {
      const ExprId divisor = rewrite(n.args[0]);
      if (graph_.is_zero(divisor)) {
        throw std::logic_error("OutputSimplifier: a divisor is identically zero");
      }
      result = graph_.inv(divisor);
      break;
    }
  }
  done_[id] = result;
  return result;
}

bool OutputSimplifier::reads_a_sign(ExprId id) {
  if (id >= reads_sign_.size()) reads_sign_.resize(graph_.size(), -1);
  if (reads_sign_[id] >= 0) return reads_sign_[id] == 1;
  const Node n = graph_.node(id);
  bool reads = n.op == Op::kSign;
  if (n.op == Op::kSymbol) {
    const SymbolKind kind = graph_.symbols()[n.symbol].kind;
    reads = kind == SymbolKind::kSign || kind == SymbolKind::kPositive ||
            kind == SymbolKind::kNegative;
  }
  for (std::size_t k = 0; k < n.args.size() && !reads; ++k) reads = reads_a_sign(n.args[k]);
  reads_sign_[id] = reads ? 1 : 0;
  return reads;
}

bool OutputSimplifier::is_zero_sum(ExprId sum) {
  if (!evaluates_to_zero(sum, 1e-9)) return false;
  const std::optional<bool> zero = forms_.is_zero(sum);
  if (zero.value_or(false)) {
    ++exact_zeros_;
    return true;
  }
  // Too deep to expand (the state Jacobians): round-off alone at every probe is taken as zero;
  // a term it could hide is below 1e-13 of the sum's terms, under the 1e-12 the generated code
  // is held to against the numeric reference.
  // Not for a sum that reads a sign: the probes never put a velocity at 0, where such a sum
  // (sign(x)^2 - 1) can be non-zero.
  if (!zero && !reads_a_sign(sum) && evaluates_to_zero(sum, 1e-13)) {
    ++numeric_zeros_;
    return true;
  }
  return false;
}

void OutputSimplifier::drop_cancelling_pairs(std::vector<ExprId>& terms) {
  if (terms.size() < 3) return;  // a sum of two that cancels is the whole sum
  std::vector<bool> dropped(terms.size(), false);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    for (std::size_t k = i + 1; k < terms.size() && !dropped[i]; ++k) {
      if (dropped[k]) continue;
      const Probe a = value(terms[i]);  // copies: probing may grow the tables
      const Probe b = value(terms[k]);
      bool opposite = true;
      for (int p = 0; p < kProbes && opposite; ++p) {
        opposite = std::abs(a[p] + b[p]) <= 1e-9 * (std::abs(a[p]) + std::abs(b[p]));
      }
      if (!opposite) continue;
      const ExprId pair = graph_.add(terms[i], terms[k]);
      if (graph_.is_zero(pair) || (graph_.node(pair).op == Op::kAdd && is_zero_sum(pair))) {
        dropped[i] = dropped[k] = true;
      }
    }
  }
  std::vector<ExprId> kept;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (!dropped[i]) kept.push_back(terms[i]);
  }
  terms = std::move(kept);
}

ExprId OutputSimplifier::normal_form(ExprId id) {
  const Node n = graph_.node(id);
  if (n.op == Op::kMul) {
    const bool has_coefficient = graph_.is_constant(n.args[0]);
    std::vector<ExprId> rest(n.args.begin() + (has_coefficient ? 1 : 0), n.args.end());
    if (rest.size() < 2) return id;  // c x: one multiplication wherever it is used
    const ExprId product = graph_.share(graph_.mul(std::move(rest)));
    return has_coefficient ? graph_.mul(n.args[0], product) : product;
  }
  if (n.op == Op::kAdd) {
    // The sign of the term whose base (the term without its constant coefficient) comes first
    // canonically: the same base in s and -s, so both choose one representative. Only the
    // sign: a magnitude taken out would be one more multiplication wherever the sum is a
    // factor (c * share(u) flattens into every product), and the statement writer already
    // prints terms with one literal factor once (0.035 * (a - b)).
    ExprId first_base = 0;
    double first = 0;
    for (ExprId term : n.args) {
      if (graph_.is_constant(term)) continue;
      const Node& t = graph_.node(term);
      const bool scaled = t.op == Op::kMul && graph_.is_constant(t.args[0]) && t.args.size() == 2;
      const ExprId base = scaled ? t.args[1] : term;
      const double coefficient = scaled ? graph_.constant_value(t.args[0]) : 1.0;
      if (first == 0 || graph_.canonical_before(base, first_base)) {
        first_base = base;
        first = coefficient;
      }
    }
    if (first > 0) return graph_.share(id);
    return graph_.neg(graph_.share(graph_.neg(id)));
  }
  return id;
}

}  // namespace modelgen::gen
