// Construction rules of the expression DAG: every builder returns the canonical node for its
// value, so structurally equal subexpressions get the same id.

#include "generator/symbolic/expr.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace modelgen::gen {

bool ExprGraph::same_structure(const Node& a, const Node& b) {
  return a.op == b.op &&
         std::bit_cast<std::uint64_t>(a.value) == std::bit_cast<std::uint64_t>(b.value) &&
         a.symbol == b.symbol && std::ranges::equal(a.args, b.args);
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
  // Room for a six-axis model's graph (some 34 000 nodes for the TX-40) without reallocation:
  // each doubling copies the nodes and touches fresh pages, and the pages reserved but never
  // used cost nothing.
  nodes_.reserve(std::size_t{1} << 16);
  hashes_.reserve(std::size_t{1} << 16);
  grow_index();
  zero_ = constant(0.0);
  one_ = constant(1.0);
}

namespace {

// A list that lives on the stack up to N elements and moves to the heap beyond: the sums and
// products built here almost always have a few terms, and a heap buffer per call was a large
// part of generation time.
template <class T, std::size_t N>
class StackList {
 public:
  void push_back(const T& value) {
    if (size_ == N) heap_.assign(local_.begin(), local_.end());
    if (size_ >= N) {
      heap_.push_back(value);
    } else {
      local_[size_] = value;
    }
    ++size_;
  }
  T* begin() { return size_ > N ? heap_.data() : local_.data(); }
  T* end() { return begin() + size_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t k) { return begin()[k]; }
  std::span<T> span() { return {begin(), size_}; }

 private:
  std::array<T, N> local_;
  std::vector<T> heap_;
  std::size_t size_ = 0;
};

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

void ExprGraph::sort_canonical(std::span<ExprId> ids) const {
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
  node.args = store_args(node.args);
  const ExprId id = static_cast<ExprId>(nodes_.size());
  nodes_.push_back(node);
  hashes_.push_back(hash);
  if (2 * nodes_.size() > slots_.size()) {
    grow_index();  // re-inserts id too
  } else {
    slots_[slot] = id;
  }
  return id;
}

std::span<const ExprId> ExprGraph::store_args(std::span<const ExprId> args) {
  if (args.empty()) return {};
  if (arg_block_used_ + args.size() > arg_block_size_) {
    arg_block_size_ = std::max<std::size_t>(std::size_t{1} << 16, args.size());
    arg_blocks_.push_back(std::make_unique<ExprId[]>(arg_block_size_));
    arg_block_used_ = 0;
  }
  ExprId* out = arg_blocks_.back().get() + arg_block_used_;
  std::copy(args.begin(), args.end(), out);
  arg_block_used_ += args.size();
  return {out, args.size()};
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
  rest.args = n.args.subspan(1);  // still in canonical order
  return {coefficient, intern(std::move(rest))};
}

ExprId ExprGraph::add(ExprId a, ExprId b) {
  const ExprId terms[] = {a, b};
  return add_terms(terms);
}

ExprId ExprGraph::add(std::vector<ExprId> terms) { return add_terms(terms); }

ExprId ExprGraph::sub(ExprId a, ExprId b) { return add(a, neg(b)); }

ExprId ExprGraph::neg(ExprId a) { return mul(constant(-1.0), a); }

ExprId ExprGraph::add_terms(std::span<const ExprId> terms) {
  // Flatten nested sums, then collect like terms: coefficient per term without its constant,
  // the terms ordered by id to meet their like terms (the args are put in canonical order below).
  StackList<std::pair<ExprId, double>, 32> collected;
  double constant_sum = 0;
  auto collect = [&](ExprId t) {
    if (nodes_[t].op == Op::kConstant) {
      constant_sum += nodes_[t].value;
    } else {
      const auto [c, base] = split_coefficient(t);
      collected.push_back({base, c});
    }
  };
  for (ExprId t : terms) {
    const Node& n = nodes_[t];
    if (n.op == Op::kAdd) {
      for (ExprId a : n.args) collect(a);  // arena ids: valid while split_coefficient interns
    } else {
      collect(t);
    }
  }
  std::stable_sort(collected.begin(), collected.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  StackList<ExprId, 32> args;
  for (std::size_t k = 0; k < collected.size();) {
    const ExprId base = collected[k].first;
    double c = 0;
    for (; k < collected.size() && collected[k].first == base; ++k) c += collected[k].second;
    if (c == 0.0) continue;
    args.push_back(c == 1.0 ? base : mul(constant(c), base));
  }
  if (constant_sum != 0.0) args.push_back(constant(constant_sum));
  if (args.empty()) return zero_;
  if (args.size() == 1) return args[0];
  sort_canonical(args.span());
  Node node;
  node.op = Op::kAdd;
  node.args = args.span();
  return intern(node);
}

ExprId ExprGraph::mul(ExprId a, ExprId b) {
  const ExprId factors[] = {a, b};
  return mul_factors(factors);
}

ExprId ExprGraph::mul(std::vector<ExprId> factors) { return mul_factors(factors); }

ExprId ExprGraph::mul_factors(std::span<const ExprId> factors) {
  double coefficient = 1.0;
  // The coefficient's slot first, filled below if it is not 1.
  StackList<ExprId, 32> args;
  args.push_back(zero_);
  for (ExprId f : factors) {
    const Node& n = nodes_[f];
    if (n.op == Op::kConstant) {
      coefficient *= n.value;
    } else if (n.op == Op::kMul) {
      for (ExprId g : n.args) {
        if (nodes_[g].op == Op::kConstant) {
          coefficient *= nodes_[g].value;
        } else {
          args.push_back(g);
        }
      }
    } else {
      args.push_back(f);
    }
  }
  const std::span<ExprId> rest = args.span().subspan(1);
  if (coefficient == 0.0) return zero_;
  if (rest.empty()) return constant(coefficient);
  if (coefficient != 1.0 && rest.size() == 1 && nodes_[rest[0]].op == Op::kAdd) {
    // Distribute a constant over a sum so that like terms can meet: 2 (a + b) -> 2a + 2b.
    // The sum's arguments live in the arena, which mul() never moves.
    const std::span<const ExprId> sum_terms = nodes_[rest[0]].args;
    std::vector<ExprId> terms;
    terms.reserve(sum_terms.size());
    for (ExprId t : sum_terms) terms.push_back(mul(constant(coefficient), t));
    return add_terms(terms);
  }
  sort_canonical(rest);
  if (coefficient == 1.0 && rest.size() == 1) return rest[0];
  Node node;
  node.op = Op::kMul;
  if (coefficient != 1.0) {
    args[0] = constant(coefficient);
    node.args = args.span();
  } else {
    node.args = rest;
  }
  return intern(node);
}

ExprId ExprGraph::share(ExprId e) {
  const Node& n = nodes_[e];
  if (n.op == Op::kConstant || n.op == Op::kSymbol || n.op == Op::kShare) return e;
  if (n.op == Op::kMul && n.args.size() == 2 && nodes_[n.args[0]].op == Op::kConstant &&
      (nodes_[n.args[1]].op == Op::kSymbol || nodes_[n.args[1]].op == Op::kShare)) {
    return e;  // a constant multiple of an atom costs one multiplication where it is used
  }
  const ExprId arg[] = {e};
  Node node;
  node.op = Op::kShare;
  node.args = arg;
  return intern(node);
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
  const ExprId arg[] = {e};
  Node node;
  node.op = Op::kSign;
  node.args = arg;
  return intern(node);
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
  const ExprId arg[] = {e};
  Node node;
  node.op = Op::kInv;
  node.args = arg;
  return intern(node);
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
