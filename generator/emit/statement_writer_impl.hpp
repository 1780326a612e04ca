// The writer behind write_statements, shared by its three files: statement_writer.cpp
// schedules (use counts, sign votes, temporaries in emission order, symbol declarations),
// scaled_copy_loop.cpp prints runs of scaled copies as loops and expression_text.cpp prints
// expressions and sums. One writer per body; its scratch arrays are the workspace's.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "generator/emit/statement_writer.hpp"
#include "generator/symbolic/expr.hpp"

namespace modelgen::gen {

class StatementWriter {
 public:
  StatementWriter(const ExprGraph& graph, Scalar scalar, TrigSource trig,
                  WriterWorkspace& workspace);
  StatementWriter(const StatementWriter&) = delete;
  StatementWriter& operator=(const StatementWriter&) = delete;
  ~StatementWriter();

  FunctionBody write(const std::vector<FunctionOutput>& outputs);

 private:
  enum class Context { kTop, kFactor };

  // Runs of at least this many outputs A[a + j] = B[b + j] * f print as one loop.
  static constexpr std::size_t kMinLoop = 4;
  // Sums of at least this many terms print as kSumGroups parenthesized partial sums (below).
  static constexpr std::size_t kLongSum = 32;
  static constexpr std::size_t kSumGroups = 4;

  // An output that is an input array's entry times one value, B[b] * f: f a symbol or a named
  // temporary, and the product positive as printed (a sign-normal -(B[b] * -t) with t stored
  // negated is B[b] * t), so that one text computes every entry of a run.
  struct ScaledCopy {
    std::string target, source;
    long target_index = 0, source_index = 0;
    ExprId factor = 0;
  };

  // One term of a printed sum: its sign and its magnitude's text.
  struct Term {
    bool negative = false;
    double coefficient = 1.0;   // a literal factor of `rest`, printed in front of it
    std::string rest;           // the term without its literal factor (or the literal alone)
    bool literal_sign = false;  // the sign can be folded into a numeric literal ("-2.0 * x")
  };

  // Scheduling (statement_writer.cpp).
  void vote(ExprId id, bool negative);
  void vote_body(ExprId id, bool negative);
  void count_uses(const std::vector<FunctionOutput>& outputs);
  void prepare(ExprId id, std::vector<std::string>& body);
  void declare_symbols(std::vector<std::string>& lines);

  // Runs of scaled copies (scaled_copy_loop.cpp).
  std::optional<ScaledCopy> scaled_copy(const FunctionOutput& out) const;
  std::size_t scaled_copy_run(const std::vector<FunctionOutput>& outputs, std::size_t first,
                              const ScaledCopy& head);
  std::string scaled_copy_loop(const std::vector<FunctionOutput>& outputs, std::size_t first,
                               std::size_t run, const ScaledCopy& head);

  // Expression text (expression_text.cpp).
  std::string factors(const Node& n, bool& negative);
  std::string product_text(double c, const std::string& body, Context context);
  void collect_terms(ExprId id, bool negate, std::vector<Term>& terms);
  void group_coefficients(std::vector<Term>& terms);
  std::string magnitude(const Term& t);
  std::string join(std::vector<Term> terms);
  std::string grouped(std::vector<Term> terms);
  std::string sum(ExprId id);
  std::string reference(ExprId id, Context context);
  std::string expression(ExprId id, Context context);

  // Whether `id`, or a shared intermediate it stands for, is (or will be) a temporary: read by
  // other values too.
  bool read_elsewhere(ExprId id) const {
    for (;;) {
      if (named(id) || becomes_temporary(id)) return true;
      if (g_.node(id).op != Op::kShare) return false;
      id = g_.node(id).args[0];
    }
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

  // The constant coefficient of a product (1 when it has none).
  double coefficient(const Node& n) const {
    return n.op == Op::kMul && g_.is_constant(n.args[0]) ? g_.constant_value(n.args[0]) : 1.0;
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

}  // namespace modelgen::gen
