// Host side of the Cortex-M4 test: reads what the float program printed in qemu
// (main.cpp's format), computes the same states with the checked-in double TX-40 model
// (generated/tx40, checked against the numeric reference and KDL by the generated_* tests) and
// compares. Exit 0 when every value is present once and within tolerance, 1 otherwise.
//
// Tolerance: relative 1e-4 of the largest |value| of the output vector a value belongs to: the
// torque vector of a state, one row of the regressor (the coefficients of one joint's torque).
// An element-wise relative error would fail on entries that are a cancellation of larger terms
// (float rounding of the terms is ~1e-7 of their size, not of the difference); scaled by its
// vector, the error is what a controller sees in that joint's torque.
//
// Usage: cortex_m4_host_reference QEMU_OUTPUT
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "states.hpp"
#include "tx40.hpp"

namespace {

namespace model = modelgen::tx40;
using namespace cortex_m4_test;

constexpr double kTolerance = 1e-4;

static_assert(model::kDof == kJoints, "states.hpp is for the six joints of the TX-40");
static_assert(model::kBaseParams == kBase, "states.hpp has a beta of the wrong length");

// (output name, state, index) -> printed float.
using Key = std::tuple<std::string, int, int>;

struct Printed {
  std::map<Key, float> values;
  bool header = false;
  bool done = false;
  std::vector<std::string> problems;
};

Printed read_output(std::istream& in) {
  Printed printed;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream fields(line);
    std::string kind;
    fields >> kind;
    if (kind == "modelgen-cortex-m4") {
      std::string robot, scalar;
      int states = 0;
      fields >> robot >> scalar >> states;
      printed.header = robot == "tx40" && scalar == "float" && states == kStates;
      if (!printed.header) printed.problems.push_back("unexpected header: " + line);
    } else if (kind == "tau" || kind == "W") {
      int state = -1, index = -1;
      std::string hex;
      fields >> state >> index >> hex;
      const int length = kind == "tau" ? kJoints : kJoints * kBase;
      char* end = nullptr;
      const unsigned long bits = std::strtoul(hex.c_str(), &end, 16);
      if (!fields || hex.size() != 8 || *end != '\0' || state < 0 || state >= kStates ||
          index < 0 || index >= length) {
        printed.problems.push_back("line " + std::to_string(number) + " malformed: " + line);
        continue;
      }
      const std::uint32_t word = static_cast<std::uint32_t>(bits);
      float value;
      std::memcpy(&value, &word, sizeof value);
      if (!printed.values.emplace(Key(kind, state, index), value).second) {
        printed.problems.push_back("line " + std::to_string(number) + " repeats " + kind + " " +
                                   std::to_string(state) + " " + std::to_string(index));
      }
    } else if (kind == "stack") {
      // Stack use, reported by run_m4.cmake.
    } else if (kind == "done") {
      printed.done = true;
    } else if (!line.empty()) {
      printed.problems.push_back("line " + std::to_string(number) + " unexpected: " + line);
    }
  }
  if (!printed.header) printed.problems.push_back("no header line: is this the program's output?");
  if (!printed.done) printed.problems.push_back("no 'done' line: the program stopped early");
  return printed;
}

struct Worst {
  double error = 0;
  std::string where;
};

// Compares one output vector (`count` values from `first` of output `kind`, state `state`)
// with the double `reference`; records problems and the worst normwise error.
void compare(const Printed& printed, const std::string& kind, int state, int first, int count,
             const double* reference, const std::string& where, Worst& worst,
             std::vector<std::string>& problems) {
  double scale = 0;
  for (int k = 0; k < count; ++k) scale = std::fmax(scale, std::fabs(reference[k]));
  double largest = 0;
  int largest_at = first;
  for (int k = 0; k < count; ++k) {
    const auto found = printed.values.find(Key(kind, state, first + k));
    if (found == printed.values.end()) {
      problems.push_back("missing " + kind + " " + std::to_string(state) + " " +
                         std::to_string(first + k));
      continue;
    }
    const double difference = std::fabs(static_cast<double>(found->second) - reference[k]);
    // A zero vector must be printed as zeros; NaN compares as an infinite error.
    const double error = scale > 0 ? difference / scale : (difference == 0 ? 0 : INFINITY);
    if (!(error <= largest)) {
      largest = std::isnan(error) ? INFINITY : error;
      largest_at = first + k;
    }
  }
  if (largest > kTolerance) {
    const auto found = printed.values.find(Key(kind, state, largest_at));
    std::ostringstream message;
    message.precision(9);
    message << where << ": " << kind << "[" << largest_at << "] is " << found->second
            << " on the target, " << reference[largest_at - first] << " on the host: error "
            << largest << " of the vector's largest |value| " << scale << " (tolerance "
            << kTolerance << ")";
    problems.push_back(message.str());
  }
  if (largest >= worst.error) worst = {largest, where};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: cortex_m4_host_reference QEMU_OUTPUT\n";
    return 2;
  }
  std::ifstream file(argv[1]);
  if (!file) {
    std::cerr << "cortex_m4_host_reference: cannot read " << argv[1] << "\n";
    return 2;
  }
  Printed printed = read_output(file);
  std::vector<std::string> problems = printed.problems;

  double beta[kBase];
  for (int k = 0; k < kBase; ++k) beta[k] = kBeta[k];
  Worst tau_worst, w_worst;
  for (int state = 0; state < kStates; ++state) {
    double q[kJoints], dq[kJoints], ddq[kJoints];
    for (int j = 0; j < kJoints; ++j) {
      q[j] = kQ[state][j];
      dq[j] = kDq[state][j];
      ddq[j] = kDdq[state][j];
    }
    double tau[kJoints];
    model::inverse_dynamics(q, dq, ddq, beta, tau);
    compare(printed, "tau", state, 0, kJoints, tau, "state " + std::to_string(state), tau_worst,
            problems);
    std::vector<double> w(kJoints * kBase);
    model::idim_regressor(q, dq, ddq, w.data());
    for (int row = 0; row < kJoints; ++row) {
      compare(printed, "W", state, row * kBase, kBase, w.data() + row * kBase,
              "state " + std::to_string(state) + " row " + std::to_string(row), w_worst,
              problems);
    }
  }
  const std::size_t expected = kStates * (kJoints + kJoints * kBase);
  std::printf("compared %zu of %zu expected values (tau and W of %d states) with the host "
              "double model\n", printed.values.size(), expected, kStates);
  std::printf("inverse_dynamics: largest error %.2e of max|tau| (%s)\n", tau_worst.error,
              tau_worst.where.c_str());
  std::printf("idim_regressor: largest error %.2e of max|W row| (%s)\n", w_worst.error,
              w_worst.where.c_str());
  if (printed.values.size() != expected && problems.empty()) {
    problems.push_back("unexpected number of values");
  }
  for (const std::string& problem : problems) std::printf("MISMATCH %s\n", problem.c_str());
  return problems.empty() ? 0 : 1;
}
