// Scheduling and printing of straight-line code. A node becomes a temporary when more than one
// parent (or output) uses it; single-use nodes are printed inline in their parent. Temporaries
// are numbered in emission order, which is a depth-first walk of the outputs in output order
// and of each node's arguments in their canonical order (ExprGraph::canonical_before): a
// function of the input only.

#include "generator/emit/statement_writer.hpp"

#include <algorithm>
#include <cmath>

#include "generator/emit/printer.hpp"

namespace modelgen::gen {

std::string render_statement(std::string_view template_name,
                             const std::vector<std::pair<const char*, std::string>>& values) {
  Printer printer(embedded_template(template_name));
  for (const auto& [name, value] : values) printer.set(name, value);
  std::string text = printer.render();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

namespace {

class StatementWriter {
 public:
  StatementWriter(const ExprGraph& graph, Scalar scalar, TrigSource trig)
      : g_(graph),
        scalar_(scalar),
        trig_(trig),
        uses_(graph.size(), 0),
        name_(graph.size()),
        prepared_(graph.size(), false),
        symbol_used_(graph.symbols().size(), false) {}

  FunctionBody write(const std::vector<FunctionOutput>& outputs) {
    count_uses(outputs);
    std::vector<std::string> body;
    for (const FunctionOutput& out : outputs) {
      prepare(out.value, body);
      const std::string value = expression(out.value, Context::kTop);
      if (out.comment.empty()) {
        body.push_back(
            render_statement("statements/output", {{"target", out.target}, {"value", value}}));
      } else {
        body.push_back(render_statement(
            "statements/output_named",
            {{"target", out.target}, {"value", value}, {"comment", out.comment}}));
      }
    }
    FunctionBody result;
    declare_symbols(result.lines);
    result.lines.insert(result.lines.end(), body.begin(), body.end());
    result.counts = counts_;
    return result;
  }

 private:
  enum class Context { kTop, kFactor };

  bool is_operation(ExprId id) const {
    const Op op = g_.node(id).op;
    return op == Op::kAdd || op == Op::kMul || op == Op::kShare || op == Op::kSign ||
           op == Op::kInv;
  }

  // A shared intermediate used once is printed as its expression.
  ExprId resolve(ExprId id) const {
    while (g_.node(id).op == Op::kShare && name_[id].empty()) id = g_.node(id).args[0];
    return id;
  }

  void count_uses(const std::vector<FunctionOutput>& outputs) {
    std::vector<bool> visited(g_.size(), false);
    std::vector<ExprId> stack;
    for (const FunctionOutput& out : outputs) {
      ++uses_[out.value];
      stack.push_back(out.value);
    }
    while (!stack.empty()) {
      const ExprId id = stack.back();
      stack.pop_back();
      if (visited[id]) continue;
      visited[id] = true;
      for (ExprId arg : g_.node(id).args) {
        ++uses_[arg];
        // A sign reads its argument twice ((x > 0) - (x < 0)): make it a temporary.
        if (g_.node(id).op == Op::kSign) ++uses_[arg];
        stack.push_back(arg);
      }
    }
  }

  // Emits the temporaries `id` depends on (and `id` itself if it is one), children first.
  void prepare(ExprId id, std::vector<std::string>& body) {
    if (prepared_[id]) return;
    prepared_[id] = true;
    const Node& n = g_.node(id);
    if (n.op == Op::kSymbol) {
      symbol_used_[n.symbol] = true;
      return;
    }
    if (!is_operation(id)) return;
    for (ExprId arg : n.args) prepare(arg, body);
    if (n.op == Op::kSign) {
      name_[id] = "t" + std::to_string(temporaries_++);
      body.push_back(render_statement("statements/sign_of",
                                      {{"scalar", scalar_name(scalar_)},
                                       {"name", name_[id]},
                                       {"value", expression(n.args[0], Context::kFactor)},
                                       {"zero", format_literal(0.0, scalar_)}}));
      return;
    }
    if (n.op == Op::kShare && !name_[n.args[0]].empty()) {
      name_[id] = name_[n.args[0]];  // already a temporary: no copy
      return;
    }
    if (uses_[id] >= 2) {
      const std::string value = expression(id, Context::kTop);
      name_[id] = "t" + std::to_string(temporaries_++);
      body.push_back(render_statement(
          "statements/temporary",
          {{"scalar", scalar_name(scalar_)}, {"name", name_[id]}, {"value", value}}));
    }
  }

  void declare_symbols(std::vector<std::string>& lines) {
    const std::string zero = format_literal(0.0, scalar_);
    for (std::size_t s = 0; s < g_.symbols().size(); ++s) {
      if (!symbol_used_[s]) continue;
      const Symbol& symbol = g_.symbols()[s];
      const char* tmpl = nullptr;
      switch (symbol.kind) {
        case SymbolKind::kInput: continue;
        case SymbolKind::kSin: tmpl = "statements/sin"; ++counts_.trig; break;
        case SymbolKind::kCos: tmpl = "statements/cos"; ++counts_.trig; break;
        case SymbolKind::kSign: tmpl = "statements/sign"; break;
        case SymbolKind::kPositive: tmpl = "statements/positive"; break;
        case SymbolKind::kNegative: tmpl = "statements/negative"; break;
      }
      const bool trig = symbol.kind == SymbolKind::kSin || symbol.kind == SymbolKind::kCos;
      std::string input = symbol.input;
      if (trig && trig_ == TrigSource::kGiven) {
        // q[i] -> sin_q[i] or cos_q[i], read instead of computed.
        --counts_.trig;
        tmpl = "statements/trig_given";
        input = (symbol.kind == SymbolKind::kSin ? "sin_" : "cos_") + input;
      }
      std::vector<std::pair<const char*, std::string>> values = {
          {"scalar", scalar_name(scalar_)}, {"name", symbol.name}, {"input", input}};
      if (!trig) {
        values.push_back({"zero", zero});
      }
      lines.push_back(render_statement(tmpl, values));
    }
  }

  std::string product(const Node& n, double coefficient) {
    std::string out;
    std::size_t first = g_.is_constant(n.args[0]) ? 1 : 0;
    if (coefficient != 1.0) {
      out = format_literal(coefficient, scalar_);
      ++counts_.mul;
    }
    for (std::size_t i = first; i < n.args.size(); ++i) {
      if (!out.empty()) {
        out += " * ";
        if (i > first) ++counts_.mul;
      }
      out += expression(n.args[i], Context::kFactor);
    }
    return out;
  }

  // The constant coefficient of a product (1 when it has none).
  double coefficient(const Node& n) const {
    return n.op == Op::kMul && g_.is_constant(n.args[0]) ? g_.constant_value(n.args[0]) : 1.0;
  }

  // One term of a printed sum: its sign and its magnitude's text.
  struct Term {
    bool negative = false;
    std::string magnitude;
    bool literal_sign = false;  // the sign can be folded into a numeric literal ("-2.0 * x")
  };

  // Collects the terms of a sum, negated when `negate`. Sums reached through inline shared
  // intermediates are spliced in (a + (b - c) prints as a + b - c), and so are negated ones
  // (a - (b - c) prints as a - b + c): same operations, no parentheses, no negations.
  void collect_terms(ExprId id, bool negate, std::vector<Term>& terms) {
    id = resolve(id);
    const Node& n = g_.node(id);
    if (name_[id].empty() && n.op == Op::kAdd) {
      for (ExprId term : n.args) collect_terms(term, negate, terms);
      return;
    }
    const bool inline_node = name_[id].empty();
    if (inline_node && n.op == Op::kMul && n.args.size() == 2 && coefficient(n) == -1.0) {
      const ExprId inner = resolve(n.args[1]);
      if (name_[inner].empty() && g_.node(inner).op == Op::kAdd) {
        collect_terms(inner, !negate, terms);
        return;
      }
    }
    Term term;
    term.negative = negate;
    if (inline_node && n.op == Op::kConstant) {
      term.negative = (n.value < 0) != negate;
      term.magnitude = format_literal(std::abs(n.value), scalar_);
      term.literal_sign = true;
    } else if (inline_node && n.op == Op::kMul && g_.is_constant(n.args[0])) {
      const double c = coefficient(n);
      term.negative = (c < 0) != negate;
      term.magnitude = product(n, std::abs(c));
      term.literal_sign = std::abs(c) != 1.0;
    } else {
      term.magnitude = expression(id, Context::kTop);
    }
    terms.push_back(std::move(term));
  }

  // A sum's text. It leads with a positive term where there is one (b - a, not -a + b), else
  // with a negative literal; only a sum of negated names starts with a negation.
  // Counting: each " + " or " - " is one addition; a leading "-" is a negation (one addition)
  // unless it is the sign of a numeric literal ("-2.0", "-0.5 * x"), which costs nothing.
  std::string sum(ExprId id) {
    std::vector<Term> terms;
    collect_terms(id, false, terms);
    auto lead = std::find_if(terms.begin(), terms.end(), [](const Term& t) { return !t.negative; });
    if (lead == terms.end()) {
      lead = std::find_if(terms.begin(), terms.end(), [](const Term& t) { return t.literal_sign; });
    }
    if (lead == terms.end()) lead = terms.begin();
    std::rotate(terms.begin(), lead, lead + 1);
    std::string out;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      const Term& t = terms[i];
      if (i == 0) {
        if (t.negative && !t.literal_sign) ++counts_.add;  // negation
        out += t.negative ? "-" + t.magnitude : t.magnitude;
      } else {
        ++counts_.add;
        out += (t.negative ? " - " : " + ") + t.magnitude;
      }
    }
    return out;
  }

  std::string expression(ExprId id, Context context) {
    if (!name_[id].empty()) return name_[id];
    id = resolve(id);
    if (!name_[id].empty()) return name_[id];
    const Node& n = g_.node(id);
    switch (n.op) {
      case Op::kConstant: {
        const std::string literal = format_literal(n.value, scalar_);
        return n.value < 0 && context == Context::kFactor ? "(" + literal + ")" : literal;
      }
      case Op::kSymbol: return g_.symbols()[n.symbol].name;
      case Op::kMul: {
        const double c = coefficient(n);
        if (c == -1.0) {
          ++counts_.add;  // negation
          const std::string magnitude = product(n, 1.0);
          return context == Context::kFactor ? "(-" + magnitude + ")" : "-" + magnitude;
        }
        const std::string text = product(n, c);  // a negative coefficient is a literal's sign
        return c < 0 && context == Context::kFactor ? "(" + text + ")" : text;
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
        if (name_[divisor].empty() && (op == Op::kMul || op == Op::kInv)) text = "(" + text + ")";
        const std::string quotient = format_literal(1.0, scalar_) + " / " + text;
        return context == Context::kFactor ? "(" + quotient + ")" : quotient;
      }
      case Op::kShare: break;  // resolved above
      case Op::kSign: break;   // always a temporary
    }
    return "";
  }

  const ExprGraph& g_;
  Scalar scalar_;
  TrigSource trig_;
  std::vector<int> uses_;
  std::vector<std::string> name_;
  std::vector<bool> prepared_;
  std::vector<bool> symbol_used_;
  int temporaries_ = 0;
  OpCounts counts_;
};

}  // namespace

FunctionBody write_statements(const ExprGraph& graph, const std::vector<FunctionOutput>& outputs,
                              Scalar scalar, TrigSource trig) {
  return StatementWriter(graph, scalar, trig).write(outputs);
}

}  // namespace modelgen::gen
