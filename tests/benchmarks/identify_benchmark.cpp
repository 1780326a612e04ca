// Speed and memory of identification (Gautier & Briot eq. 15-20) on the TX-40: IDIM-WLS with
// 100 000 samples of a Fourier trajectory (Swevers eq. 15-17) and simulated torques, through the
// checked-in generated model (what ships) and, on fewer samples, the numeric reference model.
// Building the stacked W, the fit alone and identify() end to end are timed separately; peak
// memory (ru_maxrss) is reported as counters. After the runs a summary prints the targets.

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Core>

#include "generated/kr150/kr150.hpp"
#include "generated/tx40/tx40.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/signal/prepare.hpp"
#include "tests/benchmarks/benchmark_summary.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::bench {
namespace {

constexpr Eigen::Index kSamples = 100000;         // the problem size
constexpr Eigen::Index kReferenceSamples = 2000;  // the reference regressor is ~500x slower
constexpr double kNoise[6] = {2.0, 2.0, 1.0, 0.3, 0.3, 0.1};  // N m per joint

// Peak resident memory of the process so far, MB (Linux reports ru_maxrss in KiB).
double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// One 10 s period of a five-harmonic Fourier trajectory, sampled so that it has `samples`
// samples, with torques from known base parameters plus Gaussian noise.
Trajectory simulated(const IdentificationModel& model, const Eigen::VectorXd& beta,
                     Eigen::Index samples, std::uint64_t seed) {
  test::Random random(seed);
  FourierTrajectory fourier;
  fourier.period = 10.0;
  fourier.q0 = Eigen::VectorXd::Zero(model.dof());
  fourier.a.resize(model.dof(), 5);
  fourier.b.resize(model.dof(), 5);
  for (Eigen::Index j = 0; j < model.dof(); ++j) {
    for (Eigen::Index l = 0; l < 5; ++l) {
      fourier.a(j, l) = random.uniform(-0.5, 0.5);
      fourier.b(j, l) = random.uniform(-0.5, 0.5);
    }
  }
  Trajectory x = sample(fourier, fourier.period / static_cast<double>(samples), fourier.period);
  x.source = "simulated";
  const int n = model.dof();
  double q[16], dq[16], ddq[16], tau[16];
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    for (int j = 0; j < n; ++j) {
      q[j] = x.q(s, j);
      dq[j] = x.dq(s, j);
      ddq[j] = x.ddq(s, j);
    }
    model.inverse_dynamics(q, dq, ddq, beta.data(), tau);
    for (int j = 0; j < n; ++j) x.tau(s, j) = tau[j] + kNoise[j] * random.normal();
  }
  return x;
}

// The models and data, built once before timing.
struct Workload {
  GeneratedModel<tx40::Model> generated;
  std::unique_ptr<ReferenceModel> reference;
  Eigen::VectorXd beta;
  std::vector<Trajectory> data, reference_data;

  Workload() {
    const modelgen::RobotModel description =
        modelgen::load_robot(test::source_path("robots/tx40.yaml"));
    reference = std::make_unique<ReferenceModel>(description.name, description.tree);
    test::Random random(2024);
    const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
    beta.resize(generated.num_base_params());
    generated.base_from_standard(p.data(), beta.data());
    data.push_back(simulated(generated, beta, kSamples, 1));
    reference_data.push_back(simulated(*reference, beta, kReferenceSamples, 1));
  }
};

Workload* workload = nullptr;

// The stacked IDIM of a user calling fit_wls: one row per joint and sample, one group per joint.
struct Stacked {
  Eigen::MatrixXd W;
  Eigen::VectorXd tau;
  std::vector<int> group;
};

Stacked build_stacked(const IdentificationModel& model, const Trajectory& x) {
  const int n = model.dof(), nb = model.num_base_params();
  const Eigen::Index samples = x.t.size();
  Stacked out;
  out.W.resize(samples * n, nb);
  out.tau.resize(samples * n);
  out.group.resize(static_cast<std::size_t>(samples * n));
  std::vector<double> row(static_cast<std::size_t>(n) * nb);
  double q[16], dq[16], ddq[16];
  for (Eigen::Index s = 0; s < samples; ++s) {
    for (int j = 0; j < n; ++j) {
      q[j] = x.q(s, j);
      dq[j] = x.dq(s, j);
      ddq[j] = x.ddq(s, j);
    }
    model.regressor(q, dq, ddq, row.data());
    for (int i = 0; i < n; ++i) {
      for (int b = 0; b < nb; ++b) out.W(s * n + i, b) = row[i * nb + b];
      out.tau[s * n + i] = x.tau(s, i);
      out.group[s * n + i] = i;
    }
  }
  return out;
}

// Peak resident memory right after the set-up (models and data), MB.
double setup_peak_mb = 0;

// ru_maxrss only grows: growth_MB is the peak above the set-up, over everything run so far in
// the process. Run one benchmark per process (--benchmark_filter) for its own figure.
void set_memory_counters(benchmark::State& state) {
  const double peak = peak_rss_mb();
  state.counters["peak_MB"] = peak;
  state.counters["growth_MB"] = peak - setup_peak_mb;
}

// The regressor alone over every sample, into one small buffer: the part of identify() that
// building W costs when W is not stored.
void BM_tx40_regressor_pass(benchmark::State& state) {
  const IdentificationModel& model = workload->generated;
  const Trajectory& x = workload->data[0];
  const int n = model.dof();
  std::vector<double> row(static_cast<std::size_t>(n * model.num_base_params()));
  double q[16], dq[16], ddq[16];
  for (auto _ : state) {
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      for (int j = 0; j < n; ++j) {
        q[j] = x.q(s, j);
        dq[j] = x.dq(s, j);
        ddq[j] = x.ddq(s, j);
      }
      model.regressor(q, dq, ddq, row.data());
      benchmark::DoNotOptimize(row.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * kSamples);
  set_memory_counters(state);
}

void BM_tx40_build_W(benchmark::State& state) {
  for (auto _ : state) {
    Stacked stacked = build_stacked(workload->generated, workload->data[0]);
    benchmark::DoNotOptimize(stacked.W.data());
  }
  state.SetItemsProcessed(state.iterations() * kSamples);
  set_memory_counters(state);
}

void BM_tx40_fit_wls(benchmark::State& state) {
  const Stacked stacked = build_stacked(workload->generated, workload->data[0]);
  for (auto _ : state) {
    LeastSquaresResult fit =
        fit_wls(stacked.W, stacked.tau, stacked.group, workload->generated.base_param_names());
    benchmark::DoNotOptimize(fit.value.data());
  }
  state.SetItemsProcessed(state.iterations() * kSamples);
  set_memory_counters(state);
}

void identify_benchmark(benchmark::State& state, const IdentificationModel& model,
                        const std::vector<Trajectory>& data, Method method) {
  double error = 0;
  for (auto _ : state) {
    Identification id = identify(model, data, method);
    error = test::relative_error(id.fit.value, workload->beta);
    benchmark::DoNotOptimize(id.fit.value.data());
  }
  state.SetItemsProcessed(state.iterations() * data[0].t.size());
  state.counters["beta_err"] = error;  // relative, infinity norm: the noise shows here
  set_memory_counters(state);
}

void BM_tx40_identify_wls(benchmark::State& state) {
  identify_benchmark(state, workload->generated, workload->data, Method::kWls);
}
void BM_tx40_identify_ols(benchmark::State& state) {
  identify_benchmark(state, workload->generated, workload->data, Method::kOls);
}
void BM_tx40_identify_pim_wls(benchmark::State& state) {
  identify_benchmark(state, workload->generated, workload->data, Method::kPimWls);
}
void BM_tx40_reference_identify_wls(benchmark::State& state) {
  identify_benchmark(state, *workload->reference, workload->reference_data, Method::kWls);
}

// The README's first command without its printing: the bundled KR150 run (1000 samples with
// dq, ddq) read from CSV, prepared, and fitted by IDIM-WLS with the generated model.
void BM_kr150_bundled_pipeline(benchmark::State& state) {
  const GeneratedModel<kr150::Model> model;
  const std::string path = test::source_path("robots/data/kr150/excitation.csv");
  for (auto _ : state) {
    PreparedExperiment prepared = prepare_experiment(io::read_trajectory_csv(path, model.dof()),
                                                     model.drive_chain(), PreparationOptions());
    Identification id = identify(model, {prepared.data}, Method::kWls);
    benchmark::DoNotOptimize(id.fit.value.data());
  }
  set_memory_counters(state);
}

// Registration order is run order: identify() first, so that its memory counters are not
// hidden under the peak of the benchmarks that keep a whole stacked W.
void register_all() {
  register_wall_and_process_cpu_ms(
      {{"BM_tx40_identify_wls", BM_tx40_identify_wls},
       {"BM_tx40_identify_ols", BM_tx40_identify_ols},
       {"BM_tx40_identify_pim_wls", BM_tx40_identify_pim_wls},
       {"BM_tx40_reference_identify_wls", BM_tx40_reference_identify_wls},
       {"BM_tx40_regressor_pass", BM_tx40_regressor_pass},
       {"BM_tx40_build_W", BM_tx40_build_W},
       {"BM_tx40_fit_wls", BM_tx40_fit_wls},
       {"BM_kr150_bundled_pipeline", BM_kr150_bundled_pipeline}});
}

// After the console output: per-sample times, the reference/generated ratio and the targets.
// Times are wall-clock (identify and the fit use two threads) and CPU time of the process (both
// threads), the median when there are repetitions; the unit is ms for every benchmark here.
void print_summary(const KeptRuns& runs, std::ostream& out) {
  // CPU time per sample: the reference's 2000 samples run in one thread, 100 000 in two.
  const double per_sample_ref =
      runs.cpu_time("BM_tx40_reference_identify_wls") / static_cast<double>(kReferenceSamples);
  const double per_sample_gen =
      runs.cpu_time("BM_tx40_identify_wls") / static_cast<double>(kSamples);
  out << "\nTX-40, 61 base parameters, " << kSamples << " samples"
      << (runs.any_median() ? ", median of the repetitions" : "") << "\n";
  for (const char* name :
       {"BM_tx40_regressor_pass", "BM_tx40_build_W", "BM_tx40_fit_wls", "BM_tx40_identify_wls",
        "BM_tx40_identify_ols", "BM_tx40_identify_pim_wls"}) {
    if (runs.find(name) == nullptr) continue;  // filtered out
    out << printf_string("  %-32s wall %8.1f ms, CPU %8.1f ms, peak %5.0f MB, growth %5.0f MB\n",
                         name, runs.real_time(name), runs.cpu_time(name),
                         runs.counter(name, "peak_MB"), runs.counter(name, "growth_MB"));
  }
  if (!std::isnan(per_sample_ref) && !std::isnan(per_sample_gen)) {
    out << printf_string(
        "  identify WLS, CPU per sample: generated %.2f us, reference %.1f us: ratio %.0fx\n",
        per_sample_gen * 1e3, per_sample_ref * 1e3, per_sample_ref / per_sample_gen);
  }
  const double wls = runs.real_time("BM_tx40_identify_wls");
  if (!std::isnan(wls)) {
    out << printf_string("Target: IDIM-WLS, 100 000 samples, under 100 ms: %.1f ms, %s\n", wls,
                         wls < 100 ? "met" : "MISSED");
  }
}

}  // namespace
}  // namespace modelgen::bench

int main(int argc, char** argv) {
  using namespace modelgen::bench;
  const auto register_after_setup = [] {
    setup_peak_mb = peak_rss_mb();
    register_all();
  };
  return run_benchmarks(argc, argv, "identify_benchmark", workload, register_after_setup,
                        print_summary);
}
