// Scans the checked-in generated sources for wasted work, independently of the generator: no
// store of a literal zero, no arithmetic on a literal zero, and no sum or difference that is
// zero for every input (an exact cancellation left in the code). The straight-line bodies are
// parsed here by a small expression reader of their own and evaluated at random states; an
// operation whose result is below 1e-12 of the size of its operands at all of them is reported
// with its file, line and text.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

constexpr int kStates = 16;

// A value at every probe state, with the size of the terms that made it (sums of absolute
// values): an exact cancellation leaves the first far below the second.
struct Probe {
  std::vector<double> value = std::vector<double>(kStates, 0.0);
  std::vector<double> size = std::vector<double>(kStates, 0.0);
};

// The inputs of the generated functions at the probe states: q, dq, ddq in a robot's range,
// parameters positive (efficiencies divide), sin_q and cos_q consistent with q, and any other
// array (a local regressor of the drive Jacobians, the drive regressor Y) of either sign.
class Inputs {
 public:
  double at(const std::string& array, int index, int state) {
    if (array == "sin_q") return std::sin(at("q", index, state));
    if (array == "cos_q") return std::cos(at("q", index, state));
    auto& values = arrays_[array];
    const std::size_t slot = static_cast<std::size_t>(index) * kStates + state;
    while (values.size() <= slot) {
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      const double u = unit(random_);
      double v = 0.5 + 1.5 * u;  // parameters
      // Another function's output (a local regressor, the drive regressor Y): either sign.
      if (array != "p" && array != "beta" && array != "theta" && array != "p_standard") {
        v *= unit(random_) < 0.5 ? -1.0 : 1.0;
      }
      if (array == "q") v = -3.0 + 6.0 * u;
      if (array == "dq") v = (unit(random_) < 0.5 ? -1.0 : 1.0) * (0.2 + 2.8 * u);
      if (array == "ddq") v = -10.0 + 20.0 * u;
      values.push_back(v);
    }
    return values[slot];
  }

 private:
  std::mt19937_64 random_{20261202};
  std::map<std::string, std::vector<double>> arrays_;
};

struct Finding {
  std::string what;
};

// Reads and evaluates one statement's expression: + - * / unary -, parentheses, names, array
// elements, literals, std::sin, std::cos, static_cast<T>(...) and the comparisons > < of the
// sign statements.
class ExpressionReader {
 public:
  ExpressionReader(const std::string& text, std::map<std::string, Probe>& names, Inputs& inputs,
                   std::vector<Finding>& findings)
      : text_(text), names_(names), inputs_(inputs), findings_(findings) {}

  Probe read() {
    Probe p = comparison();
    skip_space();
    if (pos_ != text_.size()) fail("unexpected text");
    return p;
  }

 private:
  void skip_space() {
    while (pos_ < text_.size() && text_[pos_] == ' ') ++pos_;
  }
  bool take(const std::string& token) {
    skip_space();
    if (text_.compare(pos_, token.size(), token) != 0) return false;
    pos_ += token.size();
    return true;
  }
  [[noreturn]] void fail(const std::string& why) {
    throw std::runtime_error(why + " at column " + std::to_string(pos_) + " of: " + text_);
  }

  static Probe combine(const Probe& a, const Probe& b, char op) {
    Probe r;
    for (int s = 0; s < kStates; ++s) {
      switch (op) {
        case '+': r.value[s] = a.value[s] + b.value[s]; r.size[s] = a.size[s] + b.size[s]; break;
        case '-': r.value[s] = a.value[s] - b.value[s]; r.size[s] = a.size[s] + b.size[s]; break;
        case '*': r.value[s] = a.value[s] * b.value[s]; r.size[s] = a.size[s] * b.size[s]; break;
        case '/':
          r.value[s] = a.value[s] / b.value[s];
          r.size[s] = a.size[s] / std::abs(b.value[s]);
          break;
        case '>': r.value[s] = a.value[s] > b.value[s]; r.size[s] = 1; break;
        case '<': r.value[s] = a.value[s] < b.value[s]; r.size[s] = 1; break;
      }
    }
    return r;
  }

  // An operation on a literal zero, or a sum whose value cancels at every state.
  void check(const Probe& a, const Probe& b, const Probe& result, char op, std::size_t from) {
    if (op == '>' || op == '<') return;  // the sign statements compare with 0 by design
    if (literal_zero(a) || literal_zero(b)) {
      findings_.push_back({std::string("arithmetic on a literal 0 in '") +
                           text_.substr(from, pos_ - from) + "'"});
    }
    if (op != '+' && op != '-') return;
    for (int s = 0; s < kStates; ++s) {
      if (!(std::abs(result.value[s]) <= 1e-12 * result.size[s]) || result.size[s] == 0) return;
    }
    findings_.push_back({"'" + text_.substr(from, pos_ - from) + "' is zero at every state"});
  }
  static bool literal_zero(const Probe& p) {
    for (int s = 0; s < kStates; ++s) {
      if (p.size[s] != 0) return false;
    }
    return true;
  }

  Probe comparison() {
    const std::size_t from = pos_;
    Probe left = sum();
    for (char op : {'>', '<'}) {
      if (take(std::string(1, op))) {
        const Probe right = sum();
        Probe r = combine(left, right, op);
        check(left, right, r, op, from);
        return r;
      }
    }
    return left;
  }

  Probe sum() {
    skip_space();
    const std::size_t from = pos_;
    Probe left = product();
    while (true) {
      char op = 0;
      if (take("+")) op = '+';
      else if (take("-")) op = '-';
      else return left;
      const Probe right = product();
      Probe r = combine(left, right, op);
      check(left, right, r, op, from);
      left = std::move(r);
    }
  }

  Probe product() {
    skip_space();
    const std::size_t from = pos_;
    Probe left = unary();
    while (true) {
      char op = 0;
      if (take("*")) op = '*';
      else if (take("/")) op = '/';
      else return left;
      const Probe right = unary();
      Probe r = combine(left, right, op);
      check(left, right, r, op, from);
      left = std::move(r);
    }
  }

  Probe unary() {
    if (take("-")) {
      Probe p = unary();
      for (double& v : p.value) v = -v;
      return p;
    }
    return primary();
  }

  Probe call_argument(double (*f)(double)) {
    if (!take("(")) fail("expected (");
    Probe p = comparison();
    if (!take(")")) fail("expected )");
    for (int s = 0; s < kStates; ++s) {
      p.value[s] = f ? f(p.value[s]) : p.value[s];
      p.size[s] = std::abs(p.value[s]);
    }
    return p;
  }

  Probe primary() {
    skip_space();
    if (take("(")) {
      Probe p = comparison();
      if (!take(")")) fail("expected )");
      return p;
    }
    if (take("std::sin")) return call_argument([](double x) { return std::sin(x); });
    if (take("std::cos")) return call_argument([](double x) { return std::cos(x); });
    if (take("static_cast<double>") || take("static_cast<float>")) return call_argument(nullptr);
    if (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) != 0)) {
      std::size_t used = 0;
      const double v = std::stod(text_.substr(pos_), &used);
      pos_ += used;
      if (pos_ < text_.size() && text_[pos_] == 'f') ++pos_;
      Probe p;
      for (int s = 0; s < kStates; ++s) {
        p.value[s] = v;
        p.size[s] = std::abs(v);
      }
      return p;
    }
    std::size_t end = pos_;
    while (end < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[end])) != 0 || text_[end] == '_')) {
      ++end;
    }
    if (end == pos_) fail("expected an operand");
    const std::string name = text_.substr(pos_, end - pos_);
    pos_ = end;
    if (take("[")) {
      std::size_t close = text_.find(']', pos_);
      if (close == std::string::npos) fail("expected ]");
      const int index = std::stoi(text_.substr(pos_, close - pos_));
      pos_ = close + 1;
      Probe p;
      for (int s = 0; s < kStates; ++s) {
        p.value[s] = inputs_.at(name, index, s);
        p.size[s] = std::abs(p.value[s]);
      }
      return p;
    }
    const auto found = names_.find(name);
    if (found == names_.end()) fail("unknown name " + name);
    Probe p = found->second;
    for (int s = 0; s < kStates; ++s) p.size[s] = std::abs(p.value[s]);
    return p;
  }

  const std::string& text_;
  std::size_t pos_ = 0;
  std::map<std::string, Probe>& names_;
  Inputs& inputs_;
  std::vector<Finding>& findings_;
};

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Every statement of every function definition of one source file, with its line number.
void scan_file(const fs::path& path, std::vector<std::string>& problems, int& statements) {
  const std::regex temporary(R"(^\s*const (double|float) (\w+) = (.*);$)");
  const std::regex output(R"(^\s*(\w+)\[(\d+)\] = (.*);$)");
  std::map<std::string, Probe> names;
  Inputs inputs;
  std::istringstream lines(read_file(path));
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.rfind("void ", 0) == 0) names.clear();  // a new function body
    std::smatch m;
    std::string value, target;
    if (std::regex_match(line, m, temporary)) {
      target = m[2];
      value = m[3];
    } else if (std::regex_match(line, m, output)) {
      target = m[1].str() + "[" + m[2].str() + "]";
      value = m[3];
    } else {
      continue;
    }
    ++statements;
    std::vector<Finding> findings;
    try {
      Probe p = ExpressionReader(value, names, inputs, findings).read();
      const bool is_output = m.size() == 4 && line.find("const ") == std::string::npos;
      if (is_output && std::all_of(p.size.begin(), p.size.end(), [](double v) { return v == 0; })) {
        findings.push_back({"stores a literal 0"});
      }
      if (!is_output) names[target] = std::move(p);
    } catch (const std::exception& e) {
      problems.push_back(path.string() + ":" + std::to_string(number) + ": cannot read: " +
                         e.what());
      continue;
    }
    for (const Finding& f : findings) {
      problems.push_back(path.filename().string() + ":" + std::to_string(number) + ": " +
                         target + ": " + f.what);
    }
  }
}

TEST(GeneratedArithmetic, NoZeroStoreNoArithmeticOnZeroNoExactCancellation) {
  std::vector<std::string> problems;
  int statements = 0, files = 0;
  for (const fs::directory_entry& robot : fs::directory_iterator(test::source_path("generated"))) {
    if (!robot.is_directory()) continue;
    for (const fs::directory_entry& file : fs::directory_iterator(robot.path())) {
      const std::string name = file.path().filename().string();
      // The model source holds names and constants, no function bodies.
      if (file.path().extension() != ".cpp" || name == robot.path().filename().string() + ".cpp") {
        continue;
      }
      ++files;
      scan_file(file.path(), problems, statements);
    }
  }
  EXPECT_GT(files, 100);
  EXPECT_GT(statements, 20000);  // the scan read the bodies, not nothing
  std::string report;
  for (std::size_t i = 0; i < problems.size() && i < 40; ++i) report += problems[i] + "\n";
  EXPECT_TRUE(problems.empty()) << problems.size() << " findings, the first:\n" << report;
}

// The scanner finds what it is meant to find: each kind of waste, written by hand.
TEST(GeneratedArithmetic, TheScannerFindsEachKindOfWaste) {
  const fs::path dir = fs::temp_directory_path() / "modelgen_arithmetic_scan";
  fs::create_directories(dir);
  const fs::path file = dir / "waste.cpp";
  std::ofstream(file) << "void f(const double* q, const double* dq, double* W) {\n"
                         "  const double s2 = std::sin(q[1]);\n"
                         "  const double c2 = std::cos(q[1]);\n"
                         "  const double t0 = c2 * dq[0];\n"
                         "  const double t1 = dq[1] * t0;\n"
                         "  W[0] = c2 * (dq[1] * (dq[0] * s2)) - s2 * t1;\n"  // cancels
                         "  W[1] = 0.0;\n"                                     // zero store
                         "  W[2] = t0 + 0.0 * dq[2];\n"                        // literal zero
                         "  W[3] = s2 * s2 + c2 * c2 - 1.0;\n"                 // cancels
                         "  W[4] = c2 * t0 - s2 * t1;\n"                       // fine
                         "}\n";
  std::vector<std::string> problems;
  int statements = 0;
  scan_file(file, problems, statements);
  fs::remove_all(dir);
  EXPECT_EQ(statements, 9);
  std::string all;
  for (const std::string& p : problems) all += p + "\n";
  EXPECT_NE(all.find(":6: W[0]: "), std::string::npos) << all;
  EXPECT_NE(all.find(":7: W[1]: stores a literal 0"), std::string::npos) << all;
  EXPECT_NE(all.find(":8: W[2]: arithmetic on a literal 0"), std::string::npos) << all;
  EXPECT_NE(all.find(":9: W[3]: "), std::string::npos) << all;
  EXPECT_EQ(all.find(":10:"), std::string::npos) << all;
}

}  // namespace
}  // namespace modelgen
