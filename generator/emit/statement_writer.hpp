// Turns the DAG nodes a generated function needs into straight-line statements: derived leaves
// (sin, cos, sign of joint variables) first, then one temporary per shared subexpression in
// a deterministic topological order, then the outputs. Operation counts are taken from exactly
// the text written.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "generator/emit/number_format.hpp"
#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

struct OpCounts {
  long mul = 0;   ///< multiplications and divisions (1 / x, for transmission efficiencies)
  long add = 0;   ///< additions, subtractions and negations
  long trig = 0;  ///< sin and cos calls
};

struct FunctionOutput {
  std::string target;   ///< e.g. "W[14]"
  ExprId value = 0;
  std::string comment;  ///< written after the first statement of each column, may be empty
};

struct FunctionBody {
  std::vector<std::string> lines;
  OpCounts counts;
};

/// Where sin and cos of the joint variables come from: computed in the body (std::sin,
/// std::cos), or read from the caller's arrays sin_q[i] and cos_q[i].
enum class TrigSource { kCompute, kGiven };

/// One statement from a templates/statements/*.tmpl template ("statements/output"), filled with
/// `values`, without its final newline.
std::string render_statement(std::string_view template_name,
                             const std::vector<std::pair<const char*, std::string>>& values);

/// The per-node scratch arrays of write_statements, kept between the bodies written on one
/// graph: a body reaches a small part of the graph, and allocating and clearing arrays the size
/// of the whole graph for each of the hundred or so bodies of a model was most of the writer's
/// time. Every entry is zero between calls; a call clears only the entries it touched.
struct WriterWorkspace {
  std::vector<int> uses;
  // 0, or k + 1 when the node is the temporary t<k> (a number, not a string per node).
  std::vector<int> temporary;
  std::vector<int> negative_votes;  // negated reads minus the others (the writer's vote())
  std::vector<char> flipped;        // the temporary holds the negated value
  std::vector<char> keep_sign;      // read by a sign or a reciprocal, never flipped
  std::vector<char> prepared;
  std::vector<char> visited;

  /// Grows every array to `nodes` entries (new ones zero).
  void fit(std::size_t nodes);
  /// Whether every entry is zero, as between calls (what the tests of the clearing check).
  bool all_zero() const;
};

FunctionBody write_statements(const ExprGraph& graph, const std::vector<FunctionOutput>& outputs,
                              Scalar scalar, TrigSource trig, WriterWorkspace& workspace);
/// The same with a workspace of its own.
FunctionBody write_statements(const ExprGraph& graph, const std::vector<FunctionOutput>& outputs,
                              Scalar scalar, TrigSource trig = TrigSource::kCompute);

}  // namespace modelgen::gen
