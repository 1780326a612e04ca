// Leaf values of symbolic expressions at a numeric state.

#include "tests/support/symbol_values.hpp"

#include <cmath>
#include <string>

namespace modelgen::test {

std::function<double(const gen::Symbol&)> symbol_values(const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& dq,
                                                        const Eigen::VectorXd& ddq,
                                                        const Eigen::VectorXd& p) {
  return [&q, &dq, &ddq, &p](const gen::Symbol& s) {
    auto input = [&](const std::string& text) {
      const std::size_t open = text.find('[');
      const std::string array = text.substr(0, open);
      const int index = std::stoi(text.substr(open + 1));
      if (array == "q") return q[index];
      if (array == "dq") return dq[index];
      if (array == "ddq") return ddq[index];
      return p[index];
    };
    switch (s.kind) {
      case gen::SymbolKind::kInput: return input(s.name);
      case gen::SymbolKind::kSin: return std::sin(input(s.input));
      case gen::SymbolKind::kCos: return std::cos(input(s.input));
      case gen::SymbolKind::kSign: {
        const double x = input(s.input);
        return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
      }
      case gen::SymbolKind::kPositive: return input(s.input) > 0 ? 1.0 : 0.0;
      case gen::SymbolKind::kNegative: return input(s.input) < 0 ? 1.0 : 0.0;
    }
    return 0.0;
  };
}

}  // namespace modelgen::test
