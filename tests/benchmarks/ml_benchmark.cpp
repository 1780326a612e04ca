// Speed of the maximum-likelihood load identification of Swevers et al. 2002 (approach 3, eq. 18:
// the load, Rv, Rc and Rz of axes 3-6, 22 unknowns) on the period-averaged KR150 experiment of
// tests/support/kr150_load_scenario.hpp (Table 1 excitation, 1540 samples, Table 2 load): fit_ml
// with the generated analytic Jacobians (GeneratedDriveModel<kr150::Model>, as shipped) and with
// the reference drive model's hand-written one, against the same fit by Ceres automatic
// differentiation (AutoDiffCostFunction blocks over the residuals written for Jets). Whole fits,
// one residual + Jacobian evaluation and the binding of the samples are timed separately.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <ceres/ceres.h>
#include <Eigen/Core>

#include "generated/kr150/kr150.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/identifiability.hpp"
#include "modelgen/ml/linear_route.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"
#include "tests/benchmarks/benchmark_summary.hpp"
#include "tests/support/kr150_load_scenario.hpp"
#include "tests/support/ml_residuals_direct.hpp"

namespace modelgen::bench {
namespace {

constexpr int kUnknowns = 22;        // approach 3 on axes 3-6: 10 load parameters, Rv, Rc, Rz of 4
constexpr double kAgreement = 1e-6;  // relative, per parameter: the variants' fitted loads

// The residuals of MlProblem's samples [begin, end) written directly, for Ceres' automatic
// differentiation (the problem supplies the known values, data, weights and axes only).
struct BlockResiduals {
  const MlProblem* problem;
  const ReferenceDriveModel* model;
  Eigen::Index begin, end;

  template <class T>
  bool operator()(const T* theta1, T* residuals) const {
    test::direct_ml_residuals(*problem, *model, theta1, begin, end, residuals);
    return true;
  }
};

// Eq. 18 over `problem`'s samples as AutoDiffCostFunction blocks, the blocks fit_ml uses.
class AutodiffResiduals {
 public:
  AutodiffResiduals(const MlProblem& problem, const ReferenceDriveModel& model,
                    int samples_per_block) {
    if (problem.num_unknowns() != kUnknowns) {
      throw std::runtime_error("the autodiff variant is compiled for " + std::to_string(kUnknowns) +
                               " unknowns, the problem has " +
                               std::to_string(problem.num_unknowns()));
    }
    const int rows_per_sample = static_cast<int>(problem.axes().size());
    for (Eigen::Index begin = 0; begin < problem.num_samples(); begin += samples_per_block) {
      const Eigen::Index end = std::min(problem.num_samples(), begin + samples_per_block);
      blocks_.push_back(
          std::make_unique<ceres::AutoDiffCostFunction<BlockResiduals, ceres::DYNAMIC, kUnknowns>>(
              new BlockResiduals{&problem, &model, begin, end},
              static_cast<int>(end - begin) * rows_per_sample));
    }
  }

  const std::vector<std::unique_ptr<ceres::CostFunction>>& blocks() const { return blocks_; }

  // Residuals and, when J is not null, their Jacobian (residuals x unknowns), block after block
  // in one thread as MlProblem::evaluate does.
  void evaluate(const Eigen::VectorXd& theta1, Eigen::VectorXd& residuals,
                Eigen::MatrixXd* J) const {
    Eigen::Index rows = 0;
    for (const auto& block : blocks_) rows += block->num_residuals();
    residuals.resize(rows);
    Eigen::Matrix<double, Eigen::Dynamic, kUnknowns, Eigen::RowMajor> jacobian;
    if (J != nullptr) jacobian.resize(rows, kUnknowns);
    const double* parameters[1] = {theta1.data()};
    double* r = residuals.data();
    double* jacobians[1] = {jacobian.data()};
    for (const auto& block : blocks_) {
      block->Evaluate(parameters, r, J != nullptr ? jacobians : nullptr);
      r += block->num_residuals();
      if (J != nullptr) jacobians[0] += Eigen::Index{block->num_residuals()} * kUnknowns;
    }
    if (J != nullptr) *J = jacobian;
  }

 private:
  std::vector<std::unique_ptr<ceres::CostFunction>> blocks_;
};

// The Levenberg-Marquardt settings of fit_ml (runtime/src/ml/fit.cpp, which does not export
// them); the start-up check notes when the two no longer take the same number of iterations.
ceres::Solver::Options fit_ml_solver_options(const MlFitOptions& options) {
  ceres::Solver::Options out;  // trust region with Levenberg-Marquardt by default, as fit_ml
  out.linear_solver_type = ceres::DENSE_QR;
  out.max_num_iterations = options.max_iterations;
  out.num_threads = std::max(1, options.threads);
  out.function_tolerance = out.parameter_tolerance = 1e-12;
  out.gradient_tolerance = 1e-14;
  out.logging_type = ceres::SILENT;
  return out;
}

// Approach 3 as fit_ml does it, with every Jacobian of eq. 18 from automatic differentiation: the
// linear initial guess (shared: it is the linear model's regressor, no Jacobian of eq. 18), the
// rank at the initial guess, Levenberg-Marquardt, and the standard deviations s^2 (J^T J)^-1 from
// ceres::Covariance at the optimum. Every unknown must be identifiable (true for this scenario).
MlFitResult fit_ml_autodiff(MlProblem& problem, const AutodiffResiduals& cost,
                            const MlFitOptions& options = {}) {
  MlFitResult result;
  result.names = problem.unknown_names();
  problem.set_values(linear_route(problem, options.rank_tolerance).values);
  result.initial = problem.initial();
  Eigen::VectorXd residuals;
  Eigen::MatrixXd J;
  cost.evaluate(result.initial, residuals, &J);
  result.identifiability = identifiability(J, result.names, options.rank_tolerance);
  if (result.identifiability.rank != kUnknowns) {
    throw std::runtime_error("autodiff variant: rank " +
                             std::to_string(result.identifiability.rank) + " at the initial guess");
  }
  result.initial_cost = 0.5 * residuals.squaredNorm();

  Eigen::VectorXd theta1 = result.initial;
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem solver_problem(problem_options);
  for (const auto& block : cost.blocks()) {
    solver_problem.AddResidualBlock(block.get(), nullptr, theta1.data());
  }
  ceres::Solver::Summary summary;
  ceres::Solve(fit_ml_solver_options(options), &solver_problem, &summary);
  if (summary.termination_type == ceres::FAILURE) {
    throw std::runtime_error("autodiff variant: " + summary.message);
  }
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.solve_seconds = summary.minimizer_time_in_seconds;
  result.solver_report = summary.BriefReport();

  cost.evaluate(theta1, residuals, nullptr);
  result.final_cost = 0.5 * residuals.squaredNorm();
  const double s2 = residuals.squaredNorm() / static_cast<double>(residuals.size() - kUnknowns);
  result.residual_std_dev = std::sqrt(s2);
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.num_threads = std::max(1, options.threads);
  ceres::Covariance covariance(covariance_options);
  Eigen::Matrix<double, kUnknowns, kUnknowns, Eigen::RowMajor> C;
  const std::vector<std::pair<const double*, const double*>> block = {
      {theta1.data(), theta1.data()}};
  if (!covariance.Compute(block, &solver_problem) ||
      !covariance.GetCovarianceBlock(theta1.data(), theta1.data(), C.data())) {
    throw std::runtime_error("autodiff variant: ceres::Covariance failed");
  }
  result.std_dev = (s2 * C.diagonal()).cwiseSqrt();
  result.value = theta1;
  result.all_values = problem.with_unknowns(theta1);
  result.rms_error = problem.torque_errors(result.all_values).colwise().norm().transpose() /
                     std::sqrt(static_cast<double>(problem.num_samples()));

  // The load: the unknowns numbered past the drive model's parameters.
  const int P = problem.model().num_params();
  std::array<double, kLoadParams> load{}, load_sd{};
  for (int u = 0; u < kUnknowns; ++u) {
    const int k = problem.unknown_indices()[u];
    if (k < P) continue;
    result.has_load = true;
    load[static_cast<size_t>(k - P)] = theta1[u];
    load_sd[static_cast<size_t>(k - P)] = result.std_dev[u];
  }
  result.load = LoadParameters::from_vector(load.data());
  result.load_std_dev = LoadParameters::from_vector(load_sd.data());
  result.load_warnings = physical_consistency_warnings(result.load);
  return result;
}

// max_k |a_k - b_k| / |b_k|.
double max_relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return ((a - b).cwiseAbs().array() / b.cwiseAbs().array()).maxCoeff();
}

Eigen::VectorXd load_vector(const LoadParameters& load) {
  const std::array<double, kLoadParams> v = load.to_vector();
  return Eigen::Map<const Eigen::VectorXd>(v.data(), kLoadParams);
}

// The scenario, the two drive models, a problem on each, the autodiff residuals (on the reference
// problem: the reference drive model is the one templated for Jets), built once before timing.
struct Workload {
  test::Kr150LoadScenario scenario{true};
  GeneratedDriveModel<kr150::Model> generated_model;
  MlSetup setup;
  Eigen::VectorXd start;
  std::unique_ptr<MlProblem> generated, reference;
  std::unique_ptr<AutodiffResiduals> autodiff;
  Eigen::VectorXd theta1_initial;  // after the linear initial guess: where evaluate() is timed

  Workload() {
    if (generated_model.param_names() != scenario.model->param_names()) {
      throw std::runtime_error(
          "the generated KR150 drive model names its parameters otherwise "
          "than the reference drive model of robots/kr150.yaml");
    }
    setup.unknown = scenario.unknowns({2, 3, 4, 5});
    setup.payload_link = 7;
    start = scenario.start(setup.unknown);
    generated =
        std::make_unique<MlProblem>(generated_model, std::vector{scenario.data}, setup, start);
    reference =
        std::make_unique<MlProblem>(*scenario.model, std::vector{scenario.data}, setup, start);
    autodiff =
        std::make_unique<AutodiffResiduals>(*reference, *scenario.model, setup.samples_per_block);
    generated->set_values(linear_route(*generated).values);
    theta1_initial = generated->initial();
    generated->set_values(start);
    check();
  }

  // The variants must compute the same thing: the Jacobians at the initial guess, and the fitted
  // loads within kAgreement; otherwise the program stops (run_benchmarks prints the message).
  void check() {
    Eigen::VectorXd r_generated, r_autodiff;
    Eigen::MatrixXd J_generated, J_autodiff;
    generated->evaluate(theta1_initial, r_generated, &J_generated);
    autodiff->evaluate(theta1_initial, r_autodiff, &J_autodiff);
    double jacobian = 0;
    for (int u = 0; u < kUnknowns; ++u) {
      jacobian =
          std::max(jacobian, (J_generated.col(u) - J_autodiff.col(u)).lpNorm<Eigen::Infinity>() /
                                 J_autodiff.col(u).lpNorm<Eigen::Infinity>());
    }
    const MlFitResult fit_generated = fit_ml(*generated);
    const MlFitResult fit_reference = fit_ml(*reference);
    reference->set_values(start);
    const MlFitResult fit_autodiff = fit_ml_autodiff(*reference, *autodiff);
    generated->set_values(start);
    reference->set_values(start);
    const Eigen::VectorXd load = load_vector(fit_autodiff.load);
    const double load_generated = max_relative_difference(load_vector(fit_generated.load), load);
    const double load_reference = max_relative_difference(load_vector(fit_reference.load), load);
    std::cerr << printf_string(
                     "check: Jacobian at the initial guess, generated vs autodiff: %.1e "
                     "(relative, per column)\n",
                     jacobian)
              << printf_string(
                     "check: fitted load vs autodiff, relative per parameter: generated %.1e, "
                     "reference %.1e\n",
                     load_generated, load_reference)
              << printf_string(
                     "check: all 22 unknowns: generated %.1e, reference %.1e; their standard "
                     "deviations: %.1e, %.1e\n",
                     max_relative_difference(fit_generated.value, fit_autodiff.value),
                     max_relative_difference(fit_reference.value, fit_autodiff.value),
                     max_relative_difference(fit_generated.std_dev, fit_autodiff.std_dev),
                     max_relative_difference(fit_reference.std_dev, fit_autodiff.std_dev))
              << printf_string("check: LM iterations: generated %d, reference %d, autodiff %d\n",
                               fit_generated.iterations, fit_reference.iterations,
                               fit_autodiff.iterations);
    if (fit_reference.iterations != fit_autodiff.iterations) {
      std::cerr << "note: fit_ml and the autodiff fit take different numbers of iterations on the "
                   "same drive model: have fit_ml's solver options changed?\n";
    }
    if (!(jacobian < 1e-9) || !(load_generated < kAgreement) || !(load_reference < kAgreement) ||
        !fit_generated.converged || !fit_reference.converged || !fit_autodiff.converged) {
      throw std::runtime_error(
          "the variants disagree (see the check lines above): timing them would measure a wrong "
          "computation");
    }
  }
};

Workload* workload = nullptr;

// One way to compute the fit: its problem, the whole fit, one residual + Jacobian evaluation.
struct Variant {
  std::string name;
  MlProblem* problem;
  std::function<MlFitResult()> fit;
  std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::MatrixXd*)> evaluate;
};

std::vector<Variant> variants() {
  Workload& w = *workload;
  const auto evaluate = [](const auto* problem) {
    return [problem](const Eigen::VectorXd& theta1, Eigen::VectorXd& r, Eigen::MatrixXd* J) {
      problem->evaluate(theta1, r, J);
    };
  };
  return {
      {"generated", w.generated.get(), [&w] { return fit_ml(*w.generated); },
       evaluate(w.generated.get())},
      {"reference", w.reference.get(), [&w] { return fit_ml(*w.reference); },
       evaluate(w.reference.get())},
      {"autodiff", w.reference.get(), [&w] { return fit_ml_autodiff(*w.reference, *w.autodiff); },
       evaluate(w.autodiff.get())}};
}

void set_size_counters(benchmark::State& state) {
  state.counters["samples"] = static_cast<double>(workload->generated->num_samples());
  state.counters["unknowns"] = workload->generated->num_unknowns();
}

// One whole approach-3 fit per iteration, from the same start; counters per fit: LM iterations,
// Ceres' minimizer time in all and per LM iteration.
void fit_benchmark(benchmark::State& state, const Variant& variant) {
  double iterations = 0, minimizer_seconds = 0;
  for (auto _ : state) {
    variant.problem->set_values(workload->start);
    const MlFitResult result = variant.fit();
    benchmark::DoNotOptimize(result.value.data());
    iterations += result.iterations;
    minimizer_seconds += result.solve_seconds;
  }
  variant.problem->set_values(workload->start);
  state.counters["lm_iterations"] =
      benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
  state.counters["lm_ms"] =
      benchmark::Counter(1e3 * minimizer_seconds, benchmark::Counter::kAvgIterations);
  state.counters["ms_per_lm_iteration"] = 1e3 * minimizer_seconds / std::max(1.0, iterations);
  set_size_counters(state);
}

// One residual + Jacobian evaluation of the whole problem (6160 x 22) at the initial guess, in
// one thread: what an LM iteration's Jacobian costs (Ceres spreads it over its threads).
void evaluate_benchmark(benchmark::State& state, const Variant& variant) {
  Eigen::VectorXd residuals;
  Eigen::MatrixXd J;
  for (auto _ : state) {
    variant.evaluate(workload->theta1_initial, residuals, &J);
    benchmark::DoNotOptimize(J.data());
  }
  set_size_counters(state);
}

// One pass of the drive model over the bound samples at the initial guess's theta, as
// MlProblem's blocks call it (through DriveModel): torque_jacobian (`jacobian`) or torque alone
// (the residual-only evaluations of Levenberg-Marquardt's trial steps). No chain rule, no
// weighting: the drive model's own share of an evaluation.
void drive_model_benchmark(benchmark::State& state, const MlProblem& problem, bool jacobian) {
  const DriveModel& model = problem.model();
  const Eigen::VectorXd theta =
      problem.drive_parameters(problem.with_unknowns(workload->theta1_initial));
  std::vector<double> tau(static_cast<size_t>(model.dof())),
      J(static_cast<size_t>(model.dof() * model.num_params()));
  for (auto _ : state) {
    for (Eigen::Index s = 0; s < model.num_samples(); ++s) {
      if (jacobian) {
        model.torque_jacobian(s, theta.data(), tau.data(), J.data());
      } else {
        model.torque(s, theta.data(), tau.data());
      }
      benchmark::DoNotOptimize(J.data());
      benchmark::DoNotOptimize(tau.data());
    }
  }
  set_size_counters(state);
}

// Building the problem: checks, stacking, binding the samples to the drive model. The reference
// drive model computes its regressor for every sample here (the autodiff variant's set-up too).
void problem_benchmark(benchmark::State& state, DriveModel& model) {
  for (auto _ : state) {
    MlProblem problem(model, {workload->scenario.data}, workload->setup, workload->start);
    benchmark::DoNotOptimize(&problem);
  }
  set_size_counters(state);
}

void register_all() {
  std::vector<NamedBenchmark> benchmarks;
  for (const char* what : {"fit", "evaluate"}) {
    for (const Variant& variant : variants()) {
      const bool fit = std::string(what) == "fit";
      benchmarks.emplace_back("BM_kr150_ml_" + std::string(what) + "_" + variant.name,
                              [variant, fit](benchmark::State& state) {
                                fit ? fit_benchmark(state, variant)
                                    : evaluate_benchmark(state, variant);
                              });
    }
  }
  for (const bool jacobian : {true, false}) {
    for (const std::string variant : {"generated", "reference"}) {
      benchmarks.emplace_back(
          "BM_kr150_drive_" + std::string(jacobian ? "jacobian" : "torque") + "_" + variant,
          [variant, jacobian](benchmark::State& state) {
            drive_model_benchmark(
                state, variant == "generated" ? *workload->generated : *workload->reference,
                jacobian);
          });
    }
  }
  benchmarks.emplace_back("BM_kr150_ml_problem_generated", [](benchmark::State& state) {
    problem_benchmark(state, workload->generated_model);
  });
  benchmarks.emplace_back("BM_kr150_ml_problem_reference", [](benchmark::State& state) {
    problem_benchmark(state, *workload->scenario.model);
  });
  register_wall_and_process_cpu_ms(benchmarks);
}

// After the console output, per variant: the whole fit (wall and CPU), LM iterations, the fit per
// LM iteration, Ceres' minimizer time in all and per LM iteration (the rest of the fit is the
// linear guess, the rank analysis and the statistics), one residual + Jacobian evaluation and
// building the problem; then the autodiff / analytic ratios and the target. Wall-clock ms (Ceres
// runs two threads), the median when there are repetitions.
void print_summary(const KeptRuns& runs, std::ostream& out) {
  out << "\nKR150 approach 3 (Swevers eq. 18): " << test::Kr150LoadScenario::kSamples
      << " samples x 4 axes, " << kUnknowns << " unknowns; wall-clock ms"
      << (runs.any_median() ? ", median of the repetitions" : "") << "\n"
      << printf_string("  %-10s %9s %9s %7s %9s %9s %9s %11s %9s\n", "variant", "fit", "fit CPU",
                       "LM its", "fit/its", "LM", "LM/its", "1 Jacobian", "problem");
  for (const std::string variant : {"generated", "reference", "autodiff"}) {
    const std::string fit = "BM_kr150_ml_fit_" + variant;
    // The autodiff variant's problem is the reference drive model's.
    const std::string problem =
        "BM_kr150_ml_problem_" + (variant == "autodiff" ? std::string("reference") : variant);
    const double iterations = runs.counter(fit, "lm_iterations");
    out << printf_string(
        "  %-10s %9.1f %9.1f %7.0f %9.2f %9.1f %9.2f %11.2f %9.1f\n", variant.c_str(),
        runs.real_time(fit), runs.cpu_time(fit), iterations, runs.real_time(fit) / iterations,
        runs.counter(fit, "lm_ms"), runs.counter(fit, "ms_per_lm_iteration"),
        runs.real_time("BM_kr150_ml_evaluate_" + variant), runs.real_time(problem));
  }
  for (const std::string analytic : {"generated", "reference"}) {
    const auto ratio = [&](const std::string& what) {
      return runs.real_time("BM_kr150_ml_" + what + "_autodiff") /
             runs.real_time("BM_kr150_ml_" + what + "_" + analytic);
    };
    const double per_iteration = runs.counter("BM_kr150_ml_fit_autodiff", "ms_per_lm_iteration") /
                                 runs.counter("BM_kr150_ml_fit_" + analytic, "ms_per_lm_iteration");
    out << printf_string(
        "Autodiff / %s: whole fit %.2fx, per LM iteration (Ceres) %.2fx, one Jacobian %.2fx\n",
        analytic.c_str(), ratio("fit"), per_iteration, ratio("evaluate"));
  }
  // The drive model alone, one pass over the samples: the generated code against the reference.
  for (const std::string what : {"jacobian", "torque"}) {
    const double generated = runs.cpu_time("BM_kr150_drive_" + what + "_generated");
    const double reference = runs.cpu_time("BM_kr150_drive_" + what + "_reference");
    if (std::isnan(generated) || std::isnan(reference)) continue;
    out << printf_string(
        "Drive model %s over the %d samples (CPU): generated %.3f ms, reference %.3f ms, "
        "reference / generated %.2fx%s\n",
        what == "jacobian" ? "torque_jacobian" : "torque", test::Kr150LoadScenario::kSamples,
        generated, reference, reference / generated,
        what == "jacobian"
            ? (reference / generated >= 2 ? " (target 2x: met)" : " (target 2x: MISSED)")
            : "");
  }
  const double fit = runs.real_time("BM_kr150_ml_fit_generated");
  if (!std::isnan(fit)) {
    out << printf_string(
        "Target: the whole approach-3 fit (generated, as shipped) under 200 ms: %.1f ms, %s\n", fit,
        fit < 200 ? "met" : "MISSED");
  }
}

}  // namespace
}  // namespace modelgen::bench

int main(int argc, char** argv) {
  using namespace modelgen::bench;
  return run_benchmarks(argc, argv, "ml_benchmark", workload, register_all, print_summary);
}
