// The canonical trigonometric polynomial form and the output rewrites: exact cancellations the
// DAG's local rules miss are proven zero (and nothing else is), rewritten expressions keep their
// value (evaluated here at random states, and on every shipped robot's Newton-Euler regressor
// and inverse dynamics), and negated or scaled copies of one sum or product become one node.

#include "generator/symbolic/output_simplifier.hpp"

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generator/dynamics/newton_euler.hpp"
#include "generator/symbolic/trig_polynomial.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/symbol_values.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

struct Leaves {
  ExprGraph g;
  ExprId s1, c1, s2, c2, a, b, c;
  Leaves() {
    s1 = g.symbol({"s1", SymbolKind::kSin, "q[0]"});
    c1 = g.symbol({"c1", SymbolKind::kCos, "q[0]"});
    s2 = g.symbol({"s2", SymbolKind::kSin, "q[1]"});
    c2 = g.symbol({"c2", SymbolKind::kCos, "q[1]"});
    a = g.symbol({"dq[0]", SymbolKind::kInput, ""});
    b = g.symbol({"dq[1]", SymbolKind::kInput, ""});
    c = g.symbol({"ddq[0]", SymbolKind::kInput, ""});
  }
  // Values at a random state, derived leaves consistent with their input.
  std::vector<double> values(std::mt19937_64& random) const {
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    std::map<std::string, double> in{{"q[0]", u(random)}, {"q[1]", u(random)},
                                     {"dq[0]", u(random)}, {"dq[1]", u(random)},
                                     {"ddq[0]", u(random)}};
    return g.evaluate([&](const Symbol& s) {
      if (s.kind == SymbolKind::kSin) return std::sin(in.at(s.input));
      if (s.kind == SymbolKind::kCos) return std::cos(in.at(s.input));
      return in.at(s.name);
    });
  }
};

TEST(TrigPolynomials, ProvesThePythagoreanIdentityAndSharedCancellations) {
  Leaves l;
  ExprGraph& g = l.g;
  const ExprId pythagoras = g.add({g.mul(l.s1, l.s1), g.mul(l.c1, l.c1), g.constant(-1.0)});
  // c2 (dq1 (-dq0 s2)) - s2 (-dq1 (c2 dq0)) with the inner products shared, as Newton-Euler
  // builds them: the DAG keeps it, the polynomial form cancels it.
  const ExprId t1 = g.share(g.mul(l.c2, l.a));
  const ExprId t3 = g.share(g.neg(g.mul(l.a, l.s2)));
  const ExprId shared = g.sub(g.mul(l.c2, g.share(g.mul(l.b, t3))),
                              g.mul(l.s2, g.share(g.neg(g.mul(l.b, t1)))));
  ASSERT_FALSE(g.is_zero(shared));
  // (c1 c2 - s1 s2)^2 + (s1 c2 + c1 s2)^2 = 1: cos^2 + sin^2 of the sum angle.
  const ExprId cos12 = g.share(g.sub(g.mul(l.c1, l.c2), g.mul(l.s1, l.s2)));
  const ExprId sin12 = g.share(g.add(g.mul(l.s1, l.c2), g.mul(l.c1, l.s2)));
  const ExprId sum_angle = g.add({g.mul(cos12, cos12), g.mul(sin12, sin12), g.constant(-1.0)});
  TrigPolynomials forms(g);
  EXPECT_EQ(forms.is_zero(pythagoras), std::optional<bool>(true));
  EXPECT_EQ(forms.is_zero(shared), std::optional<bool>(true));
  EXPECT_EQ(forms.is_zero(sum_angle), std::optional<bool>(true));
  // Not zero: s^2 - c^2, s c - c s + a, 0.035 (s1 s2 - c1 c2) + 0.035 cos12.
  EXPECT_EQ(forms.is_zero(g.sub(g.mul(l.s1, l.s1), g.mul(l.c1, l.c1))),
            std::optional<bool>(false));
  EXPECT_EQ(forms.is_zero(g.add(cos12, g.mul(l.s1, l.s2))), std::optional<bool>(false));
  EXPECT_EQ(forms.is_zero(g.add(g.mul(g.constant(0.035), cos12),
                                g.mul(g.constant(0.035), g.sub(g.mul(l.s1, l.s2),
                                                               g.mul(l.c1, l.c2))))),
            std::optional<bool>(true));
}

TEST(TrigPolynomials, AnExpansionOverBudgetHasNoForm) {
  Leaves l;
  ExprGraph& g = l.g;
  // (a + b + c + s1 + c2)^6 has 210 monomials: over a budget of 50.
  const ExprId base = g.share(g.add({l.a, l.b, l.c, l.s1, l.c2}));
  ExprId power = base;
  for (int k = 1; k < 6; ++k) power = g.share(g.mul(power, base));
  TrigPolynomials small(g, 50);
  EXPECT_EQ(small.is_zero(power), std::nullopt);
  TrigPolynomials large(g, 1000);
  EXPECT_EQ(large.is_zero(power), std::optional<bool>(false));
}

TEST(OutputSimplifier, ReplacesAnExactZeroAndFoldsWhatUsesIt) {
  Leaves l;
  ExprGraph& g = l.g;
  const ExprId t1 = g.share(g.mul(l.c2, l.a));
  const ExprId t3 = g.share(g.neg(g.mul(l.a, l.s2)));
  const ExprId zero = g.share(g.sub(g.mul(l.c2, g.share(g.mul(l.b, t3))),
                                    g.mul(l.s2, g.share(g.neg(g.mul(l.b, t1))))));
  const ExprId product = g.mul(l.c, zero);
  const ExprId sum = g.add(l.c, zero);
  OutputSimplifier simplify(g);
  EXPECT_TRUE(g.is_zero(simplify(zero)));
  EXPECT_TRUE(g.is_zero(simplify(product)));
  EXPECT_EQ(simplify(sum), l.c);
  EXPECT_EQ(simplify.exact_zeros(), 1);  // memoized: proven once
}

TEST(OutputSimplifier, NegatedCopiesBecomeOneNode) {
  Leaves l;
  ExprGraph& g = l.g;
  const ExprId ab = g.mul(l.a, l.b);
  const ExprId minus_ab = g.mul(g.constant(-1.0), ab);
  const ExprId a_minus_b = g.sub(l.a, l.b);
  const ExprId b_minus_a = g.sub(l.b, l.a);
  OutputSimplifier simplify(g);
  // Each rewritten node is c * x with x one shared node.
  auto split = [&](ExprId id) -> std::pair<double, ExprId> {
    const Node& n = g.node(id);
    if (n.op == Op::kMul && n.args.size() == 2 && g.is_constant(n.args[0])) {
      return {g.constant_value(n.args[0]), n.args[1]};
    }
    return {1.0, id};
  };
  const auto [c_ab, x_ab] = split(simplify(ab));
  const auto [c_minus_ab, x_minus_ab] = split(simplify(minus_ab));
  EXPECT_EQ(x_ab, x_minus_ab);
  EXPECT_EQ(c_ab, -c_minus_ab);
  EXPECT_EQ(g.node(x_ab).op, Op::kShare);
  const auto [c1, x1] = split(simplify(a_minus_b));
  const auto [c2, x2] = split(simplify(b_minus_a));
  EXPECT_EQ(x1, x2);
  EXPECT_EQ(c1, -c2);
}

TEST(OutputSimplifier, RewrittenExpressionsKeepTheirValues) {
  Leaves l;
  ExprGraph& g = l.g;
  std::vector<ExprId> originals;
  std::mt19937_64 random(7);
  // Random sums and products of the leaves and of earlier expressions, some shared.
  std::vector<ExprId> pool{l.s1, l.c1, l.s2, l.c2, l.a, l.b, l.c, g.constant(0.5)};
  for (int k = 0; k < 300; ++k) {
    std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
    const ExprId x = pool[pick(random)], y = pool[pick(random)];
    ExprId e = k % 3 == 0 ? g.mul(x, y) : (k % 3 == 1 ? g.sub(x, y) : g.add(x, g.neg(g.mul(y, x))));
    if (k % 5 == 0) e = g.share(e);
    pool.push_back(e);
    originals.push_back(e);
  }
  OutputSimplifier simplify(g);
  std::vector<ExprId> rewritten;
  for (ExprId e : originals) rewritten.push_back(simplify(e));
  for (int state = 0; state < 5; ++state) {
    std::mt19937_64 draw(100 + state);
    const std::vector<double> v = l.values(draw);
    for (std::size_t k = 0; k < originals.size(); ++k) {
      const double expected = v[originals[k]];
      EXPECT_NEAR(v[rewritten[k]], expected, 1e-12 * (1 + std::abs(expected))) << k;
    }
  }
}

// On the symbolic models of every shipped robot: the rewritten regressor and inverse dynamics
// equal the originals at random states.
TEST(OutputSimplifier, KeepsTheValuesOfEveryShippedRobotsModels) {
  for (const std::string& robot : test::shipped_robots()) {
    SCOPED_TRACE(robot);
    const RobotModel model = load_robot(robot);
    ExprGraph g;
    const SymbolicInputs in = make_symbolic_inputs(g, model.tree);
    std::vector<ExprId> outputs = derive_standard_regressor(g, model.tree, in);
    const std::vector<ExprId> tau = derive_inverse_dynamics(g, model.tree, in);
    outputs.insert(outputs.end(), tau.begin(), tau.end());
    OutputSimplifier simplify(g);
    std::vector<ExprId> rewritten;
    for (ExprId e : outputs) rewritten.push_back(simplify(e));
    test::Random random(3);
    const int n = model.tree.dof;
    for (int state = 0; state < 3; ++state) {
      const Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2),
                            ddq = random.vector(n, -5, 5),
                            p = random.vector(static_cast<int>(model.tree.params.size()), -1, 1);
      const std::vector<double> v = g.evaluate(test::symbol_values(q, dq, ddq, p));
      double worst = 0, scale = 1;
      for (std::size_t k = 0; k < outputs.size(); ++k) {
        scale = std::max(scale, std::abs(v[outputs[k]]));
        worst = std::max(worst, std::abs(v[rewritten[k]] - v[outputs[k]]));
      }
      EXPECT_LT(worst, 1e-12 * scale);
    }
  }
}

}  // namespace
}  // namespace modelgen::gen
