// Expression DAG for the symbolic models: hash-consed nodes (one node per distinct
// subexpression, so shared subexpressions are shared by construction), constants folded,
// neutral and absorbing elements removed, commutative operands in a canonical order, and like
// terms collected. Operands are ordered by structure (canonical_before: constants, symbols by
// name, then operations by height and their arguments), never by node id: ids follow creation
// order, and creation order depends on the order in which a compiler evaluates the arguments of
// a call such as add(mul(a, b), mul(c, d)). Ordering by structure makes the generated code a
// function of the input alone, whichever compiler built modelgen (and never of pointer values
// or hash seeds).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace modelgen::gen {

using ExprId = std::uint32_t;

enum class Op : std::uint8_t {
  kConstant,
  kSymbol,
  kAdd,  // n-ary sum, args in canonical order, no constant zero, no nested sums
  // n-ary product, at most one constant (first), no 0 or 1 constants, no nested products; the
  // other factors in canonical order
  kMul,
  kShare,  // one arg: an intermediate result kept whole, an atom to sums and products
  kSign,   // one arg: -1, 0 or 1 (Coulomb friction of a motor driving several joints)
  kInv,    // one arg: its reciprocal 1 / arg (transmission efficiency, Swevers eq. 8); never
           // of a constant, of a reciprocal or of a product with a constant coefficient
};

/// What a leaf stands for. The statement writer defines derived leaves (sin, cos, sign of a
/// joint variable) once at the top of a function body.
enum class SymbolKind : std::uint8_t {
  kInput,     ///< an array element read directly: q[i], dq[i], ddq[i], p[k]
  kSin,       ///< sin(input)
  kCos,       ///< cos(input)
  kSign,      ///< sign(input), 0 at 0
  kPositive,  ///< 1 if input > 0 else 0
  kNegative,  ///< 1 if input < 0 else 0
};

struct Symbol {
  std::string name;   ///< C++ text of the leaf: "q[0]" for inputs, "s1", "c1", "sg1" for derived
  SymbolKind kind = SymbolKind::kInput;
  std::string input;  ///< for derived symbols: the input they are computed from, e.g. "q[0]"
};

struct Node {
  /// kAdd, kMul and the one-argument operations. The ids live in the graph's argument arena,
  /// which never moves them: the span stays valid as long as the graph, however it grows.
  std::span<const ExprId> args;
  double value = 0;          ///< kConstant
  std::uint32_t symbol = 0;  ///< kSymbol: index into ExprGraph::symbols()
  /// Set by the graph: 0 for leaves, else one more than the highest argument.
  std::uint32_t height = 0;
  Op op = Op::kConstant;
};

class ExprGraph {
 public:
  ExprGraph();

  ExprId constant(double value);
  ExprId zero() const { return zero_; }
  ExprId one() const { return one_; }
  /// The leaf for `symbol`; the same name always gives the same node.
  ExprId symbol(const Symbol& symbol);

  ExprId add(ExprId a, ExprId b);
  ExprId add(std::vector<ExprId> terms);
  ExprId sub(ExprId a, ExprId b);
  ExprId neg(ExprId a);
  ExprId mul(ExprId a, ExprId b);
  ExprId mul(std::vector<ExprId> factors);

  /// `e` as an atom: sums and products that use it do not flatten into it, so it is computed
  /// once and shared, as the intermediate variables of a customized Newton-Euler model
  /// (Khalil & Kleinfinger). Constants, symbols and constant multiples of symbols stay as they
  /// are.
  ExprId share(ExprId e);

  /// sign(e): -1, 0 or +1; folded when e is a constant, and sign(c e) = sign(c) sign(e) for a
  /// constant coefficient c.
  ExprId sign(ExprId e);

  /// 1 / e. Folded: a constant gives its reciprocal (std::logic_error for 0), 1 / (1 / x) gives
  /// x, and 1 / (c x) gives (1 / c) (1 / x), so constant coefficients stay in front where sums
  /// can collect them. Products are not searched for x (1 / x): x / x stays as it is.
  ExprId inv(ExprId e);
  /// a / b as a (1 / b), with the folding of inv().
  ExprId div(ExprId a, ExprId b);

  const Node& node(ExprId id) const { return nodes_[id]; }
  /// The canonical order of operands, a total order on structures: constants by value, then
  /// symbols by name, then operations by height, kind and arguments (lexicographically, in
  /// this order). Two nodes have one structure only if they are one node (hash-consing), so a
  /// comparison descends one path of differing arguments: its cost is the height.
  bool canonical_before(ExprId a, ExprId b) const;
  const std::vector<Symbol>& symbols() const { return symbols_; }
  std::size_t size() const { return nodes_.size(); }

  bool is_constant(ExprId id) const { return nodes_[id].op == Op::kConstant; }
  bool is_zero(ExprId id) const { return id == zero_; }
  double constant_value(ExprId id) const { return nodes_[id].value; }

  /// Numeric value of every node, indexed by ExprId, with each symbol's value given by `leaf`
  /// (for tests and numeric checks of derivations).
  std::vector<double> evaluate(const std::function<double(const Symbol&)>& leaf) const;

 private:
  static std::uint64_t structure_hash(const Node& node);
  static bool same_structure(const Node& a, const Node& b);
  // Hash-consing: the existing node of this structure, or the node added (its arguments, which
  // may point into a caller's buffer, copied into the arena).
  ExprId intern(Node node);
  // `args` copied into the arena: blocks that are never reallocated, so a node costs no
  // allocation of its own and spans into the arena stay valid.
  std::span<const ExprId> store_args(std::span<const ExprId> args);
  ExprId add_terms(std::span<const ExprId> terms);
  ExprId mul_factors(std::span<const ExprId> factors);
  // Grows the open-addressing table (1024 slots, then doubling) and re-inserts every node.
  void grow_index();
  void sort_canonical(std::span<ExprId> ids) const;
  // Splits a term into its constant coefficient and the rest (1 for a constant).
  std::pair<double, ExprId> split_coefficient(ExprId id);

  std::vector<Node> nodes_;
  std::vector<Symbol> symbols_;
  std::vector<std::unique_ptr<ExprId[]>> arg_blocks_;
  std::size_t arg_block_size_ = 0;  // ids in the last block
  std::size_t arg_block_used_ = 0;  // of which taken
  // The hash-consing index: open addressing with linear probing over node ids (kNoNode marks
  // an empty slot), a power-of-two size at most half full. A lookup compares nodes in place, so
  // it allocates nothing; hashes_[id] caches each node's structure_hash.
  static constexpr ExprId kNoNode = ~ExprId{0};
  std::vector<ExprId> slots_;
  std::vector<std::uint64_t> hashes_;
  std::unordered_map<std::string, ExprId> symbol_index_;
  ExprId zero_ = 0;
  ExprId one_ = 0;
};

}  // namespace modelgen::gen
