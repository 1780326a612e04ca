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
#include <optional>

#include "generator/emit/printer.hpp"
#include "generator/emit/statement_writer_impl.hpp"

namespace modelgen::gen {

std::string render_statement(std::string_view template_name,
                             const std::vector<std::pair<const char*, std::string>>& values) {
  Printer printer(embedded_template(template_name));
  for (const auto& [name, value] : values) printer.set(name, value);
  std::string text = printer.render();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

StatementWriter::StatementWriter(const ExprGraph& graph, Scalar scalar, TrigSource trig,
                                 WriterWorkspace& workspace)
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

// The touched entries back to zero: the nodes reached from the outputs, and the negations
// prepare() passed through, which count their uses on what they negate.
StatementWriter::~StatementWriter() {
  for (const std::vector<ExprId>* ids : {&reachable_, &prepared_list_}) {
    for (ExprId id : *ids) {
      uses_[id] = temporary_[id] = negative_votes_[id] = 0;
      flipped_[id] = keep_sign_[id] = prepared_[id] = visited_[id] = 0;
    }
  }
}

FunctionBody StatementWriter::write(const std::vector<FunctionOutput>& outputs) {
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
      body.push_back(
          render_statement("statements/output_named",
                           {{"target", out.target}, {"value", value}, {"comment", out.comment}}));
    }
  }
  FunctionBody result;
  declare_symbols(result.lines);
  result.lines.insert(result.lines.end(), body.begin(), body.end());
  result.counts = counts_;
  return result;
}

// The vote of one printed value (an output or a temporary's definition) for the sign of the
// temporaries it multiplies with a coefficient of +-1 (a coefficient of another size prints
// its sign for free, and so does a sum): `negative` when it prints them negated.
// negative_votes_[t] counts the negated reads of t minus the others.
void StatementWriter::vote(ExprId id, bool negative) {
  if (becomes_temporary(id)) {
    negative_votes_[id] += negative ? 1 : -1;
    return;
  }
  vote_body(id, negative);
}

void StatementWriter::vote_body(ExprId id, bool negative) {
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

void StatementWriter::count_uses(const std::vector<FunctionOutput>& outputs) {
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
void StatementWriter::prepare(ExprId id, std::vector<std::string>& body) {
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
    body.push_back(
        render_statement("statements/sign_of", {{"scalar", scalar_name(scalar_)},
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
    const bool flip =
        negative_votes_[id] >= 2 && !keep_sign_[id] && g_.node(resolve(id)).op == Op::kAdd;
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
    body.push_back(
        render_statement("statements/temporary",
                         {{"scalar", scalar_name(scalar_)}, {"name", name(id)}, {"value", value}}));
  }
}

void StatementWriter::declare_symbols(std::vector<std::string>& lines) {
  const std::string zero = format_literal(0.0, scalar_);
  for (std::size_t s = 0; s < g_.symbols().size(); ++s) {
    if (!symbol_used_[s]) continue;
    const Symbol& symbol = g_.symbols()[s];
    const char* tmpl = nullptr;
    switch (symbol.kind) {
      case SymbolKind::kInput:
        continue;
      case SymbolKind::kSin:
        tmpl = "statements/sin";
        ++counts_.trig;
        break;
      case SymbolKind::kCos:
        tmpl = "statements/cos";
        ++counts_.trig;
        break;
      case SymbolKind::kSign:
        tmpl = "statements/sign";
        break;
      case SymbolKind::kPositive:
        tmpl = "statements/positive";
        break;
      case SymbolKind::kNegative:
        tmpl = "statements/negative";
        break;
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
