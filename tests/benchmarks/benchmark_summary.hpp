// What the benchmark programs share: main()'s sequence (flags, set-up, registration, the run with
// a summary of ratios and targets after the console output), the runs kept for that summary (the
// median of the repetitions, else the single run), and the registration of multi-threaded code.
#pragma once

#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

namespace modelgen::bench {

/// printf-style formatting into a std::string (at most 255 characters), for summary lines.
template <class... Args>
std::string printf_string(const char* format, Args... args) {
  char text[256];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

/// Per benchmark (function name, e.g. "BM_tx40_identify_wls") the run the summary uses: the
/// median aggregate when there are repetitions (less disturbed by other load on the machine than
/// the mean), else the single run.
class KeptRuns {
 public:
  using Run = benchmark::BenchmarkReporter::Run;

  void add(const Run& run);
  /// nullptr when the benchmark was filtered out or failed.
  const Run* find(const std::string& name) const;
  /// Wall-clock and CPU time in the benchmark's own unit, a counter; NaN when absent.
  double real_time(const std::string& name) const;
  double cpu_time(const std::string& name) const;
  double counter(const std::string& name, const std::string& key) const;
  /// Whether any kept run is a median of repetitions.
  bool any_median() const { return !from_median_.empty(); }

 private:
  std::map<std::string, Run> runs_;
  std::set<std::string> from_median_;
};

/// Prints the summary after the console output.
using Summary = std::function<void(const KeptRuns&, std::ostream&)>;

/// main() of a benchmark program: initialises Google Benchmark from the command line, runs
/// `setup` (builds the workload and registers the benchmarks; an exception ends the program with
/// "<program>: setup failed: <what>" and exit code 1), then runs the benchmarks: console output
/// followed by `summary`, or the library's own reporter for the other formats.
int run_benchmarks(int argc, char** argv, const char* program, const std::function<void()>& setup,
                   const Summary& summary);

/// run_benchmarks() for a program whose benchmarks read one workload built before timing: the
/// set-up default-constructs a Workload (kept until the end), points `workload` at it and calls
/// `register_all`.
template <class Workload>
int run_benchmarks(int argc, char** argv, const char* program, Workload*& workload,
                   const std::function<void()>& register_all, const Summary& summary) {
  std::unique_ptr<Workload> owned;
  const auto setup = [&] {
    owned = std::make_unique<Workload>();
    workload = owned.get();
    register_all();
  };
  return run_benchmarks(argc, argv, program, setup, summary);
}

/// A benchmark to register: its name and its function.
using NamedBenchmark = std::pair<std::string, std::function<void(benchmark::State&)>>;

/// Registers `benchmarks` in this order, in ms, timed by wall clock and by the CPU time of the
/// whole process (for code running several threads).
void register_wall_and_process_cpu_ms(const std::vector<NamedBenchmark>& benchmarks);

}  // namespace modelgen::bench
