// Expression text for the statement writer: products with their coefficients, sums with
// their terms' signs, literal factors grouped and long sums split into parallel partial sums,
// each operation counted as it is printed.

#include "generator/emit/statement_writer_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "generator/emit/number_format.hpp"

namespace modelgen::gen {

// The factors of a product after its coefficient, joined by " * ". A flipped temporary
// among them (or among the factors of an inline product among them) prints as its name and
// toggles `negative`: the caller prints the sign.
std::string StatementWriter::factors(const Node& n, bool& negative) {
  std::string out;
  const std::size_t first = g_.is_constant(n.args[0]) ? 1 : 0;
  for (std::size_t i = first; i < n.args.size(); ++i) {
    if (i > first) {
      out += " * ";
      ++counts_.mul;
    }
    const ExprId factor = resolve(n.args[i]);
    const Node& f = g_.node(factor);
    if (named(factor)) {
      if (flipped_[factor]) negative = !negative;
      out += name(factor);
    } else if (f.op == Op::kMul && !g_.is_constant(f.args[0])) {
      out += factors(f, negative);
    } else {
      out += expression(factor, Context::kFactor);
    }
  }
  return out;
}

// A product with coefficient c (its own, or -c when its factors say so) and factors `body`.
std::string StatementWriter::product_text(double c, const std::string& body, Context context) {
  if (c == 1.0) return body;
  if (c == -1.0) {
    ++counts_.add;  // negation
    return context == Context::kFactor ? "(-" + body + ")" : "-" + body;
  }
  ++counts_.mul;
  const std::string text = format_literal(c, scalar_) + " * " + body;
  return c < 0 && context == Context::kFactor ? "(" + text + ")" : text;
}

// Collects the terms of a sum, negated when `negate`. Sums reached through inline shared
// intermediates are spliced in (a + (b - c) prints as a + b - c), and so are negated ones
// (a - (b - c) prints as a - b + c): same operations, no parentheses, no negations.
void StatementWriter::collect_terms(ExprId id, bool negate, std::vector<Term>& terms) {
  id = resolve(id);
  const Node& n = g_.node(id);
  if (!named(id) && n.op == Op::kAdd) {
    for (ExprId term : n.args) collect_terms(term, negate, terms);
    return;
  }
  const bool inline_node = !named(id);
  if (inline_node && n.op == Op::kMul && n.args.size() == 2 && coefficient(n) == -1.0) {
    const ExprId inner = resolve(n.args[1]);
    if (!named(inner) && g_.node(inner).op == Op::kAdd) {
      collect_terms(inner, !negate, terms);
      return;
    }
  }
  Term term;
  term.negative = negate;
  if (inline_node && n.op == Op::kConstant) {
    term.negative = (n.value < 0) != negate;
    term.rest = format_literal(std::abs(n.value), scalar_);
    term.literal_sign = true;
  } else if (inline_node && n.op == Op::kMul) {
    const double c = coefficient(n);
    bool flip = false;
    term.rest = factors(n, flip);
    term.negative = ((c < 0) != negate) != flip;
    term.coefficient = std::abs(c);
    term.literal_sign = std::abs(c) != 1.0;
  } else if (!inline_node) {
    term.negative = negate != (flipped_[id] != 0);
    term.rest = name(id);
  } else {
    term.rest = expression(id, Context::kTop);
  }
  terms.push_back(std::move(term));
}

// Terms with one literal factor print it once: 0.035 * a - 0.035 * b * c becomes
// 0.035 * (a - b * c), one multiplication instead of two. The group takes the place of its
// first term; a group of only negative terms is negated as a whole.
void StatementWriter::group_coefficients(std::vector<Term>& terms) {
  std::map<double, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (terms[i].coefficient != 1.0) groups[terms[i].coefficient].push_back(i);
  }
  std::vector<bool> removed(terms.size(), false);
  for (const auto& [c, members] : groups) {
    if (members.size() < 2) continue;
    std::vector<Term> inner;
    bool all_negative = true;
    for (std::size_t i : members) {
      Term t = terms[i];
      t.coefficient = 1.0;
      t.literal_sign = false;
      all_negative = all_negative && t.negative;
      inner.push_back(std::move(t));
    }
    if (all_negative) {
      for (Term& t : inner) t.negative = false;
    }
    Term group;
    group.negative = all_negative;
    group.coefficient = c;
    group.rest = "(" + join(inner) + ")";
    group.literal_sign = true;
    terms[members.front()] = std::move(group);
    for (std::size_t k = 1; k < members.size(); ++k) removed[members[k]] = true;
  }
  std::vector<Term> kept;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (!removed[i]) kept.push_back(std::move(terms[i]));
  }
  terms = std::move(kept);
}

// One term's magnitude: its literal factor (one multiplication) and the rest.
std::string StatementWriter::magnitude(const Term& t) {
  if (t.coefficient == 1.0) return t.rest;
  ++counts_.mul;
  return format_literal(t.coefficient, scalar_) + " * " + t.rest;
}

// Terms joined into a sum. It leads with a positive term where there is one (b - a, not
// -a + b), else with a negative literal; only a sum of negated names starts with a negation.
// Counting: each " + " or " - " is one addition; a leading "-" is a negation (one addition)
// unless it is the sign of a numeric literal ("-2.0", "-0.5 * x"), which costs nothing.
std::string StatementWriter::join(std::vector<Term> terms) {
  auto lead = std::find_if(terms.begin(), terms.end(), [](const Term& t) { return !t.negative; });
  if (lead == terms.end()) {
    lead = std::find_if(terms.begin(), terms.end(), [](const Term& t) { return t.literal_sign; });
  }
  if (lead == terms.end()) lead = terms.begin();
  std::rotate(terms.begin(), lead, lead + 1);
  if (terms.size() >= kLongSum) return grouped(std::move(terms));
  std::string out;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const Term& t = terms[i];
    if (i == 0) {
      if (t.negative && !t.literal_sign) ++counts_.add;  // negation
      out += t.negative ? "-" + magnitude(t) : magnitude(t);
    } else {
      ++counts_.add;
      out += (t.negative ? " - " : " + ") + magnitude(t);
    }
  }
  return out;
}

// A long sum as consecutive groups of terms, each summed in parentheses: the groups are
// independent chains of additions that run in parallel, where one long chain waits for each
// addition in turn. Same additions; a group of only negative terms is subtracted whole. (A
// sum of only negative terms pays one negation, even where a literal could have led it.)
std::string StatementWriter::grouped(std::vector<Term> terms) {
  std::vector<Term> groups;
  const std::size_t size = (terms.size() + kSumGroups - 1) / kSumGroups;
  for (std::size_t first = 0; first < terms.size(); first += size) {
    std::vector<Term> members(
        terms.begin() + static_cast<std::ptrdiff_t>(first),
        terms.begin() + static_cast<std::ptrdiff_t>(std::min(first + size, terms.size())));
    Term group;
    group.negative =
        std::all_of(members.begin(), members.end(), [](const Term& t) { return t.negative; });
    if (group.negative) {
      for (Term& t : members) t.negative = false;
    }
    group.rest = "(" + join(std::move(members)) + ")";
    groups.push_back(std::move(group));
  }
  return join(std::move(groups));
}

std::string StatementWriter::sum(ExprId id) {
  std::vector<Term> terms;
  collect_terms(id, false, terms);
  group_coefficients(terms);
  return join(std::move(terms));
}

// A temporary where its value is read: a flipped one is negated.
std::string StatementWriter::reference(ExprId id, Context context) {
  if (!flipped_[id]) return name(id);
  ++counts_.add;  // negation
  return context == Context::kFactor ? "(-" + name(id) + ")" : "-" + name(id);
}

std::string StatementWriter::expression(ExprId id, Context context) {
  id = resolve(id);
  if (named(id)) return reference(id, context);
  const Node& n = g_.node(id);
  switch (n.op) {
    case Op::kConstant: {
      const std::string literal = format_literal(n.value, scalar_);
      return n.value < 0 && context == Context::kFactor ? "(" + literal + ")" : literal;
    }
    case Op::kSymbol:
      return g_.symbols()[n.symbol].name;
    case Op::kMul: {
      const double c = coefficient(n);
      if (negated(id) != id) {
        const ExprId inner = resolve(negated(id));
        if (!named(inner) && g_.node(inner).op == Op::kAdd) {
          // -(a - b) prints as b - a: the negation costs nothing.
          const std::string out = sum(id);
          return context == Context::kFactor ? "(" + out + ")" : out;
        }
      }
      bool flip = false;
      const std::string body = factors(n, flip);
      // A negative coefficient other than -1 is a literal's sign.
      return product_text(flip ? -c : c, body, context);
    }
    case Op::kAdd: {
      const std::string out = sum(id);
      return context == Context::kFactor ? "(" + out + ")" : out;
    }
    case Op::kInv: {
      // One division, counted as a multiplication. The divisor is parenthesized unless it is
      // a single name or a sum (which kFactor already parenthesizes): 1.0 / (a * b).
      ++counts_.mul;
      const ExprId divisor = resolve(n.args[0]);
      std::string text = expression(divisor, Context::kFactor);
      const Op op = g_.node(divisor).op;
      if (!named(divisor) && (op == Op::kMul || op == Op::kInv)) text = "(" + text + ")";
      const std::string quotient = format_literal(1.0, scalar_) + " / " + text;
      return context == Context::kFactor ? "(" + quotient + ")" : quotient;
    }
    case Op::kShare:
      break;  // resolved above
    case Op::kSign:
      break;  // always a temporary
  }
  return "";
}

}  // namespace modelgen::gen
