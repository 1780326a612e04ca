// Runs of outputs A[a + j] = B[b + j] * f, printed as one loop (statements/output_loop*.tmpl)
// instead of one statement per output.

#include "generator/emit/statement_writer_impl.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace modelgen::gen {

namespace {

// "J[12]" as ("J", 12); nullopt for a target or a symbol name of another form.
std::optional<std::pair<std::string, long>> array_entry(const std::string& text) {
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

}  // namespace

std::optional<StatementWriter::ScaledCopy> StatementWriter::scaled_copy(
    const FunctionOutput& out) const {
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
std::size_t StatementWriter::scaled_copy_run(const std::vector<FunctionOutput>& outputs,
                                             std::size_t first, const ScaledCopy& head) {
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
std::string StatementWriter::scaled_copy_loop(const std::vector<FunctionOutput>& outputs,
                                              std::size_t first, std::size_t run,
                                              const ScaledCopy& head) {
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

}  // namespace modelgen::gen
