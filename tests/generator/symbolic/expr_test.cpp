// The expression DAG's construction rules: hash-consing up to operand order, constant folding,
// neutral and absorbing elements, like-term collection (the cancellations the Newton-Euler
// derivation relies on), share() as an atom, numeric evaluation against a direct double
// computation of random formulas, node ids that depend on the input only, and operand order
// that does not depend on the order in which nodes were created.

#include "generator/symbolic/expr.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace modelgen::gen {
namespace {

Symbol input(std::string name) { return Symbol{std::move(name), SymbolKind::kInput, ""}; }

class ExprTest : public testing::Test {
 protected:
  ExprGraph g;
  const ExprId a = g.symbol(input("p[0]"));
  const ExprId b = g.symbol(input("p[1]"));
  const ExprId c = g.symbol(input("p[2]"));
  const ExprId d = g.symbol(input("p[3]"));
};

TEST_F(ExprTest, ZeroAndOneAreConstants) {
  EXPECT_TRUE(g.is_constant(g.zero()));
  EXPECT_TRUE(g.is_constant(g.one()));
  EXPECT_EQ(g.constant_value(g.zero()), 0.0);
  EXPECT_EQ(g.constant_value(g.one()), 1.0);
  EXPECT_TRUE(g.is_zero(g.zero()));
  EXPECT_FALSE(g.is_zero(g.one()));
  EXPECT_EQ(g.constant(0.0), g.zero());
  EXPECT_EQ(g.constant(1.0), g.one());
}

TEST_F(ExprTest, SymbolsAreLeavesNamedOnce) {
  EXPECT_EQ(g.symbol(input("p[0]")), a);
  EXPECT_NE(a, b);
  EXPECT_EQ(g.node(a).op, Op::kSymbol);
  EXPECT_EQ(g.symbols()[g.node(a).symbol].name, "p[0]");
  const ExprId s1 = g.symbol(Symbol{"s1", SymbolKind::kSin, "q[0]"});
  EXPECT_EQ(g.symbols()[g.node(s1).symbol].kind, SymbolKind::kSin);
  EXPECT_EQ(g.symbols()[g.node(s1).symbol].input, "q[0]");
  EXPECT_EQ(g.symbol(Symbol{"s1", SymbolKind::kSin, "q[0]"}), s1);
}

TEST_F(ExprTest, SameExpressionTwiceIsTheSameNode) {
  const ExprId first = g.add(g.mul(a, b), g.mul(c, d));
  const std::size_t size = g.size();
  const ExprId second = g.add(g.mul(a, b), g.mul(c, d));
  EXPECT_EQ(first, second);
  EXPECT_EQ(g.size(), size) << "rebuilding an existing expression must create no node";
  EXPECT_EQ(g.constant(0.225), g.constant(0.225));
}

TEST_F(ExprTest, CommutativeOperandsInEitherOrder) {
  EXPECT_EQ(g.add(a, b), g.add(b, a));
  EXPECT_EQ(g.mul(a, b), g.mul(b, a));
  EXPECT_EQ(g.add(g.mul(a, b), c), g.add(c, g.mul(b, a)));
  EXPECT_EQ(g.mul(g.add(a, b), c), g.mul(c, g.add(b, a)));
  EXPECT_EQ(g.add(std::vector<ExprId>{c, a, d, b}), g.add(std::vector<ExprId>{b, d, a, c}));
  EXPECT_EQ(g.mul(std::vector<ExprId>{c, a, d, b}), g.mul(std::vector<ExprId>{d, b, c, a}));
}

TEST_F(ExprTest, AssociativeSumsAndProductsFlatten) {
  EXPECT_EQ(g.add(a, g.add(b, c)), g.add(g.add(a, b), c));
  EXPECT_EQ(g.mul(a, g.mul(b, c)), g.mul(g.mul(a, b), c));
  const ExprId sum = g.add(a, g.add(b, c));
  EXPECT_EQ(g.node(sum).op, Op::kAdd);
  EXPECT_EQ(g.node(sum).args.size(), 3u);
  const ExprId product = g.mul(g.mul(a, b), c);
  EXPECT_EQ(g.node(product).op, Op::kMul);
  EXPECT_EQ(g.node(product).args.size(), 3u);
}

TEST_F(ExprTest, ConstantsFold) {
  const ExprId six = g.mul(g.constant(2), g.constant(3));
  ASSERT_TRUE(g.is_constant(six));
  EXPECT_EQ(g.constant_value(six), 6.0);
  EXPECT_EQ(six, g.constant(6));
  EXPECT_EQ(g.add(g.constant(2), g.constant(3)), g.constant(5));
  EXPECT_EQ(g.sub(g.constant(2), g.constant(3)), g.constant(-1));
  EXPECT_EQ(g.neg(g.constant(2.5)), g.constant(-2.5));
  // Constants inside products multiply into one coefficient: 2 * (3 * a) == 6 * a.
  EXPECT_EQ(g.mul(g.constant(2), g.mul(g.constant(3), a)), g.mul(g.constant(6), a));
  EXPECT_EQ(g.mul(std::vector<ExprId>{g.constant(2), a, g.constant(0.5)}), a);
}

TEST_F(ExprTest, NeutralAndAbsorbingElements) {
  EXPECT_EQ(g.mul(a, g.zero()), g.zero());
  EXPECT_EQ(g.mul(g.zero(), g.add(a, b)), g.zero());
  EXPECT_EQ(g.mul(a, g.one()), a);
  EXPECT_EQ(g.mul(g.one(), a), a);
  EXPECT_EQ(g.add(a, g.zero()), a);
  EXPECT_EQ(g.add(g.zero(), a), a);
  EXPECT_EQ(g.sub(a, g.zero()), a);
  EXPECT_EQ(g.neg(g.neg(a)), a);
  EXPECT_EQ(g.add(std::vector<ExprId>{}), g.zero());
  EXPECT_EQ(g.mul(std::vector<ExprId>{}), g.one());
}

TEST_F(ExprTest, LikeTermsCollect) {
  EXPECT_EQ(g.sub(a, a), g.zero());
  EXPECT_EQ(g.sub(g.mul(a, b), g.mul(b, a)), g.zero());
  EXPECT_EQ(g.add(a, a), g.mul(g.constant(2), a));
  EXPECT_EQ(g.add(g.mul(g.constant(3), g.mul(a, b)), g.neg(g.mul(b, a))),
            g.mul(g.constant(2), g.mul(a, b)));
  // Terms cancel inside a longer sum and the rest survives: (a + b + c) - (a + c) == b.
  EXPECT_EQ(g.sub(g.add(std::vector<ExprId>{a, b, c}), g.add(a, c)), b);
}

TEST_F(ExprTest, RodriguesCancellation) {
  // c + (1 - c) == 1 exactly: cos terms of a rotation must not survive as "c1 + 1 - c1".
  const ExprId cos1 = g.symbol(Symbol{"c1", SymbolKind::kCos, "q[0]"});
  EXPECT_EQ(g.add(cos1, g.sub(g.one(), cos1)), g.one());
  EXPECT_EQ(g.add(g.sub(g.one(), cos1), cos1), g.one());
  // With a constant factor, which distributes: 2 c + 2 (1 - c) == 2.
  const ExprId two = g.constant(2);
  EXPECT_EQ(g.add(g.mul(two, cos1), g.mul(two, g.sub(g.one(), cos1))), two);
}

TEST_F(ExprTest, ConstantDistributesOverASum) {
  const ExprId two = g.constant(2);
  EXPECT_EQ(g.sub(g.mul(two, g.add(a, b)), g.mul(two, a)), g.mul(two, b));
  EXPECT_EQ(g.mul(two, g.add(a, b)), g.add(g.mul(two, a), g.mul(two, b)));
  // -(a - b) == b - a.
  EXPECT_EQ(g.neg(g.sub(a, b)), g.sub(b, a));
  // The constant term of the sum is scaled too: 2 (a + 1) - 2 == 2 a.
  EXPECT_EQ(g.sub(g.mul(two, g.add(a, g.one())), two), g.mul(two, a));
  // A sum minus itself, the negation distributing over it: (a + b) - (a + b) == 0.
  EXPECT_EQ(g.sub(g.add(a, b), g.add(a, b)), g.zero());
}

TEST_F(ExprTest, SignsAndCoefficientsCombine) {
  EXPECT_EQ(g.mul(g.neg(a), g.neg(b)), g.mul(a, b));
  EXPECT_EQ(g.mul(g.neg(a), b), g.neg(g.mul(a, b)));
  EXPECT_EQ(g.add(g.mul(g.constant(2), a), g.mul(g.constant(3), a)), g.mul(g.constant(5), a));
  EXPECT_EQ(g.mul(g.mul(g.constant(2), a), g.mul(g.constant(0.5), b)), g.mul(a, b));
  // A product holding a sum cancels against its negation: x - x == 0 for x = (a + b) c.
  const ExprId x = g.mul(g.add(a, b), c);
  EXPECT_EQ(g.sub(x, x), g.zero());
  EXPECT_EQ(g.add(g.mul(g.constant(3), x), g.mul(g.constant(-3), x)), g.zero());
}

TEST_F(ExprTest, ArgumentsStayValidAsTheGraphGrowsPastItsReserve) {
  // Node::args points into the argument arena: growing the graph past the node vector's
  // reserve (65 536) and past an arena block must move no argument list, and hash-consing must
  // still find the early nodes.
  const ExprId sum = g.add({a, b, c});
  const ExprId product = g.mul(g.constant(3.0), g.mul(a, d));
  const std::span<const ExprId> sum_args = g.node(sum).args;
  const std::vector<ExprId> sum_before(sum_args.begin(), sum_args.end());
  const std::vector<ExprId> product_before(g.node(product).args.begin(), g.node(product).args.end());
  ExprId chain = a;
  for (int k = 0; k < 40000; ++k) chain = g.share(g.add({chain, g.mul(g.constant(1.0 + k), b), c}));
  ASSERT_GT(g.size(), std::size_t{1} << 17);
  EXPECT_TRUE(std::ranges::equal(sum_args, sum_before));  // the span taken before growing
  EXPECT_TRUE(std::ranges::equal(g.node(product).args, product_before));
  EXPECT_EQ(g.add({c, a, b}), sum);
  EXPECT_EQ(g.mul(d, g.mul(a, g.constant(3.0))), product);
}

TEST_F(ExprTest, ReciprocalsFold) {
  EXPECT_EQ(g.inv(g.constant(4)), g.constant(0.25));
  EXPECT_EQ(g.inv(g.constant(-0.5)), g.constant(-2));
  EXPECT_THROW(g.inv(g.zero()), std::logic_error);
  const ExprId inv_a = g.inv(a);
  ASSERT_EQ(g.node(inv_a).op, Op::kInv);
  EXPECT_EQ(std::vector<ExprId>(g.node(inv_a).args.begin(), g.node(inv_a).args.end()),
            std::vector<ExprId>{a});
  EXPECT_EQ(g.inv(a), inv_a);  // hash-consed
  EXPECT_EQ(g.inv(inv_a), a);
  // The constant coefficient leaves the reciprocal: 1 / (4 a b) = 0.25 (1 / (a b)).
  const ExprId ab = g.mul(a, b);
  EXPECT_EQ(g.inv(g.mul(g.constant(4), ab)), g.mul(g.constant(0.25), g.inv(ab)));
  EXPECT_EQ(g.inv(g.neg(a)), g.neg(inv_a));
  EXPECT_EQ(g.div(b, a), g.mul(b, inv_a));
  EXPECT_EQ(g.div(g.zero(), a), g.zero());
  // A reciprocal is an atom to sums and products: like terms collect over it.
  EXPECT_EQ(g.add(g.mul(g.constant(2), inv_a), inv_a), g.mul(g.constant(3), inv_a));
  // Values: 1 / (a + b) and b / (2 a) at a = 0.5, b = 3.
  const ExprId sum_inverse = g.inv(g.add(a, b));
  const ExprId quotient = g.div(b, g.mul(g.constant(2), a));
  const std::vector<double> v = g.evaluate([](const Symbol& s) {
    return s.name == "p[0]" ? 0.5 : (s.name == "p[1]" ? 3.0 : 0.0);
  });
  EXPECT_DOUBLE_EQ(v[sum_inverse], 1.0 / 3.5);
  EXPECT_DOUBLE_EQ(v[quotient], 3.0);
}

TEST_F(ExprTest, SignOfAProductDropsItsConstantCoefficient) {
  EXPECT_EQ(g.sign(g.mul(g.constant(3), a)), g.sign(a));
  EXPECT_EQ(g.sign(g.mul({g.constant(-0.25), a, b})), g.neg(g.sign(g.mul(a, b))));
  EXPECT_EQ(g.sign(g.constant(-2)), g.constant(-1));
  const std::vector<double> v =
      g.evaluate([](const Symbol& s) { return s.name == "p[0]" ? -1.5 : 2.0; });
  EXPECT_EQ(v[g.sign(g.mul({g.constant(-0.25), a, b}))], 1.0);  // -0.25 * -1.5 * 2 > 0
}

TEST_F(ExprTest, NegativeZeroIsZero) {
  EXPECT_EQ(g.constant(-0.0), g.zero());
  EXPECT_FALSE(std::signbit(g.constant_value(g.constant(-0.0))));
  EXPECT_EQ(g.mul(g.constant(-1), g.zero()), g.zero());
  EXPECT_EQ(g.neg(g.zero()), g.zero());
  EXPECT_EQ(g.add(g.constant(-0.0), a), a);
}

TEST_F(ExprTest, NonFiniteConstantIsRejected) {
  EXPECT_THROW(g.constant(INFINITY), std::logic_error);
  EXPECT_THROW(g.constant(NAN), std::logic_error);
}

TEST_F(ExprTest, ShareKeepsItsArgumentWhole) {
  const ExprId shared = g.share(g.add(a, b));
  EXPECT_EQ(g.node(shared).op, Op::kShare);
  const ExprId sum = g.add(shared, c);
  ASSERT_EQ(g.node(sum).op, Op::kAdd);
  EXPECT_EQ(g.node(sum).args.size(), 2u);
  const ExprId product = g.mul(g.share(g.mul(a, b)), c);
  ASSERT_EQ(g.node(product).op, Op::kMul);
  EXPECT_EQ(g.node(product).args.size(), 2u);
  // A constant factor does not distribute into a shared sum.
  const ExprId scaled = g.mul(g.constant(2), shared);
  ASSERT_EQ(g.node(scaled).op, Op::kMul);
  EXPECT_EQ(g.node(scaled).args.size(), 2u);
  // But the shared node itself is hash-consed: sharing the same sum twice gives one node.
  EXPECT_EQ(g.share(g.add(b, a)), shared);
  EXPECT_EQ(g.share(shared), shared);
  // Like terms over shared atoms still collect.
  EXPECT_EQ(g.sub(g.add(shared, c), shared), c);
}

TEST_F(ExprTest, ShareOfALeafIsTheLeaf) {
  EXPECT_EQ(g.share(a), a);
  EXPECT_EQ(g.share(g.constant(0.5)), g.constant(0.5));
  EXPECT_EQ(g.share(g.zero()), g.zero());
  const ExprId three_a = g.mul(g.constant(3), a);
  EXPECT_EQ(g.share(three_a), three_a);
}

// A random formula kept twice: as DAG nodes and as a list of operations the test evaluates
// directly in double arithmetic, in the order it was written.
struct Formula {
  enum Kind { kLeaf, kAdd, kSub, kMul, kNeg, kShare, kConstant };
  Kind kind;
  int lhs = -1, rhs = -1;  // indices into the formula list
  double constant = 0;
  int leaf = -1;
};

class RandomFormulas {
 public:
  RandomFormulas(ExprGraph& graph, std::uint64_t seed, int leaves) : g_(graph), engine_(seed) {
    for (int i = 0; i < leaves; ++i) {
      formulas_.push_back({Formula::kLeaf, -1, -1, 0, i});
      ids_.push_back(g_.symbol(input("x[" + std::to_string(i) + "]")));
    }
  }

  void grow(int count) {
    for (int i = 0; i < count; ++i) {
      const int kind = pick(7);
      const int lhs = pick(static_cast<int>(formulas_.size()));
      const int rhs = pick(static_cast<int>(formulas_.size()));
      Formula f{Formula::kLeaf, lhs, rhs, 0, -1};
      ExprId id = 0;
      switch (kind) {
        case 0:
          f.kind = Formula::kAdd;
          id = g_.add(ids_[lhs], ids_[rhs]);
          break;
        case 1:
          f.kind = Formula::kSub;
          id = g_.sub(ids_[lhs], ids_[rhs]);
          break;
        case 2:
          f.kind = Formula::kMul;
          id = g_.mul(ids_[lhs], ids_[rhs]);
          break;
        case 3:
          f.kind = Formula::kNeg;
          id = g_.neg(ids_[lhs]);
          break;
        case 4:
          f.kind = Formula::kShare;
          id = g_.share(ids_[lhs]);
          break;
        case 5: {
          // Small integers and halves, so products keep exact coefficients and cancel.
          f.kind = Formula::kConstant;
          f.constant = (pick(9) - 4) * 0.5;
          id = g_.constant(f.constant);
          break;
        }
        default: {
          f.kind = Formula::kAdd;  // a sum with a scaled copy: exercises like terms
          f.rhs = static_cast<int>(formulas_.size());
          formulas_.push_back({Formula::kMul, lhs, -2, 0, -1});  // lhs * 2, see value()
          ids_.push_back(g_.mul(g_.constant(2), ids_[lhs]));
          id = g_.add(ids_[rhs], ids_.back());
          f.lhs = rhs;
          break;
        }
      }
      formulas_.push_back(f);
      ids_.push_back(id);
    }
  }

  // Value and magnitude bound (the same formula on absolute values) of formula `i`.
  std::pair<double, double> value(int i, const std::vector<double>& leaves,
                                  std::vector<std::pair<double, double>>& memo,
                                  std::vector<bool>& done) const {
    if (done[i]) return memo[i];
    const Formula& f = formulas_[i];
    std::pair<double, double> r;
    auto arg = [&](int j) { return value(j, leaves, memo, done); };
    switch (f.kind) {
      case Formula::kLeaf:
        r = {leaves[f.leaf], std::fabs(leaves[f.leaf])};
        break;
      case Formula::kConstant:
        r = {f.constant, std::fabs(f.constant)};
        break;
      case Formula::kShare:
        r = arg(f.lhs);
        break;
      case Formula::kNeg:
        r = {-arg(f.lhs).first, arg(f.lhs).second};
        break;
      case Formula::kAdd:
        r = {arg(f.lhs).first + arg(f.rhs).first, arg(f.lhs).second + arg(f.rhs).second};
        break;
      case Formula::kSub:
        r = {arg(f.lhs).first - arg(f.rhs).first, arg(f.lhs).second + arg(f.rhs).second};
        break;
      case Formula::kMul:
        if (f.rhs == -2) {
          r = {2 * arg(f.lhs).first, 2 * arg(f.lhs).second};
        } else {
          r = {arg(f.lhs).first * arg(f.rhs).first, arg(f.lhs).second * arg(f.rhs).second};
        }
        break;
    }
    memo[i] = r;
    done[i] = true;
    return r;
  }

  std::size_t size() const { return formulas_.size(); }
  ExprId id(std::size_t i) const { return ids_[i]; }

 private:
  int pick(int n) { return static_cast<int>(engine_() % static_cast<std::uint64_t>(n)); }

  ExprGraph& g_;
  std::mt19937_64 engine_;
  std::vector<Formula> formulas_;
  std::vector<ExprId> ids_;
};

TEST(ExprEvaluate, RandomFormulasMatchDirectDoubleComputation) {
  constexpr int kLeaves = 4;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    ExprGraph g;
    RandomFormulas formulas(g, seed, kLeaves);
    formulas.grow(200);
    // The formulas must exercise every kind of node, not collapse to constants.
    int counts[5] = {};
    std::size_t widest = 0;
    for (ExprId id = 0; id < g.size(); ++id) {
      ++counts[static_cast<int>(g.node(id).op)];
      widest = std::max(widest, g.node(id).args.size());
    }
    ASSERT_GT(counts[static_cast<int>(Op::kAdd)], 20) << "seed " << seed;
    ASSERT_GT(counts[static_cast<int>(Op::kMul)], 20) << "seed " << seed;
    ASSERT_GT(counts[static_cast<int>(Op::kShare)], 5) << "seed " << seed;
    ASSERT_GT(widest, 3u) << "seed " << seed;
    std::mt19937_64 engine(seed * 1000);
    std::uniform_real_distribution<double> uniform(-1.5, 1.5);
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> leaves(kLeaves);
      for (double& x : leaves) x = uniform(engine);
      const std::vector<double> values = g.evaluate([&](const Symbol& s) {
        const int index = std::stoi(s.name.substr(2));
        return leaves[index];
      });
      ASSERT_EQ(values.size(), g.size());
      std::vector<std::pair<double, double>> memo(formulas.size());
      std::vector<bool> done(formulas.size(), false);
      for (std::size_t i = 0; i < formulas.size(); ++i) {
        const auto [expected, magnitude] = formulas.value(static_cast<int>(i), leaves, memo, done);
        ASSERT_NEAR(values[formulas.id(i)], expected, 1e-12 * std::max(magnitude, 1.0))
            << "seed " << seed << ", formula " << i;
      }
    }
  }
}

TEST(ExprEvaluate, LeafKindsAreGivenToTheCallback) {
  ExprGraph g;
  const ExprId q = g.symbol(input("q[0]"));
  const ExprId s = g.symbol(Symbol{"s1", SymbolKind::kSin, "q[0]"});
  const ExprId e = g.add(g.mul(g.constant(3), s), g.neg(q));
  const double q0 = 0.7;
  const std::vector<double> values = g.evaluate(
      [&](const Symbol& symbol) { return symbol.kind == SymbolKind::kSin ? std::sin(q0) : q0; });
  EXPECT_DOUBLE_EQ(values[e], 3 * std::sin(q0) - q0);
  EXPECT_EQ(values[g.zero()], 0.0);
  EXPECT_EQ(values[g.one()], 1.0);
}

TEST(ExprDeterminism, SameSequenceGivesSameIdsInSeparateGraphs) {
  ExprGraph first, second;
  RandomFormulas a(first, 99, 5), b(second, 99, 5);
  a.grow(500);
  b.grow(500);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.id(i), b.id(i)) << "formula " << i;
  }
  for (ExprId id = 0; id < first.size(); ++id) {
    const Node& x = first.node(id);
    const Node& y = second.node(id);
    ASSERT_EQ(x.op, y.op) << id;
    ASSERT_TRUE(std::ranges::equal(x.args, y.args)) << id;
    ASSERT_EQ(x.symbol, y.symbol) << id;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(x.value), std::bit_cast<std::uint64_t>(y.value)) << id;
  }
}

// Whether node x of graph gx and node y of graph gy are the same expression written the same
// way: operation, constant, symbol name and arguments in their stored order.
bool same_structure(const ExprGraph& gx, ExprId x, const ExprGraph& gy, ExprId y,
                    std::set<std::pair<ExprId, ExprId>>& known) {
  if (known.count({x, y})) return true;
  const Node& a = gx.node(x);
  const Node& b = gy.node(y);
  if (a.op != b.op || a.args.size() != b.args.size()) return false;
  if (a.op == Op::kConstant && a.value != b.value) return false;
  if (a.op == Op::kSymbol && gx.symbols()[a.symbol].name != gy.symbols()[b.symbol].name) {
    return false;
  }
  for (std::size_t k = 0; k < a.args.size(); ++k) {
    if (!same_structure(gx, a.args[k], gy, b.args[k], known)) return false;
  }
  known.insert({x, y});
  return true;
}

// A compiler may evaluate the arguments of add(mul(a, b), mul(c, d)) in either order, so node
// ids differ between builds of modelgen; the generated code must not (issue 15).
TEST(ExprDeterminism, OperandOrderDoesNotDependOnCreationOrder) {
  ExprGraph first, second;
  // The second graph meets the leaves and many products and sums first, in reverse order.
  std::vector<ExprId> leaves;
  for (int i = 4; i >= 0; --i) {
    leaves.push_back(second.symbol(input("x[" + std::to_string(i) + "]")));
  }
  for (std::size_t i = leaves.size(); i-- > 0;) {
    for (std::size_t j = leaves.size(); j-- > 0;) {
      const ExprId product = second.mul(leaves[i], leaves[j]);
      second.add(product, leaves[j]);
      second.sub(leaves[i], product);
    }
  }
  RandomFormulas a(first, 77, 5), b(second, 77, 5);
  a.grow(400);
  b.grow(400);
  std::set<std::pair<ExprId, ExprId>> known;
  std::size_t differing_ids = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(same_structure(first, a.id(i), second, b.id(i), known)) << "formula " << i;
    differing_ids += a.id(i) != b.id(i);
  }
  EXPECT_GT(differing_ids, 100u) << "the two graphs were to create their nodes in other orders";
}

TEST(ExprDeterminism, CanonicalFormInvariantsHold) {
  // The invariants expr.hpp promises for every node, over a large random graph.
  ExprGraph g;
  RandomFormulas formulas(g, 5, 4);
  formulas.grow(2000);
  for (ExprId id = 0; id < g.size(); ++id) {
    const Node& n = g.node(id);
    for (ExprId arg : n.args) {
      ASSERT_LT(arg, id) << "children are created before parents";
    }
    if (n.op == Op::kAdd) {
      ASSERT_GE(n.args.size(), 2u);
      for (std::size_t k = 0; k < n.args.size(); ++k) {
        ASSERT_NE(g.node(n.args[k]).op, Op::kAdd) << "nested sum in node " << id;
        ASSERT_NE(n.args[k], g.zero()) << "zero term in node " << id;
        if (k > 0) {
          ASSERT_TRUE(g.canonical_before(n.args[k - 1], n.args[k]))
              << "sum args not in canonical order in " << id;
        }
      }
    } else if (n.op == Op::kMul) {
      ASSERT_GE(n.args.size(), 2u);
      for (std::size_t k = 0; k < n.args.size(); ++k) {
        const Node& arg = g.node(n.args[k]);
        ASSERT_NE(arg.op, Op::kMul) << "nested product in node " << id;
        if (arg.op == Op::kConstant) {
          ASSERT_EQ(k, 0u) << "constant not first in product " << id;
          ASSERT_NE(arg.value, 0.0);
          ASSERT_NE(arg.value, 1.0);
        }
        if (k > 1 || (k == 1 && !g.is_constant(n.args[0]))) {
          ASSERT_FALSE(g.canonical_before(n.args[k], n.args[k - 1]))
              << "product args not in canonical order in " << id;
        }
      }
    } else if (n.op == Op::kShare) {
      ASSERT_EQ(n.args.size(), 1u);
      const Op inner = g.node(n.args[0]).op;
      ASSERT_NE(inner, Op::kConstant);
      ASSERT_NE(inner, Op::kSymbol);
      ASSERT_NE(inner, Op::kShare);
    }
  }
}

}  // namespace
}  // namespace modelgen::gen
