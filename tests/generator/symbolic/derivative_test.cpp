// Symbolic partial derivatives: closed forms of small expressions (compared as canonical nodes),
// the constant 0 node for expressions without the variable, share() kept through the chain
// rule, memoization, bad variables; random expression DAGs and the symbolic Newton-Euler
// inverse dynamics of every shipped robot against central finite differences of the evaluated
// expressions, and d tau / d p against the separately derived standard regressor.

#include "generator/symbolic/derivative.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "generator/dynamics/newton_euler.hpp"
#include "tests/support/symbol_values.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

Symbol input(std::string name) { return Symbol{std::move(name), SymbolKind::kInput, ""}; }

// Leaf values from input values by name; derived leaves computed from their input.
std::function<double(const Symbol&)> leaf_values(const std::map<std::string, double>& inputs) {
  return [&inputs](const Symbol& s) {
    if (s.kind == SymbolKind::kInput) return inputs.at(s.name);
    const double v = inputs.at(s.input);
    switch (s.kind) {
      case SymbolKind::kSin: return std::sin(v);
      case SymbolKind::kCos: return std::cos(v);
      case SymbolKind::kSign: return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
      case SymbolKind::kPositive: return v > 0 ? 1.0 : 0.0;
      case SymbolKind::kNegative: return v < 0 ? 1.0 : 0.0;
      case SymbolKind::kInput: break;
    }
    return 0.0;
  };
}

class DerivativeTest : public testing::Test {
 protected:
  ExprGraph g;
  const ExprId x = g.symbol(input("x"));
  const ExprId y = g.symbol(input("y"));
  const ExprId z = g.symbol(input("z"));
  const ExprId sx = g.symbol({"sx", SymbolKind::kSin, "x"});
  const ExprId cx = g.symbol({"cx", SymbolKind::kCos, "x"});
  const ExprId sy = g.symbol({"sy", SymbolKind::kSin, "y"});
  const ExprId cy = g.symbol({"cy", SymbolKind::kCos, "y"});
  const ExprId sgx = g.symbol({"sgx", SymbolKind::kSign, "x"});
  const ExprId posx = g.symbol({"posx", SymbolKind::kPositive, "x"});
  const ExprId negx = g.symbol({"negx", SymbolKind::kNegative, "x"});
  const ExprId sgz = g.symbol({"sgz", SymbolKind::kSign, "z"});

  ExprId d(ExprId e, ExprId variable) { return PartialDerivative(g, variable)(e); }
};

TEST_F(DerivativeTest, LeavesAndPolynomialsHaveTheirClosedForms) {
  EXPECT_EQ(d(x, x), g.one());
  EXPECT_EQ(d(y, x), g.zero());
  EXPECT_EQ(d(g.constant(4.5), x), g.zero());
  // d/dx (x y + 3 x) = y + 3
  EXPECT_EQ(d(g.add(g.mul(x, y), g.mul(g.constant(3), x)), x), g.add(y, g.constant(3)));
  // d/dx x^2 = 2 x, d/dx x^3 = 3 x^2 (repeated factors of one product)
  EXPECT_EQ(d(g.mul(x, x), x), g.mul(g.constant(2), x));
  EXPECT_EQ(d(g.mul({x, x, x}), x), g.mul({g.constant(3), x, x}));
  // d/dy (x y z + sin y) = x z + cos y
  EXPECT_EQ(d(g.add(g.mul({x, y, z}), sy), y), g.add(g.mul(x, z), cy));
  // d/dx (x - y)^2 written as a product of sums: 2 (x - y)
  const ExprId diff = g.sub(x, y);
  const ExprId dsq = d(g.mul(diff, diff), x);
  const std::map<std::string, double> at = {{"x", 0.3}, {"y", -1.1}, {"z", 2.0}};
  EXPECT_DOUBLE_EQ(g.evaluate(leaf_values(at))[dsq], 2 * (0.3 + 1.1));
}

TEST_F(DerivativeTest, SinAndCosOfTheVariableAreDifferentiatedExactly) {
  EXPECT_EQ(d(sx, x), cx);
  EXPECT_EQ(d(cx, x), g.neg(sx));
  EXPECT_EQ(d(sy, x), g.zero());  // sin of another input
  EXPECT_EQ(d(cy, y), g.neg(sy));
  // d/dx (sin x cos x) = cos^2 x - sin^2 x = cos 2x
  const ExprId e = d(g.mul(sx, cx), x);
  for (double v : {-2.5, -0.4, 0.0, 0.9, 3.0}) {
    const std::map<std::string, double> at = {{"x", v}, {"y", 0.0}, {"z", 0.0}};
    EXPECT_NEAR(g.evaluate(leaf_values(at))[e], std::cos(2 * v), 1e-15);
  }
  // d/dx x sin x = sin x + x cos x
  EXPECT_EQ(d(g.mul(x, sx), x), g.add(sx, g.mul(x, cx)));
}

TEST_F(DerivativeTest, SignsArePiecewiseConstant) {
  EXPECT_EQ(d(g.sign(g.mul(x, y)), x), g.zero());
  EXPECT_EQ(d(sgx, x), g.zero());
  EXPECT_EQ(d(posx, x), g.zero());
  EXPECT_EQ(d(negx, x), g.zero());
  // |x| = sign(x) x has derivative sign(x) away from 0
  EXPECT_EQ(d(g.mul(sgx, x), x), sgx);
  // a sign node's argument is not differentiated (it may be anything)
  EXPECT_EQ(d(g.mul(g.sign(g.add(x, sy)), y), y), g.sign(g.add(x, sy)));
}

TEST_F(DerivativeTest, ReciprocalsFollowTheQuotientRule) {
  // d (1/x) / dx = -(1/x)^2, built on the node 1/x itself.
  const ExprId inv_x = g.inv(x);
  EXPECT_EQ(d(inv_x, x), g.mul({g.constant(-1), inv_x, inv_x}));
  EXPECT_EQ(d(inv_x, y), g.zero());
  // d (y / (x^2 + 1)) / dx = -2 x y / (x^2 + 1)^2, compared by value with the closed form.
  const ExprId e = g.div(y, g.add(g.mul(x, x), g.one()));
  const ExprId dx = d(e, x);
  const ExprId dy = d(e, y);
  const std::map<std::string, double> at = {{"x", 0.7}, {"y", -1.3}, {"z", 0.0}};
  const std::vector<double> v = g.evaluate(leaf_values(at));
  const double den = 0.7 * 0.7 + 1;
  EXPECT_NEAR(v[dx], -2 * 0.7 * -1.3 / (den * den), 1e-15);
  EXPECT_NEAR(v[dy], 1 / den, 1e-15);
  // Through a share and a product: d (1 / share(x y)) / dy = -x / (x y)^2.
  const ExprId shared = g.share(g.add(g.mul(x, y), z));
  const ExprId d_shared = d(g.inv(shared), y);
  const std::vector<double> w = g.evaluate(leaf_values(at));
  EXPECT_NEAR(w[d_shared], -0.7 / ((0.7 * -1.3) * (0.7 * -1.3)), 1e-14);
}

TEST_F(DerivativeTest, ExpressionsWithoutTheVariableGiveTheZeroNode) {
  const ExprId shared = g.share(g.add(g.mul(y, z), sy));
  const ExprId e = g.add({g.mul(shared, cy), g.mul(g.constant(2), z), g.sign(y), sgz,
                          g.share(g.mul({shared, shared, z}))});
  EXPECT_EQ(d(e, x), g.zero());
  EXPECT_NE(d(e, y), g.zero());
  // with respect to a symbol that appears nowhere
  const ExprId w = g.symbol(input("w"));
  EXPECT_EQ(d(e, w), g.zero());
}

TEST_F(DerivativeTest, DerivativesOfSharedResultsStayShared) {
  const ExprId inner = g.share(g.add(g.mul({x, y, z}), cy));
  const ExprId dx = d(inner, x);
  EXPECT_EQ(g.node(dx).op, Op::kShare);
  EXPECT_EQ(dx, g.share(g.mul(y, z)));
  // the chain rule goes through the share: d/dx inner^2 = 2 inner d inner
  const ExprId square = d(g.mul(inner, inner), x);
  EXPECT_EQ(square, g.mul({g.constant(2), inner, g.share(g.mul(y, z))}));
}

TEST_F(DerivativeTest, MemoizedPerNodeAndDeterministic) {
  const ExprId a = g.share(g.add(g.mul(x, sx), y));
  const ExprId b = g.share(g.mul({a, a, cx}));
  const ExprId e = g.add(g.mul(a, b), g.mul(b, z));
  PartialDerivative dx(g, x);
  EXPECT_EQ(dx.variable(), x);
  const ExprId first = dx(e);
  const std::size_t size = g.size();
  EXPECT_EQ(dx(e), first);
  EXPECT_EQ(g.size(), size);  // nothing rebuilt
  // the batched form equals one-by-one calls, and a new object finds the same canonical nodes
  const std::vector<ExprId> batch = PartialDerivative(g, x)({e, a, b});
  EXPECT_EQ(batch, (std::vector<ExprId>{first, dx(a), dx(b)}));
  EXPECT_EQ(g.size(), size);
  const std::vector<ExprId> J = jacobian(g, {e, a}, {x, y, z});
  ASSERT_EQ(J.size(), 6u);
  EXPECT_EQ(J[0], first);
  EXPECT_EQ(J[1], d(e, y));
  EXPECT_EQ(J[3], dx(a));
  EXPECT_EQ(J[5], g.zero());  // a does not contain z
}

TEST_F(DerivativeTest, RejectsNonSymbolsAndMissingTrigPartners) {
  EXPECT_THROW(PartialDerivative(g, g.add(x, y)), std::invalid_argument);
  EXPECT_THROW(PartialDerivative(g, static_cast<ExprId>(g.size() + 10)), std::invalid_argument);
  PartialDerivative dx(g, x);
  EXPECT_THROW(dx(static_cast<ExprId>(g.size() + 10)), std::invalid_argument);
  const ExprId w = g.symbol(input("w"));
  const ExprId sw = g.symbol({"sw", SymbolKind::kSin, "w"});  // no cos w in the graph
  try {
    PartialDerivative(g, w)(g.mul(sw, y));
    FAIL() << "expected std::logic_error";
  } catch (const std::logic_error& error) {
    EXPECT_NE(std::string(error.what()).find("'sw' of 'w' has no cos leaf"), std::string::npos)
        << error.what();
  }
}

// Random DAGs of sums, products, shares and signs over the leaves, differentiated with respect
// to x, y and z, against finite differences of the evaluated expressions.
TEST_F(DerivativeTest, RandomExpressionsMatchFiniteDifferences) {
  std::mt19937_64 engine(17);
  auto pick = [&engine](std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(engine);
  };
  auto uniform = [&engine](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(engine);
  };
  std::vector<ExprId> pool = {x, y, z, sx, cx, sy, cy, sgx, sgz, posx, negx};
  for (int k = 0; k < 6; ++k) pool.push_back(g.constant(std::round(uniform(-3, 3) * 4) / 4));
  for (int k = 0; k < 300; ++k) {
    const std::size_t choice = pick(10);
    // Operands drawn from the most recent part of the pool, so that depth builds up.
    auto operand = [&]() {
      const std::size_t window = std::min<std::size_t>(pool.size(), 40);
      return pool[pool.size() - 1 - pick(window)];
    };
    ExprId e;
    if (choice < 4) {
      std::vector<ExprId> terms;
      for (std::size_t t = 0, n = 2 + pick(3); t < n; ++t) terms.push_back(operand());
      e = g.add(std::move(terms));
    } else if (choice < 7) {
      // Products of a few leaves and one pooled node keep values of moderate size.
      std::vector<ExprId> factors = {operand(), pool[pick(11)]};
      if (pick(2) == 0) factors.push_back(g.constant(uniform(-1, 1)));
      e = g.mul(std::move(factors));
    } else if (choice < 9) {
      e = g.share(g.add(operand(), g.mul(operand(), pool[pick(11)])));
    } else {
      e = g.mul(g.sign(operand()), operand());
    }
    pool.push_back(e);
  }
  const std::vector<ExprId> outputs(pool.end() - 40, pool.end());
  const std::vector<ExprId> variables = {x, y, z};
  const std::vector<ExprId> J = jacobian(g, outputs, variables);
  const std::vector<std::string> names = {"x", "y", "z"};

  double worst = 0;
  int checked = 0;
  for (int trial = 0; trial < 50; ++trial) {
    std::map<std::string, double> at = {
        {"x", uniform(-1.5, 1.5)}, {"y", uniform(-1.5, 1.5)}, {"z", uniform(-1.5, 1.5)}};
    // Stay away from the jumps of the sign leaves (at x = 0 and z = 0).
    if (std::abs(at["x"]) < 0.05 || std::abs(at["z"]) < 0.05) continue;
    const std::vector<double> value = g.evaluate(leaf_values(at));
    for (std::size_t k = 0; k < variables.size(); ++k) {
      const double h = 1e-4, base = at[names[k]];
      std::vector<std::vector<double>> shifted;
      for (double step : {-2 * h, -h, h, 2 * h}) {
        at[names[k]] = base + step;
        shifted.push_back(g.evaluate(leaf_values(at)));
      }
      at[names[k]] = base;
      // Skip outputs whose sign nodes jump inside the stencil: no derivative there.
      bool jump = false;
      for (ExprId id = 0; id < g.size() && !jump; ++id) {
        if (g.node(id).op != Op::kSign) continue;
        for (const std::vector<double>& s : shifted) jump = jump || s[id] != value[id];
      }
      if (jump) continue;
      for (std::size_t i = 0; i < outputs.size(); ++i) {
        const ExprId o = outputs[i];
        const double fd =
            (8 * (shifted[2][o] - shifted[1][o]) - (shifted[3][o] - shifted[0][o])) / (12 * h);
        const double symbolic = value[J[i * variables.size() + k]];
        const double scale = std::max({1.0, std::abs(fd), std::abs(value[o])});
        worst = std::max(worst, std::abs(symbolic - fd) / scale);
        ++checked;
      }
    }
  }
  std::cout << "[ DERIVATIVE] random DAG of " << g.size() << " nodes: worst relative difference "
            << worst << " over " << checked << " derivatives\n";
  EXPECT_GT(checked, 3000);
  EXPECT_LT(worst, 1e-7);
}

// The symbolic inverse dynamics of every shipped robot: d tau / d p is the standard regressor
// (derived separately, column by column, by derive_standard_regressor), and d tau / d(q, dq, ddq)
// matches finite differences of the evaluated torques.
class NewtonEulerDerivative : public testing::TestWithParam<std::string> {};

TEST_P(NewtonEulerDerivative, MatchesRegressorAndFiniteDifferences) {
  const RobotModel model = load_robot(GetParam());
  const RigidBodyTree& tree = model.tree;
  const int n = tree.dof, np = static_cast<int>(tree.params.size());
  ExprGraph graph;
  const SymbolicInputs in = make_symbolic_inputs(graph, tree);
  const std::vector<ExprId> tau = derive_inverse_dynamics(graph, tree, in);
  const std::vector<ExprId> W = derive_standard_regressor(graph, tree, in);
  const std::vector<ExprId> tau_p = jacobian(graph, tau, in.p);
  std::vector<ExprId> state = in.q;
  state.insert(state.end(), in.dq.begin(), in.dq.end());
  state.insert(state.end(), in.ddq.begin(), in.ddq.end());
  const std::vector<ExprId> J = jacobian(graph, tau, state);

  test::Random random(41);
  double worst_regressor = 0, worst_state = 0;
  int skipped = 0;
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2),
                    ddq = random.vector(n, -5, 5);
    const Eigen::VectorXd p = random.vector(np, -1, 1);
    // Away from the jumps of Coulomb friction at dq = 0.
    for (int i = 0; i < n; ++i) dq[i] += dq[i] < 0 ? -0.1 : 0.1;
    const std::vector<double> value = graph.evaluate(test::symbol_values(q, dq, ddq, p));
    for (int i = 0; i < n; ++i) {
      double scale = 1;
      for (int k = 0; k < np; ++k) scale = std::max(scale, std::abs(value[W[i * np + k]]));
      for (int k = 0; k < np; ++k) {
        worst_regressor = std::max(
            worst_regressor, std::abs(value[tau_p[i * np + k]] - value[W[i * np + k]]) / scale);
      }
    }
    for (int k = 0; k < 3 * n; ++k) {
      Eigen::VectorXd& x = k < n ? q : (k < 2 * n ? dq : ddq);
      const int index = k % n;
      const double base = x[index];
      std::vector<std::vector<double>> shifted;
      const double h = 1e-4;
      for (double step : {-2 * h, -h, h, 2 * h}) {
        x[index] = base + step;
        shifted.push_back(graph.evaluate(test::symbol_values(q, dq, ddq, p)));
      }
      x[index] = base;
      // Coulomb friction of a motor driving several joints is sign(K dq): skip a stencil that
      // crosses its jump.
      bool jump = false;
      for (ExprId id = 0; id < graph.size() && !jump; ++id) {
        if (graph.node(id).op != Op::kSign) continue;
        for (const std::vector<double>& s : shifted) jump = jump || s[id] != value[id];
      }
      if (jump) {
        ++skipped;
        continue;
      }
      double scale = 1;
      for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(value[tau[i]]));
      for (int i = 0; i < n; ++i) {
        const ExprId t = tau[i];
        const double fd =
            (8 * (shifted[2][t] - shifted[1][t]) - (shifted[3][t] - shifted[0][t])) / (12 * h);
        worst_state = std::max(worst_state, std::abs(value[J[i * 3 * n + k]] - fd) /
                                                std::max(scale, std::abs(fd)));
      }
    }
  }
  std::cout << "[ DERIVATIVE] " << GetParam() << ": " << graph.size() << " nodes, worst relative "
            << "difference d tau/d p vs regressor " << worst_regressor
            << ", d tau/d state vs finite differences " << worst_state << " (" << skipped
            << " stencils across a friction jump skipped)\n";
  EXPECT_LE(skipped, 3);
  EXPECT_LT(worst_regressor, 1e-12);
  EXPECT_LT(worst_state, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(All, NewtonEulerDerivative, testing::ValuesIn(test::shipped_robots()),
                         test::robot_test_name);

}  // namespace
}  // namespace modelgen::gen
