// Scheduling and printing of straight-line code. A node becomes a temporary when more than one
// parent (or output) uses it; single-use nodes are printed inline in their parent. Temporaries
// are numbered in emission order, which is a depth-first walk of the outputs in output order
// and of each node's arguments in their canonical order (ExprGraph::canonical_before): a
// function of the input only. A temporary that is a sum holds its negation when the values
// printed from it (outputs and other temporaries) read it negated, through a coefficient of -1,
// at least twice more often than not (the drive Jacobian's -Y[k] * t6 entries become
// Y[k] * t6): every reference to it then carries the sign, and the sum costs at most one
// leading negation more.

#include "generator/emit/statement_writer.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

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
  StatementWriter(const ExprGraph& graph, Scalar scalar, TrigSource trig, WriterWorkspace& workspace)
      : g_(graph),
        scalar_(scalar),
        trig_(trig),
        uses_(workspace.uses),
        temporary_(workspace.temporary),
        flipped_(workspace.flipped),
        keep_sign_(workspace.keep_sign),
        negative_votes_(workspace.negative_votes),
        prepared_(workspace.prepared),
        visited_(workspace.visited),
        symbol_used_(graph.symbols().size(), false) {
    workspace.fit(graph.size());  // resizes the vectors the members refer to
  }
  StatementWriter(const StatementWriter&) = delete;
  StatementWriter& operator=(const StatementWriter&) = delete;
  // The touched entries back to zero: the nodes reached from the outputs, and the negations
  // prepare() passed through, which count their uses on what they negate.
  ~StatementWriter() {
    for (const std::vector<ExprId>* ids : {&reachable_, &prepared_list_}) {
      for (ExprId id : *ids) {
        uses_[id] = temporary_[id] = negative_votes_[id] = 0;
        flipped_[id] = keep_sign_[id] = prepared_[id] = visited_[id] = 0;
      }
    }
  }

  FunctionBody write(const std::vector<FunctionOutput>& outputs) {
    count_uses(outputs);
    for (const FunctionOutput& out : outputs) {
      if (!g_.is_zero(out.value)) vote(out.value, false);
    }
    for (ExprId id : reachable_) {
      if (becomes_temporary(id)) vote_body(id, false);
    }
    std::vector<std::string> body;
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      const FunctionOutput& out = outputs[o];
      if (g_.is_zero(out.value)) continue;  // zero for every input: the caller zeroes it once
      prepare(out.value, body);
      if (const std::optional<ScaledCopy> head = scaled_copy(out)) {
        if (const std::size_t run = scaled_copy_run(outputs, o, *head); run >= kMinLoop) {
          body.push_back(scaled_copy_loop(outputs, o, run, *head));
          o += run - 1;
          continue;
        }
      }
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

  // Runs of at least this many outputs A[a + j] = B[b + j] * f print as one loop.
  static constexpr std::size_t kMinLoop = 4;
  // Sums of at least this many terms print as kSumGroups parenthesized partial sums (below).
  static constexpr std::size_t kLongSum = 32;
  static constexpr std::size_t kSumGroups = 4;

  // "J[12]" as ("J", 12); nullopt for a target or a symbol name of another form.
  static std::optional<std::pair<std::string, long>> array_entry(const std::string& text) {
    const std::size_t open = text.find('[');
    if (open == std::string::npos || open == 0 || open + 2 >= text.size() || text.back() != ']') {
      return std::nullopt;
    }
    long index = 0;
    for (std::size_t i = open + 1; i + 1 < text.size(); ++i) {
      if (text[i] < '0' || text[i] > '9') return std::nullopt;
      index = 10 * index + (text[i] - '0');
    }
    return std::make_pair(text.substr(0, open), index);
  }

  // An output that is an input array's entry times one value, B[b] * f: f a symbol or a named
  // temporary, and the product positive as printed (a sign-normal -(B[b] * -t) with t stored
  // negated is B[b] * t), so that one text computes every entry of a run.
  struct ScaledCopy {
    std::string target, source;
    long target_index = 0, source_index = 0;
    ExprId factor = 0;
  };
  // Whether `id`, or a shared intermediate it stands for, is (or will be) a temporary: read by
  // other values too.
  bool read_elsewhere(ExprId id) const {
    for (;;) {
      if (named(id) || becomes_temporary(id)) return true;
      if (g_.node(id).op != Op::kShare) return false;
      id = g_.node(id).args[0];
    }
  }
  std::optional<ScaledCopy> scaled_copy(const FunctionOutput& out) const {
    // A product the function reads elsewhere too is a temporary of its own, not a loop entry
    // (only the run's first output has been through prepare(): ask for later ones as well).
    if (read_elsewhere(out.value)) return std::nullopt;
    ExprId id = resolve(out.value);
    if (g_.node(id).op != Op::kMul) return std::nullopt;
    const double c = coefficient(g_.node(id));
    if (c != 1.0) {
      if (c != -1.0 || g_.node(id).args.size() != 2) return std::nullopt;
      if (read_elsewhere(g_.node(id).args[1])) return std::nullopt;
      id = resolve(g_.node(id).args[1]);
    }
    const Node& n = g_.node(id);
    if (n.op != Op::kMul || n.args.size() != 2 || g_.is_constant(n.args[0])) return std::nullopt;
    for (int s = 0; s < 2; ++s) {
      const Node& entry = g_.node(n.args[s]);
      if (entry.op != Op::kSymbol || g_.symbols()[entry.symbol].kind != SymbolKind::kInput) continue;
      const ExprId factor = resolve(n.args[1 - s]);
      const bool symbol = g_.node(factor).op == Op::kSymbol;
      if (!symbol && !named(factor)) continue;
      const bool negative = (c < 0) != (!symbol && flipped_[factor] != 0);
      const auto target = array_entry(out.target);
      const auto source = array_entry(g_.symbols()[entry.symbol].name);
      if (negative || !target || !source) continue;
      return ScaledCopy{target->first, source->first, target->second, source->second, factor};
    }
    return std::nullopt;
  }

  // The number of outputs from `first` (the scaled copy `head`) on that continue it: consecutive
  // targets reading consecutive entries of one array times one factor.
  std::size_t scaled_copy_run(const std::vector<FunctionOutput>& outputs, std::size_t first,
                              const ScaledCopy& head) {
    std::size_t run = 1;
    for (std::size_t o = first + 1; o < outputs.size(); ++o, ++run) {
      const std::optional<ScaledCopy> next = scaled_copy(outputs[o]);
      const long step = static_cast<long>(run);
      if (!next || next->target != head.target || next->source != head.source ||
          next->factor != head.factor || next->target_index != head.target_index + step ||
          next->source_index != head.source_index + step) {
        break;
      }
    }
    return run;
  }

  // One loop for a run of scaled copies, counted as the multiplications it performs, with the
  // outputs' comments (the parameter names of a regressor's columns) after it. The compiler
  // vectorizes it, where the same copies as statements stay scalar.
  std::string scaled_copy_loop(const std::vector<FunctionOutput>& outputs, std::size_t first,
                               std::size_t run, const ScaledCopy& head) {
    counts_.mul += static_cast<long>(run);
    std::string comments;
    for (std::size_t o = first; o < first + run; ++o) {
      if (outputs[o].comment.empty()) continue;
      comments += (comments.empty() ? "" : " ") + outputs[o].comment;
    }
    const ExprId factor = head.factor;
    const std::string factor_text =
        named(factor) ? name(factor) : g_.symbols()[g_.node(factor).symbol].name;
    if (g_.node(factor).op == Op::kSymbol) symbol_used_[g_.node(factor).symbol] = true;
    std::vector<std::pair<const char*, std::string>> values = {
        {"count", std::to_string(run)},
        {"target", head.target},
        {"target_first", std::to_string(head.target_index)},
        {"source", head.source},
        {"source_first", std::to_string(head.source_index)},
        {"factor", factor_text}};
    if (comments.empty()) return render_statement("statements/output_loop", values);
    values.push_back({"comment", comments});
    return render_statement("statements/output_loop_named", values);
  }

  bool is_operation(ExprId id) const {
    const Op op = g_.node(id).op;
    return op == Op::kAdd || op == Op::kMul || op == Op::kShare || op == Op::kSign ||
           op == Op::kInv;
  }

  // x for a negation -x (a product of -1 and one factor), else `id` itself. A negation is
  // never a temporary: its uses count as uses of x, and each prints as a subtraction (or, for
  // a flipped temporary x, as x's name).
  ExprId negated(ExprId id) const {
    const Node& n = g_.node(id);
    if (n.op == Op::kMul && n.args.size() == 2 && g_.is_constant(n.args[0]) &&
        g_.constant_value(n.args[0]) == -1.0) {
      return n.args[1];
    }
    return id;
  }

  bool named(ExprId id) const { return temporary_[id] != 0; }
  std::string name(ExprId id) const { return "t" + std::to_string(temporary_[id] - 1); }

  // A shared intermediate used once is printed as its expression.
  ExprId resolve(ExprId id) const {
    while (g_.node(id).op == Op::kShare && !named(id)) id = g_.node(id).args[0];
    return id;
  }

  // Whether prepare() will make `id` a temporary of its own (uses_ counted): not a share of
  // a temporary, which only names its argument.
  bool becomes_temporary(ExprId id) const {
    const Node& n = g_.node(id);
    if (n.op == Op::kSign) return true;
    if (uses_[id] < 2 || !is_operation(id) || negated(id) != id) return false;
    return n.op != Op::kShare || !becomes_temporary(n.args[0]);
  }

  // The vote of one printed value (an output or a temporary's definition) for the sign of the
  // temporaries it multiplies with a coefficient of +-1 (a coefficient of another size prints
  // its sign for free, and so does a sum): `negative` when it prints them negated.
  // negative_votes_[t] counts the negated reads of t minus the others.
  void vote(ExprId id, bool negative) {
    if (becomes_temporary(id)) {
      negative_votes_[id] += negative ? 1 : -1;
      return;
    }
    vote_body(id, negative);
  }
  void vote_body(ExprId id, bool negative) {
    const Node& n = g_.node(id);
    if (n.op == Op::kShare) {
      vote(n.args[0], negative);
    } else if (n.op == Op::kMul) {
      const double c = coefficient(n);
      if (std::abs(c) != 1.0) return;
      for (ExprId arg : n.args) {
        if (!g_.is_constant(arg)) vote(arg, negative != (c < 0));
      }
    }
  }

  void count_uses(const std::vector<FunctionOutput>& outputs) {
    std::vector<char>& visited = visited_;
    std::vector<ExprId> stack;
    auto use = [&](ExprId id) {
      id = negated(id);
      ++uses_[id];
      stack.push_back(id);
    };
    for (const FunctionOutput& out : outputs) {
      if (!g_.is_zero(out.value)) use(out.value);
    }
    while (!stack.empty()) {
      const ExprId id = stack.back();
      stack.pop_back();
      if (visited[id]) continue;
      visited[id] = true;
      reachable_.push_back(id);
      for (ExprId arg : g_.node(id).args) {
        use(arg);
        // A sign reads its argument twice ((x > 0) - (x < 0)): make it a temporary.
        if (g_.node(id).op == Op::kSign) ++uses_[negated(arg)];
        // A sign or a reciprocal of a flipped temporary would pay for its negation.
        if (g_.node(id).op == Op::kSign || g_.node(id).op == Op::kInv) {
          keep_sign_[negated(arg)] = 1;
        }
      }
    }
  }

  // Emits the temporaries `id` depends on (and `id` itself if it is one), children first.
  void prepare(ExprId id, std::vector<std::string>& body) {
    if (prepared_[id]) return;
    prepared_[id] = 1;
    prepared_list_.push_back(id);
    const Node& n = g_.node(id);
    if (n.op == Op::kSymbol) {
      symbol_used_[n.symbol] = true;
      return;
    }
    if (!is_operation(id)) return;
    if (negated(id) != id) {
      prepare(negated(id), body);
      return;
    }
    for (ExprId arg : n.args) prepare(arg, body);
    if (n.op == Op::kSign) {
      temporary_[id] = ++temporaries_;
      body.push_back(render_statement("statements/sign_of",
                                      {{"scalar", scalar_name(scalar_)},
                                       {"name", name(id)},
                                       {"value", expression(n.args[0], Context::kFactor)},
                                       {"zero", format_literal(0.0, scalar_)}}));
      return;
    }
    if (n.op == Op::kShare && named(n.args[0])) {
      temporary_[id] = temporary_[n.args[0]];  // already a temporary: no copy
      flipped_[id] = flipped_[n.args[0]];
      return;
    }
    if (uses_[id] >= 2) {
      // A sum prints negated for free (its terms' signs flip), but for a leading negation
      // when all its terms are positive: flip on a net vote of two.
      const bool flip = negative_votes_[id] >= 2 && !keep_sign_[id] &&
                        g_.node(resolve(id)).op == Op::kAdd;
      std::string value;
      if (flip) {
        std::vector<Term> terms;
        collect_terms(id, true, terms);
        group_coefficients(terms);
        value = join(std::move(terms));
      } else {
        value = expression(id, Context::kTop);
      }
      temporary_[id] = ++temporaries_;
      flipped_[id] = flip ? 1 : 0;
      body.push_back(render_statement(
          "statements/temporary",
          {{"scalar", scalar_name(scalar_)}, {"name", name(id)}, {"value", value}}));
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

  // The factors of a product after its coefficient, joined by " * ". A flipped temporary
  // among them (or among the factors of an inline product among them) prints as its name and
  // toggles `negative`: the caller prints the sign.
  std::string factors(const Node& n, bool& negative) {
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
  std::string product_text(double c, const std::string& body, Context context) {
    if (c == 1.0) return body;
    if (c == -1.0) {
      ++counts_.add;  // negation
      return context == Context::kFactor ? "(-" + body + ")" : "-" + body;
    }
    ++counts_.mul;
    const std::string text = format_literal(c, scalar_) + " * " + body;
    return c < 0 && context == Context::kFactor ? "(" + text + ")" : text;
  }

  // The constant coefficient of a product (1 when it has none).
  double coefficient(const Node& n) const {
    return n.op == Op::kMul && g_.is_constant(n.args[0]) ? g_.constant_value(n.args[0]) : 1.0;
  }

  // One term of a printed sum: its sign and its magnitude's text.
  struct Term {
    bool negative = false;
    double coefficient = 1.0;   // a literal factor of `rest`, printed in front of it
    std::string rest;           // the term without its literal factor (or the literal alone)
    bool literal_sign = false;  // the sign can be folded into a numeric literal ("-2.0 * x")
  };

  // Collects the terms of a sum, negated when `negate`. Sums reached through inline shared
  // intermediates are spliced in (a + (b - c) prints as a + b - c), and so are negated ones
  // (a - (b - c) prints as a - b + c): same operations, no parentheses, no negations.
  void collect_terms(ExprId id, bool negate, std::vector<Term>& terms) {
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
  void group_coefficients(std::vector<Term>& terms) {
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
  std::string magnitude(const Term& t) {
    if (t.coefficient == 1.0) return t.rest;
    ++counts_.mul;
    return format_literal(t.coefficient, scalar_) + " * " + t.rest;
  }

  // Terms joined into a sum. It leads with a positive term where there is one (b - a, not
  // -a + b), else with a negative literal; only a sum of negated names starts with a negation.
  // Counting: each " + " or " - " is one addition; a leading "-" is a negation (one addition)
  // unless it is the sign of a numeric literal ("-2.0", "-0.5 * x"), which costs nothing.
  std::string join(std::vector<Term> terms) {
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
  std::string grouped(std::vector<Term> terms) {
    std::vector<Term> groups;
    const std::size_t size = (terms.size() + kSumGroups - 1) / kSumGroups;
    for (std::size_t first = 0; first < terms.size(); first += size) {
      std::vector<Term> members(terms.begin() + static_cast<std::ptrdiff_t>(first),
                                terms.begin() + static_cast<std::ptrdiff_t>(
                                                    std::min(first + size, terms.size())));
      Term group;
      group.negative = std::all_of(members.begin(), members.end(),
                                   [](const Term& t) { return t.negative; });
      if (group.negative) {
        for (Term& t : members) t.negative = false;
      }
      group.rest = "(" + join(std::move(members)) + ")";
      groups.push_back(std::move(group));
    }
    return join(std::move(groups));
  }

  std::string sum(ExprId id) {
    std::vector<Term> terms;
    collect_terms(id, false, terms);
    group_coefficients(terms);
    return join(std::move(terms));
  }

  // A temporary where its value is read: a flipped one is negated.
  std::string reference(ExprId id, Context context) {
    if (!flipped_[id]) return name(id);
    ++counts_.add;  // negation
    return context == Context::kFactor ? "(-" + name(id) + ")" : "-" + name(id);
  }

  std::string expression(ExprId id, Context context) {
    id = resolve(id);
    if (named(id)) return reference(id, context);
    const Node& n = g_.node(id);
    switch (n.op) {
      case Op::kConstant: {
        const std::string literal = format_literal(n.value, scalar_);
        return n.value < 0 && context == Context::kFactor ? "(" + literal + ")" : literal;
      }
      case Op::kSymbol: return g_.symbols()[n.symbol].name;
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
      case Op::kShare: break;  // resolved above
      case Op::kSign: break;   // always a temporary
    }
    return "";
  }

  const ExprGraph& g_;
  Scalar scalar_;
  TrigSource trig_;
  // Per node, the workspace's arrays (statement_writer.hpp says what each holds).
  std::vector<int>& uses_;
  std::vector<int>& temporary_;
  std::vector<char>& flipped_;
  std::vector<char>& keep_sign_;
  std::vector<int>& negative_votes_;
  std::vector<char>& prepared_;
  std::vector<char>& visited_;
  std::vector<ExprId> reachable_;      // the nodes the outputs use
  std::vector<ExprId> prepared_list_;  // the nodes prepare() marked
  std::vector<bool> symbol_used_;
  int temporaries_ = 0;
  OpCounts counts_;
};

}  // namespace

void WriterWorkspace::fit(std::size_t nodes) {
  if (uses.size() >= nodes) return;
  for (std::vector<int>* v : {&uses, &temporary, &negative_votes}) v->resize(nodes, 0);
  for (std::vector<char>* v : {&flipped, &keep_sign, &prepared, &visited}) v->resize(nodes, 0);
}

bool WriterWorkspace::all_zero() const {
  const auto zero = [](const auto& v) {
    return std::all_of(v.begin(), v.end(), [](auto x) { return x == 0; });
  };
  return zero(uses) && zero(temporary) && zero(negative_votes) && zero(flipped) &&
         zero(keep_sign) && zero(prepared) && zero(visited);
}

FunctionBody write_statements(const ExprGraph& graph, const std::vector<FunctionOutput>& outputs,
                              Scalar scalar, TrigSource trig, WriterWorkspace& workspace) {
  return StatementWriter(graph, scalar, trig, workspace).write(outputs);
}

FunctionBody write_statements(const ExprGraph& graph, const std::vector<FunctionOutput>& outputs,
                              Scalar scalar, TrigSource trig) {
  WriterWorkspace workspace;
  return write_statements(graph, outputs, scalar, trig, workspace);
}

}  // namespace modelgen::gen
