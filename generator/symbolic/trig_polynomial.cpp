// Expansion into monomials, with the Pythagorean reduction applied to every product as it is
// formed so that forms stay canonical (no cos^2 left) and small.

#include "generator/symbolic/trig_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace modelgen::gen {

TrigPolynomials::TrigPolynomials(const ExprGraph& graph, std::size_t max_terms)
    : graph_(graph), max_terms_(max_terms) {
  std::unordered_map<std::string, ExprId> sin_of_input;
  std::vector<std::pair<std::string, ExprId>> cos_leaves;
  for (ExprId id = 0; id < graph.size(); ++id) {
    const Node& n = graph.node(id);
    if (n.op != Op::kSymbol) continue;
    const Symbol& symbol = graph.symbols()[n.symbol];
    if (symbol.kind == SymbolKind::kSin) sin_of_input[symbol.input] = id;
    if (symbol.kind == SymbolKind::kCos) cos_leaves.emplace_back(symbol.input, id);
  }
  for (const auto& [input, cos_id] : cos_leaves) {
    if (const auto found = sin_of_input.find(input); found != sin_of_input.end()) {
      sin_of_cos_[cos_id] = found->second;
    }
  }
}

Monomial TrigPolynomials::multiply(const Monomial& a, const Monomial& b) {
  Monomial out;
  out.reserve(a.size() + b.size());
  std::size_t i = 0, k = 0;
  while (i < a.size() || k < b.size()) {
    if (k == b.size() || (i < a.size() && a[i].first < b[k].first)) {
      out.push_back(a[i++]);
    } else if (i == a.size() || b[k].first < a[i].first) {
      out.push_back(b[k++]);
    } else {
      out.emplace_back(a[i].first, a[i].second + b[k].second);
      ++i;
      ++k;
    }
  }
  return out;
}

void TrigPolynomials::add_reduced(Form& out, Monomial monomial, double coefficient) const {
  for (std::size_t i = 0; i < monomial.size(); ++i) {
    const auto sin_leaf = sin_of_cos_.find(monomial[i].first);
    if (monomial[i].second < 2 || sin_leaf == sin_of_cos_.end()) continue;
    // m c^2 = m - m s^2
    Monomial rest = monomial;
    rest[i].second -= 2;
    if (rest[i].second == 0) rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(i));
    Monomial with_sin = multiply(rest, Monomial{{sin_leaf->second, 2}});
    add_reduced(out, std::move(rest), coefficient);
    add_reduced(out, std::move(with_sin), -coefficient);
    return;
  }
  out.scale = std::max(out.scale, std::abs(coefficient));
  out.terms[std::move(monomial)] += coefficient;
}

const TrigPolynomials::Form* TrigPolynomials::expand(ExprId id) {
  if (const auto found = memo_.find(id); found != memo_.end()) {
    return found->second ? &*found->second : nullptr;
  }
  const Node& n = graph_.node(id);
  std::optional<Form> result = Form{};
  switch (n.op) {
    case Op::kConstant:
      if (n.value != 0.0) add_reduced(*result, {}, n.value);
      break;
    case Op::kSymbol:
    case Op::kSign:
    case Op::kInv: add_reduced(*result, {{id, 1}}, 1.0); break;
    case Op::kShare: {
      const Form* inner = expand(n.args[0]);
      if (inner == nullptr) {
        result.reset();
      } else {
        result = *inner;
      }
      break;
    }
    case Op::kAdd:
      for (ExprId arg : n.args) {
        const Form* term = expand(arg);
        if (term == nullptr) {
          result.reset();
          break;
        }
        for (const auto& [monomial, c] : term->terms) result->terms[monomial] += c;
        result->scale = std::max(result->scale, term->scale);
        if (result->terms.size() > max_terms_) {
          result.reset();
          break;
        }
      }
      break;
    case Op::kMul: {
      result->terms[{}] = 1.0;
      result->scale = 1.0;
      for (ExprId arg : n.args) {
        const Form* factor = expand(arg);
        if (factor == nullptr || result->terms.size() * factor->terms.size() > 4 * max_terms_) {
          result.reset();
          break;
        }
        Form product;
        product.scale = result->scale * factor->scale;
        for (const auto& [a, ca] : result->terms) {
          for (const auto& [b, cb] : factor->terms) add_reduced(product, multiply(a, b), ca * cb);
        }
        *result = std::move(product);
        if (result->terms.size() > max_terms_) {
          result.reset();
          break;
        }
      }
      break;
    }
  }
  const auto [slot, inserted] = memo_.emplace(id, std::move(result));
  return slot->second ? &*slot->second : nullptr;
}

std::optional<bool> TrigPolynomials::is_zero(ExprId id) {
  const Form* form = expand(id);
  if (form == nullptr) return std::nullopt;
  const double tolerance = 1e-11 * form->scale;
  return std::all_of(form->terms.begin(), form->terms.end(),
                     [&](const auto& term) { return std::abs(term.second) <= tolerance; });
}

}  // namespace modelgen::gen
