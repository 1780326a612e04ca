// Construction rules of the expression DAG: every builder returns the canonical node for its
// value, so structurally equal subexpressions get the same id.

#include "generator/symbolic/expr.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <stdexcept>

namespace modelgen::gen {

bool ExprGraph::same_structure(const Node& a, const Node& b) {
  return a.op == b.op &&
         std::bit_cast<std::uint64_t>(a.value) == std::bit_cast<std::uint64_t>(b.value) &&
         a.symbol == b.symbol && a.args == b.args;
}

std::uint64_t ExprGraph::structure_hash(const Node& node) {
  std::uint64_t h = 1469598103934665603ull ^ static_cast<std::uint64_t>(node.op);
  auto mix = [&h](std::uint64_t v) {
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  };
  mix(std::bit_cast<std::uint64_t>(node.value));
  mix(node.symbol);
  for (ExprId a : node.args) mix(a);
  // Finalizer (splitmix64): the table takes the low bits.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

ExprGraph::ExprGraph() {
  grow_index();
  zero_ = constant(0.0);
  one_ = constant(1.0);
}

namespace {

int kind_rank(Op op) {
  if (op == Op::kConstant) return 0;
  if (op == Op::kSymbol) return 1;
  return 2;
}

}  // namespace

bool ExprGraph::canonical_before(ExprId a, ExprId b) const {
  if (a == b) return false;
  const Node& x = nodes_[a];
  const Node& y = nodes_[b];
  if (kind_rank(x.op) != kind_rank(y.op)) return kind_rank(x.op) < kind_rank(y.op);
  if (x.op == Op::kConstant) return x.value < y.value;
  if (x.op == Op::kSymbol) return symbols_[x.symbol].name < symbols_[y.symbol].name;
  if (x.height != y.height) return x.height < y.height;
  if (x.op != y.op) return x.op < y.op;
  const std::size_t common = std::min(x.args.size(), y.args.size());
  for (std::size_t k = 0; k < common; ++k) {
    if (x.args[k] != y.args[k]) return canonical_before(x.args[k], y.args[k]);
  }
  return x.args.size() < y.args.size();
}

void ExprGraph::sort_canonical(std::vector<ExprId>& ids) const {
  std::sort(ids.begin(), ids.end(),
            [this](ExprId a, ExprId b) { return canonical_before(a, b); });
}

ExprId ExprGraph::intern(Node node) {
  const std::uint64_t hash = structure_hash(node);
  std::size_t mask = slots_.size() - 1;
  std::size_t slot = hash & mask;
  for (; slots_[slot] != kNoNode; slot = (slot + 1) & mask) {
    const ExprId existing = slots_[slot];
    if (hashes_[existing] == hash && same_structure(nodes_[existing], node)) return existing;
  }
  node.height = 0;
  for (ExprId a : node.args) node.height = std::max(node.height, nodes_[a].height + 1);
  const ExprId id = static_cast<ExprId>(nodes_.size());
  nodes_.push_back(std::move(node));
  hashes_.push_back(hash);
  if (2 * nodes_.size() > slots_.size()) {
    grow_index();  // re-inserts id too
  } else {
    slots_[slot] = id;
  }
  return id;
}

void ExprGraph::grow_index() {
  slots_.assign(std::max<std::size_t>(1024, 2 * slots_.size()), kNoNode);
  const std::size_t mask = slots_.size() - 1;
  for (ExprId id = 0; id < nodes_.size(); ++id) {
    std::size_t slot = hashes_[id] & mask;
    while (slots_[slot] != kNoNode) slot = (slot + 1) & mask;
    slots_[slot] = id;
  }
}

ExprId ExprGraph::constant(double value) {
  if (!std::isfinite(value)) throw std::logic_error("ExprGraph: non-finite constant");
  Node node;
  node.op = Op::kConstant;
  node.value = value == 0.0 ? 0.0 : value;  // one zero: -0 folds into +0
  return intern(std::move(node));
}

ExprId ExprGraph::symbol(const Symbol& symbol) {
  auto found = symbol_index_.find(symbol.name);
  if (found != symbol_index_.end()) return found->second;
  Node node;
  node.op = Op::kSymbol;
  node.symbol = static_cast<std::uint32_t>(symbols_.size());
  symbols_.push_back(symbol);
  const ExprId id = intern(std::move(node));
  symbol_index_.emplace(symbol.name, id);
  return id;
}

std::pair<double, ExprId> ExprGraph::split_coefficient(ExprId id) {
  const Node& n = nodes_[id];
  if (n.op != Op::kMul || nodes_[n.args[0]].op != Op::kConstant) return {1.0, id};
  const double coefficient = nodes_[n.args[0]].value;
  if (n.args.size() == 2) return {coefficient, n.args[1]};
  Node rest;
  rest.op = Op::kMul;
  rest.args.assign(n.args.begin() + 1, n.args.end());  // still in canonical order
  return {coefficient, intern(std::move(rest))};
}

ExprId ExprGraph::add(ExprId a, ExprId b) { return add(std::vector<ExprId>{a, b}); }

ExprId ExprGraph::sub(ExprId a, ExprId b) { return add(a, neg(b)); }

ExprId ExprGraph::neg(ExprId a) { return mul(constant(-1.0), a); }

ExprId ExprGraph::add(std::vector<ExprId> terms) {
  // Flatten nested sums, then collect like terms: coefficient per term without its constant.
  std::vector<ExprId> flat;
  for (ExprId t : terms) {
    const Node& n = nodes_[t];
    if (n.op == Op::kAdd) {
      flat.insert(flat.end(), n.args.begin(), n.args.end());
    } else {
      flat.push_back(t);
    }
  }
  double constant_sum = 0;
  std::map<ExprId, double> coefficients;  // the args are put in canonical order below
  for (ExprId t : flat) {
    if (nodes_[t].op == Op::kConstant) {
      constant_sum += nodes_[t].value;
      continue;
    }
    const auto [c, base] = split_coefficient(t);
    coefficients[base] += c;
  }
  std::vector<ExprId> args;
  for (const auto& [base, c] : coefficients) {
    if (c == 0.0) continue;
    args.push_back(c == 1.0 ? base : mul(constant(c), base));
  }
  if (constant_sum != 0.0) args.push_back(constant(constant_sum));
  if (args.empty()) return zero_;
  if (args.size() == 1) return args[0];
  sort_canonical(args);
  Node node;
  node.op = Op::kAdd;
  node.args = std::move(args);
  return intern(std::move(node));
}

ExprId ExprGraph::mul(ExprId a, ExprId b) { return mul(std::vector<ExprId>{a, b}); }

ExprId ExprGraph::mul(std::vector<ExprId> factors) {
  double coefficient = 1.0;
  std::vector<ExprId> rest;
  for (ExprId f : factors) {
    const Node& n = nodes_[f];
    if (n.op == Op::kConstant) {
      coefficient *= n.value;
    } else if (n.op == Op::kMul) {
      for (ExprId g : n.args) {
        if (nodes_[g].op == Op::kConstant) {
          coefficient *= nodes_[g].value;
        } else {
          rest.push_back(g);
        }
      }
    } else {
      rest.push_back(f);
    }
  }
  if (coefficient == 0.0) return zero_;
  if (rest.empty()) return constant(coefficient);
  if (coefficient != 1.0 && rest.size() == 1 && nodes_[rest[0]].op == Op::kAdd) {
    // Distribute a constant over a sum so that like terms can meet: 2 (a + b) -> 2a + 2b.
    // A copy: mul() adds nodes, which may move nodes_ and the argument list with it.
    const std::vector<ExprId> sum_terms = nodes_[rest[0]].args;
    std::vector<ExprId> terms;
    for (ExprId t : sum_terms) terms.push_back(mul(constant(coefficient), t));
    return add(std::move(terms));
  }
  sort_canonical(rest);
  if (coefficient == 1.0 && rest.size() == 1) return rest[0];
  Node node;
  node.op = Op::kMul;
  if (coefficient != 1.0) node.args.push_back(constant(coefficient));
  node.args.insert(node.args.end(), rest.begin(), rest.end());
  return intern(std::move(node));
}

ExprId ExprGraph::share(ExprId e) {
  const Node& n = nodes_[e];
  if (n.op == Op::kConstant || n.op == Op::kSymbol || n.op == Op::kShare) return e;
  if (n.op == Op::kMul && n.args.size() == 2 && nodes_[n.args[0]].op == Op::kConstant &&
      (nodes_[n.args[1]].op == Op::kSymbol || nodes_[n.args[1]].op == Op::kShare)) {
    return e;  // a constant multiple of an atom costs one multiplication where it is used
  }
  Node node;
  node.op = Op::kShare;
  node.args = {e};
  return intern(std::move(node));
}

ExprId ExprGraph::sign(ExprId e) {
  if (nodes_[e].op == Op::kConstant) {
    const double v = nodes_[e].value;
    return constant(v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0));
  }
  if (const auto [c, rest] = split_coefficient(e); c != 1.0) {
    // The coefficient of a product is non-zero (mul folds zero away): only its sign matters.
    return c > 0 ? sign(rest) : neg(sign(rest));
  }
  Node node;
  node.op = Op::kSign;
  node.args = {e};
  return intern(std::move(node));
}

ExprId ExprGraph::inv(ExprId e) {
  const Node& n = nodes_[e];
  if (n.op == Op::kConstant) {
    if (n.value == 0.0) throw std::logic_error("ExprGraph: reciprocal of the constant 0");
    return constant(1.0 / n.value);
  }
  if (n.op == Op::kInv) return n.args[0];
  if (const auto [c, rest] = split_coefficient(e); c != 1.0) {
    return mul(constant(1.0 / c), inv(rest));
  }
  Node node;
  node.op = Op::kInv;
  node.args = {e};
  return intern(std::move(node));
}

ExprId ExprGraph::div(ExprId a, ExprId b) { return mul(a, inv(b)); }

std::vector<double> ExprGraph::evaluate(const std::function<double(const Symbol&)>& leaf) const {
  std::vector<double> value(nodes_.size());
  // Children are interned before their parents, so one pass in id order suffices.
  for (ExprId i = 0; i < nodes_.size(); ++i) {
    const Node& n = nodes_[i];
    switch (n.op) {
      case Op::kConstant: value[i] = n.value; break;
      case Op::kSymbol: value[i] = leaf(symbols_[n.symbol]); break;
      case Op::kAdd: {
        double s = 0;
        for (ExprId a : n.args) s += value[a];
        value[i] = s;
        break;
      }
      case Op::kMul: {
        double p = 1;
        for (ExprId a : n.args) p *= value[a];
        value[i] = p;
        break;
      }
      case Op::kShare: value[i] = value[n.args[0]]; break;
      case Op::kSign: {
        const double x = value[n.args[0]];
        value[i] = x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
        break;
      }
      case Op::kInv: value[i] = 1.0 / value[n.args[0]]; break;
    }
  }
  return value;
}

}  // namespace modelgen::gen
