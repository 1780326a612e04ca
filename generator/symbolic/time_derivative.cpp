// Differentiation rules over the node kinds of the DAG.

#include "generator/symbolic/time_derivative.hpp"

#include <vector>

namespace modelgen::gen {

ExprId TimeDerivative::operator()(ExprId e) {
  if (auto found = done_.find(e); found != done_.end()) return found->second;
  const Node node = graph_.node(e);  // a copy: the graph grows below
  ExprId result = graph_.zero();
  switch (node.op) {
    case Op::kConstant:
      break;
    case Op::kSymbol: {
      auto leaf = leaves_.find(e);
      if (leaf != leaves_.end()) result = leaf->second;
      break;
    }
    case Op::kAdd: {
      std::vector<ExprId> terms;
      for (ExprId a : node.args) terms.push_back((*this)(a));
      result = graph_.add(std::move(terms));
      break;
    }
    case Op::kMul: {
      // Product rule: sum over factors of (d factor) times the other factors.
      std::vector<ExprId> terms;
      for (std::size_t i = 0; i < node.args.size(); ++i) {
        const ExprId d = (*this)(node.args[i]);
        if (graph_.is_zero(d)) continue;
        std::vector<ExprId> factors = {d};
        for (std::size_t k = 0; k < node.args.size(); ++k) {
          if (k != i) factors.push_back(node.args[k]);
        }
        terms.push_back(graph_.mul(std::move(factors)));
      }
      result = graph_.add(std::move(terms));
      break;
    }
    case Op::kShare:
      result = graph_.share((*this)(node.args[0]));
      break;
    case Op::kSign:
      break;  // piecewise constant: zero wherever it is differentiable
    case Op::kInv: {
      // d/dt (1/u) = -(1/u)^2 du/dt
      const ExprId d = (*this)(node.args[0]);
      if (!graph_.is_zero(d)) result = graph_.mul({graph_.constant(-1.0), e, e, d});
      break;
    }

  }
  done_.emplace(e, result);
  return result;
}

}  // namespace modelgen::gen
