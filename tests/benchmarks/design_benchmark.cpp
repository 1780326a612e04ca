// Excitation design for the TX-40 (issue 12): 6 axes, 5 harmonics, period 10 s, 66 variables,
// the full base set with friction (61 parameters), through the checked-in generated model; the
// criterion against the best of 100 random feasible starts. Acceleration limit: 10 rad/s^2 on
// every joint (chosen; Staubli publishes none), as robots/data/tx40/design.yaml. Issue 28: one
// evaluation of the criterion with its gradient (200 samples), the regressor's state derivative
// from the generated state Jacobian against the central differences of the regressor that
// design_gradient.cpp keeps for the numeric reference (forced here by a wrapper that says its
// state Jacobian is not exact), and the whole design both ways.

#include <cmath>
#include <ostream>
#include <vector>

#include <benchmark/benchmark.h>

#include "generated/tx40/tx40.hpp"
#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/benchmarks/benchmark_summary.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::bench {
namespace {

// The wrapped model with its state Jacobian declared inexact: the design then differentiates
// the regressor by central differences (5 regressor evaluations per moving joint and sample),
// as before issue 28.
class DifferencedStateJacobian final : public IdentificationModel {
 public:
  explicit DifferencedStateJacobian(const IdentificationModel& m) : m_(m) {}
  std::string name() const override { return m_.name(); }
  std::string description_sha256() const override { return m_.description_sha256(); }
  int dof() const override { return m_.dof(); }
  const std::vector<std::string>& standard_param_names() const override {
    return m_.standard_param_names();
  }
  const std::vector<std::string>& base_param_names() const override {
    return m_.base_param_names();
  }
  void regressor(const double* q, const double* dq, const double* ddq, double* W) const override {
    m_.regressor(q, dq, ddq, W);
  }
  void power_regressor(const double* q, const double* dq, const double* ddq,
                       double* dh) const override {
    m_.power_regressor(q, dq, ddq, dh);
  }
  void inverse_dynamics(const double* q, const double* dq, const double* ddq, const double* beta,
                        double* tau) const override {
    m_.inverse_dynamics(q, dq, ddq, beta, tau);
  }
  void base_from_standard(const double* p, double* beta) const override {
    m_.base_from_standard(p, beta);
  }
  const DriveChain& drive_chain() const override { return m_.drive_chain(); }

 private:
  const IdentificationModel& m_;
};

struct Workload {
  GeneratedModel<tx40::Model> model;
  DifferencedStateJacobian differenced{model};
  ExcitationDesignProblem problem;
  // One criterion evaluation: every base parameter, unit scale, a random point.
  std::vector<int> columns;
  Eigen::VectorXd scale;
  std::vector<double> x;

  Workload() {
    const RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
    problem.model = &model;
    problem.period = 10;
    problem.harmonics = 5;
    problem.moving = {0, 1, 2, 3, 4, 5};
    problem.hold = Eigen::VectorXd::Zero(6);
    for (int j = 0; j < 6; ++j) {
      JointLimits limits = description.joints[static_cast<std::size_t>(j)].limits;
      limits.ddq = 10.0;
      problem.limits.push_back(limits);
    }
    problem.seed = 1;
    for (int c = 0; c < model.num_base_params(); ++c) columns.push_back(c);
    scale = Eigen::VectorXd::Ones(model.num_base_params());
    test::Random random(5);
    for (int j = 0; j < 6; ++j) {
      x.push_back(random.uniform(-0.5, 0.5));
      for (int e = 0; e < 10; ++e) x.push_back(random.uniform(-0.1, 0.1));
    }
  }
};

Workload* workload = nullptr;

void BM_tx40_design(benchmark::State& state) {
  ExcitationDesign design;
  for (auto _ : state) design = design_excitation(workload->problem);
  state.counters["cond_before"] = design.before.cond_scaled;
  state.counters["cond_after"] = design.after.cond_scaled;
  state.counters["unscaled_before"] = design.before.cond_unscaled;
  state.counters["unscaled_after"] = design.after.cond_unscaled;
  state.counters["evaluations"] = design.evaluations;
}

void BM_tx40_design_differenced(benchmark::State& state) {
  ExcitationDesignProblem problem = workload->problem;
  problem.model = &workload->differenced;
  ExcitationDesign design;
  for (auto _ : state) design = design_excitation(problem);
  state.counters["cond_after"] = design.after.cond_scaled;
  state.counters["evaluations"] = design.evaluations;
}

// One criterion value with its gradient; arg 0: cond, 1: logdet.
void gradient_evaluation(benchmark::State& state, const IdentificationModel& model) {
  ExcitationDesignProblem problem = workload->problem;
  problem.model = &model;
  problem.criterion = state.range(0) == 0 ? DesignCriterion::kCond : DesignCriterion::kLogDet;
  std::vector<double> gradient;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        design_objective(problem, workload->columns, workload->scale, workload->x, &gradient));
  }
}

void BM_tx40_gradient(benchmark::State& state) { gradient_evaluation(state, workload->model); }

void BM_tx40_gradient_differenced(benchmark::State& state) {
  gradient_evaluation(state, workload->differenced);
}

void register_all() {
  benchmark::RegisterBenchmark("BM_tx40_gradient", BM_tx40_gradient)
      ->Unit(benchmark::kMillisecond)
      ->Arg(0)
      ->Arg(1);
  benchmark::RegisterBenchmark("BM_tx40_gradient_differenced", BM_tx40_gradient_differenced)
      ->Unit(benchmark::kMillisecond)
      ->Arg(0)
      ->Arg(1);
  benchmark::RegisterBenchmark("BM_tx40_design", BM_tx40_design)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  benchmark::RegisterBenchmark("BM_tx40_design_differenced", BM_tx40_design_differenced)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
}

void print_summary(const KeptRuns& runs, std::ostream& out) {
  for (const char* arg : {"0", "1"}) {
    const double exact = runs.cpu_time(std::string("BM_tx40_gradient/") + arg);
    const double differenced = runs.cpu_time(std::string("BM_tx40_gradient_differenced/") + arg);
    if (std::isnan(exact) || std::isnan(differenced)) continue;
    out << printf_string(
        "\nTX-40 criterion (%s) with its gradient, 200 samples: %.2f ms through the generated "
        "state Jacobian, %.2f ms by differences of the regressor: %.2fx\n",
        arg[0] == '0' ? "cond" : "logdet", exact, differenced, differenced / exact);
  }
  const double differenced_ms = runs.real_time("BM_tx40_design_differenced");
  if (!std::isnan(differenced_ms)) {
    out << printf_string(
        "TX-40 design by differences of the regressor: %.1f s, cond %.3g, %.0f evaluations\n",
        differenced_ms / 1e3, runs.counter("BM_tx40_design_differenced", "cond_after"),
        runs.counter("BM_tx40_design_differenced", "evaluations"));
  }
  const double ms = runs.real_time("BM_tx40_design");
  if (std::isnan(ms)) return;
  const double before = runs.counter("BM_tx40_design", "cond_before");
  const double after = runs.counter("BM_tx40_design", "cond_after");
  out << printf_string(
      "\nTX-40 design, 66 variables, 61 base parameters: cond %.3g (best of 100 random feasible "
      "starts) -> %.3g, %.2fx lower; unscaled %.3g -> %.3g; %.0f evaluations\n",
      before, after, before / after, runs.counter("BM_tx40_design", "unscaled_before"),
      runs.counter("BM_tx40_design", "unscaled_after"),
      runs.counter("BM_tx40_design", "evaluations"));
  out << printf_string("Target: under 60 s on one core: %.1f s, %s\n", ms / 1e3,
                       ms < 60e3 ? "met" : "MISSED");
  out << printf_string("Target: 10x lower cond than the best random start: %.2fx, %s\n",
                       before / after, before / after >= 10 ? "met" : "MISSED");
}

}  // namespace
}  // namespace modelgen::bench

int main(int argc, char** argv) {
  using namespace modelgen::bench;
  return run_benchmarks(argc, argv, "design_benchmark", workload, register_all, print_summary);
}
