// The benchmark programs' shared main(), the runs kept for their summaries and the console
// reporter that prints them.

#include "tests/benchmarks/benchmark_summary.hpp"

#include <unistd.h>

#include <exception>
#include <iostream>
#include <limits>
#include <string_view>

namespace modelgen::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The summary only makes sense on the console; other formats get the library's reporter.
bool console_format(int argc, char** argv) {
  constexpr std::string_view kFlag = "--benchmark_format=";
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.substr(0, kFlag.size()) == kFlag) return arg.substr(kFlag.size()) == "console";
  }
  return true;
}

// Google Benchmark's console output, then the summary of the kept runs.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  SummaryReporter(OutputOptions options, const Summary& summary)
      : ConsoleReporter(options), summary_(summary) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) kept_.add(run);
    ConsoleReporter::ReportRuns(runs);
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    summary_(kept_, GetOutputStream());
    GetOutputStream().flush();
  }

 private:
  const Summary& summary_;
  KeptRuns kept_;
};

}  // namespace

void KeptRuns::add(const Run& run) {
  if (run.error_occurred) return;
  const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
  if (run.run_type == Run::RT_Aggregate && !median) return;  // mean, stddev, cv
  const std::string& name = run.run_name.function_name;
  if (!median && from_median_.count(name) != 0) return;
  runs_.insert_or_assign(name, run);
  if (median) from_median_.insert(name);
}

const KeptRuns::Run* KeptRuns::find(const std::string& name) const {
  const auto it = runs_.find(name);
  return it == runs_.end() ? nullptr : &it->second;
}

double KeptRuns::real_time(const std::string& name) const {
  const Run* run = find(name);
  return run == nullptr ? kNaN : run->GetAdjustedRealTime();
}

double KeptRuns::cpu_time(const std::string& name) const {
  const Run* run = find(name);
  return run == nullptr ? kNaN : run->GetAdjustedCPUTime();
}

double KeptRuns::counter(const std::string& name, const std::string& key) const {
  const Run* run = find(name);
  if (run == nullptr) return kNaN;
  const auto it = run->counters.find(key);
  return it == run->counters.end() ? kNaN : static_cast<double>(it->second);
}

int run_benchmarks(int argc, char** argv, const char* program, const std::function<void()>& setup,
                   const Summary& summary) {
  const bool console = console_format(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  try {
    setup();
  } catch (const std::exception& e) {
    std::cerr << program << ": setup failed: " << e.what() << "\n";
    return 1;
  }
  if (console) {
    SummaryReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                                                   : benchmark::ConsoleReporter::OO_Tabular,
                             summary);
    benchmark::RunSpecifiedBenchmarks(&reporter);
  } else {
    benchmark::RunSpecifiedBenchmarks();
  }
  benchmark::Shutdown();
  return 0;
}

void register_wall_and_process_cpu_ms(const std::vector<NamedBenchmark>& benchmarks) {
  for (const auto& [name, function] : benchmarks) {
    benchmark::RegisterBenchmark(name.c_str(), function)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->UseRealTime();
  }
}

}  // namespace modelgen::bench
