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

FunctionBody write_statements(const ExprGraph& graph, const std::vector<FunctionOutput>& outputs,
                              Scalar scalar, TrigSource trig = TrigSource::kCompute);

}  // namespace modelgen::gen
