// Differentiation rules over the node kinds of the DAG, applied children first without
// recursion (Newton-Euler chains of shared intermediates can be long), each node once.

#include "generator/symbolic/derivative.hpp"

#include <stdexcept>
#include <string>

namespace modelgen::gen {

PartialDerivative::PartialDerivative(ExprGraph& graph, ExprId variable)
    : graph_(graph), variable_(variable) {
  if (variable >= graph.size() || graph.node(variable).op != Op::kSymbol) {
    throw std::invalid_argument("PartialDerivative: node " + std::to_string(variable) +
                                " is not a symbol");
  }
}

ExprId PartialDerivative::operator()(ExprId root) {
  if (root >= graph_.size()) {
    throw std::invalid_argument("PartialDerivative: no node " + std::to_string(root));
  }
  auto is_done = [this](ExprId id) { return id < done_.size() && done_[id] != kNotDone; };
  std::vector<ExprId> stack = {root};
  while (!stack.empty()) {
    const ExprId e = stack.back();
    if (is_done(e)) {
      stack.pop_back();
      continue;
    }
    // Derivatives of the arguments first; e is built when it comes back to the top. The
    // argument of a sign is not needed: sign is piecewise constant.
    bool ready = true;
    if (graph_.node(e).op != Op::kSign) {
      for (ExprId arg : graph_.node(e).args) {
        if (!is_done(arg)) {
          stack.push_back(arg);
          ready = false;
        }
      }
    }
    if (!ready) continue;
    stack.pop_back();
    const ExprId d = differentiate_node(e);
    if (done_.size() <= e) done_.resize(graph_.size(), kNotDone);
    done_[e] = d;
  }
  return done_[root];
}

std::vector<ExprId> PartialDerivative::operator()(const std::vector<ExprId>& expressions) {
  std::vector<ExprId> result;
  result.reserve(expressions.size());
  for (ExprId e : expressions) result.push_back((*this)(e));
  return result;
}

ExprId PartialDerivative::differentiate_node(ExprId e) {
  const Node node = graph_.node(e);  // a copy: the graph grows below
  switch (node.op) {
    case Op::kConstant: return graph_.zero();
    case Op::kSymbol: return differentiate_symbol(e);
    case Op::kAdd: {
      std::vector<ExprId> terms;
      for (ExprId arg : node.args) {
        const ExprId d = done_[arg];
        if (!graph_.is_zero(d)) terms.push_back(d);
      }
      return graph_.add(std::move(terms));
    }
    case Op::kMul: {
      // Product rule: the sum over factors of (d factor) times the other factors. A repeated
      // factor (x x) appears once per position, so d (x x) = 2 x after like terms meet.
      std::vector<ExprId> terms;
      for (std::size_t i = 0; i < node.args.size(); ++i) {
        const ExprId d = done_[node.args[i]];
        if (graph_.is_zero(d)) continue;
        std::vector<ExprId> factors = {d};
        for (std::size_t k = 0; k < node.args.size(); ++k) {
          if (k != i) factors.push_back(node.args[k]);
        }
        terms.push_back(graph_.mul(std::move(factors)));
      }
      return graph_.add(std::move(terms));
    }
    case Op::kShare: return graph_.share(done_[node.args[0]]);
    case Op::kSign: return graph_.zero();  // zero wherever it is differentiable
    case Op::kInv: {
      // d (1/u) = -(1/u)^2 du, reusing the node 1/u itself (e), so no new division.
      const ExprId d = done_[node.args[0]];
      if (graph_.is_zero(d)) return graph_.zero();
      return graph_.mul({graph_.constant(-1.0), e, e, d});
    }
  }
  return graph_.zero();
}

ExprId PartialDerivative::differentiate_symbol(ExprId e) {
  if (e == variable_) return graph_.one();
  const Symbol& symbol = graph_.symbols()[graph_.node(e).symbol];
  const Symbol& variable = graph_.symbols()[graph_.node(variable_).symbol];
  if (symbol.kind == SymbolKind::kInput || symbol.input != variable.name) return graph_.zero();
  switch (symbol.kind) {
    case SymbolKind::kSin: return partner(SymbolKind::kCos, e);
    case SymbolKind::kCos: return graph_.neg(partner(SymbolKind::kSin, e));
    default: return graph_.zero();  // sign, positive, negative: piecewise constant
  }
}

ExprId PartialDerivative::partner(SymbolKind kind, ExprId of) {
  const std::string& input = graph_.symbols()[graph_.node(of).symbol].input;
  for (const Symbol& symbol : graph_.symbols()) {
    if (symbol.kind == kind && symbol.input == input) {
      const Symbol copy = symbol;  // symbol() looks the name up; it adds nothing
      return graph_.symbol(copy);
    }
  }
  throw std::logic_error("PartialDerivative: '" + graph_.symbols()[graph_.node(of).symbol].name +
                         "' of '" + input + "' has no " +
                         (kind == SymbolKind::kCos ? "cos" : "sin") +
                         " leaf to express its derivative");
}

std::vector<ExprId> jacobian(ExprGraph& graph, const std::vector<ExprId>& expressions,
                             const std::vector<ExprId>& variables) {
  const std::size_t n = variables.size();
  std::vector<ExprId> result(expressions.size() * n, graph.zero());
  for (std::size_t k = 0; k < n; ++k) {
    PartialDerivative d(graph, variables[k]);
    for (std::size_t i = 0; i < expressions.size(); ++i) result[i * n + k] = d(expressions[i]);
  }
  return result;
}

}  // namespace modelgen::gen
