// Speed of the checked-in generated code (generated/, what ships) against Orocos KDL's
// recursive Newton-Euler and modelgen's numeric reference, and time to generate a model, for the
// TX-40, the KR150 and the 7-DOF KUKA iiwa14. Per-call times cycle through a fixed pool of
// seeded random states; after the runs a table of the ratios is printed (console output only).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Core>
#include <kdl/jntarray.hpp>

#include "generated/kr150/kr150.hpp"
#include "generated/kuka_iiwa14_drake/kuka_iiwa14_drake.hpp"
#include "generated/tx40/tx40.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/robot_model.hpp"
#include "generator/generate.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/benchmarks/benchmark_summary.hpp"
#include "tests/benchmarks/kdl_setup.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::bench {
namespace {

constexpr int kPoolSize = 256;  // states cycled through; a power of two keeps the index cheap
constexpr std::uint64_t kSeed = 2024;

// Each generated model lives in its own namespace; these adapters give the three one interface.
struct Tx40 {
  static constexpr const char* kName = "tx40";
  static constexpr const char* kDescription = "robots/tx40.yaml";
  static constexpr int kDof = tx40::kDof;
  static constexpr int kParams = tx40::kStandardParams;
  template <class T>
  static void inverse_dynamics(const T* q, const T* dq, const T* ddq, const T* p, T* tau) {
    tx40::inverse_dynamics_standard(q, dq, ddq, p, tau);
  }
  template <class T>
  static void regressor(const T* q, const T* dq, const T* ddq, T* W) {
    tx40::idim_regressor_standard(q, dq, ddq, W);
  }
  static constexpr int kBase = tx40::kBaseParams;
  static void base_from_standard(const double* p, double* beta) {
    tx40::base_from_standard(p, beta);
  }
  static void joint_sincos(const double* q, double* s, double* c) { tx40::joint_sincos(q, s, c); }
  static void base_regressor(const double* q, const double* dq, const double* ddq, double* W) {
    tx40::idim_regressor(q, dq, ddq, W);
  }
  static void power_regressor(const double* q, const double* dq, const double* ddq, double* dh) {
    tx40::power_regressor(q, dq, ddq, dh);
  }
  static void base_inverse_dynamics(const double* q, const double* s, const double* c,
                                    const double* dq, const double* ddq, const double* beta,
                                    double* tau) {
    if (s == nullptr) {
      tx40::inverse_dynamics(q, dq, ddq, beta, tau);
    } else {
      tx40::inverse_dynamics_sincos(q, s, c, dq, ddq, beta, tau);
    }
  }
};

struct Kr150 {
  static constexpr const char* kName = "kr150";
  static constexpr const char* kDescription = "robots/kr150.yaml";
  static constexpr int kDof = kr150::kDof;
  static constexpr int kParams = kr150::kStandardParams;
  template <class T>
  static void inverse_dynamics(const T* q, const T* dq, const T* ddq, const T* p, T* tau) {
    kr150::inverse_dynamics_standard(q, dq, ddq, p, tau);
  }
  template <class T>
  static void regressor(const T* q, const T* dq, const T* ddq, T* W) {
    kr150::idim_regressor_standard(q, dq, ddq, W);
  }
  static constexpr int kBase = kr150::kBaseParams;
  static void base_from_standard(const double* p, double* beta) {
    kr150::base_from_standard(p, beta);
  }
  static void joint_sincos(const double* q, double* s, double* c) { kr150::joint_sincos(q, s, c); }
  static void base_regressor(const double* q, const double* dq, const double* ddq, double* W) {
    kr150::idim_regressor(q, dq, ddq, W);
  }
  static void power_regressor(const double* q, const double* dq, const double* ddq, double* dh) {
    kr150::power_regressor(q, dq, ddq, dh);
  }
  static void base_inverse_dynamics(const double* q, const double* s, const double* c,
                                    const double* dq, const double* ddq, const double* beta,
                                    double* tau) {
    if (s == nullptr) {
      kr150::inverse_dynamics(q, dq, ddq, beta, tau);
    } else {
      kr150::inverse_dynamics_sincos(q, s, c, dq, ddq, beta, tau);
    }
  }
};

struct Iiwa14 {
  static constexpr const char* kName = "iiwa14";
  static constexpr const char* kDescription = "robots/urdf/kuka_iiwa14_drake.urdf";
  static constexpr int kDof = iiwa14::kDof;
  static constexpr int kParams = iiwa14::kStandardParams;
  template <class T>
  static void inverse_dynamics(const T* q, const T* dq, const T* ddq, const T* p, T* tau) {
    iiwa14::inverse_dynamics_standard(q, dq, ddq, p, tau);
  }
  template <class T>
  static void regressor(const T* q, const T* dq, const T* ddq, T* W) {
    iiwa14::idim_regressor_standard(q, dq, ddq, W);
  }
  static constexpr int kBase = iiwa14::kBaseParams;
  static void base_from_standard(const double* p, double* beta) {
    iiwa14::base_from_standard(p, beta);
  }
  static void joint_sincos(const double* q, double* s, double* c) { iiwa14::joint_sincos(q, s, c); }
  static void base_regressor(const double* q, const double* dq, const double* ddq, double* W) {
    iiwa14::idim_regressor(q, dq, ddq, W);
  }
  static void power_regressor(const double* q, const double* dq, const double* ddq, double* dh) {
    iiwa14::power_regressor(q, dq, ddq, dh);
  }
  static void base_inverse_dynamics(const double* q, const double* s, const double* c,
                                    const double* dq, const double* ddq, const double* beta,
                                    double* tau) {
    if (s == nullptr) {
      iiwa14::inverse_dynamics(q, dq, ddq, beta, tau);
    } else {
      iiwa14::inverse_dynamics_sincos(q, s, c, dq, ddq, beta, tau);
    }
  }
};

// Everything a robot's per-call benchmarks read, prepared before any timing starts.
struct Workload {
  Workload(const std::string& description, int generated_dof, int generated_params);

  modelgen::RobotModel model;
  ReferenceDynamics reference;
  Eigen::VectorXd p;                     // random physical standard parameters
  std::vector<float> p_float;            // the same, rounded
  std::vector<test::JointState> states;  // kPoolSize states for the reference
  std::vector<double> q, dq, ddq;        // the same states flattened, kPoolSize x dof
  std::vector<float> q_float, dq_float, ddq_float;
  std::unique_ptr<KdlRne> kdl;         // segment per body, as kdl_parser builds it
  std::unique_ptr<KdlRne> kdl_oracle;  // tests/support/kdl_oracle.cpp's two segments per body
  std::vector<KDL::JntArray> kdl_q, kdl_dq, kdl_ddq;  // the states in KDL joint order
};

// Both KDL chains must equal the oracle on the inertial parameters alone (KDL has no drive
// model), or the timing would be of the wrong computation.
void check_kdl(const Workload& w, KdlRne& kdl, const char* what) {
  Eigen::VectorXd p_inertial = w.p;
  for (std::size_t k = 0; k < w.model.tree.params.size(); ++k) {
    if (test::inertial_slot(w.model.tree.params[k].kind) < 0) {
      p_inertial[static_cast<Eigen::Index>(k)] = 0;
    }
  }
  for (int s = 0; s < 16; ++s) {
    const test::JointState& x = w.states[s];
    const Eigen::VectorXd expected =
        test::kdl_inverse_dynamics(w.model.tree, x.q, x.dq, x.ddq, p_inertial);
    const Eigen::VectorXd got = kdl.inverse_dynamics(x.q, x.dq, x.ddq);
    const double error = test::relative_error(got, expected, 1.0);
    if (!(error < 1e-10)) {
      throw std::runtime_error(std::string(what) + " KDL chain of " + w.model.name +
                               " disagrees with the KDL oracle: relative error " +
                               std::to_string(error));
    }
  }
}

Workload::Workload(const std::string& description, int generated_dof, int generated_params)
    : model(modelgen::load_robot(test::source_path(description))), reference(model.tree) {
  const int n = model.dof();
  if (n != generated_dof || reference.num_params() != generated_params) {
    throw std::runtime_error(description + " does not match its generated code: regenerate");
  }
  test::Random random(kSeed);
  p = test::random_physical_parameters(model.tree, random);
  p_float.assign(p.data(), p.data() + p.size());
  kdl = std::make_unique<KdlRne>(model.tree, p, KdlChainShape::kSegmentPerBody);
  kdl_oracle = std::make_unique<KdlRne>(model.tree, p, KdlChainShape::kFixedThenJoint);
  for (int s = 0; s < kPoolSize; ++s) {
    states.push_back(test::random_state(model, random));
    const test::JointState& x = states.back();
    q.insert(q.end(), x.q.data(), x.q.data() + n);
    dq.insert(dq.end(), x.dq.data(), x.dq.data() + n);
    ddq.insert(ddq.end(), x.ddq.data(), x.ddq.data() + n);
    kdl_q.push_back(kdl->to_kdl(x.q));
    kdl_dq.push_back(kdl->to_kdl(x.dq));
    kdl_ddq.push_back(kdl->to_kdl(x.ddq));
  }
  q_float.assign(q.begin(), q.end());
  dq_float.assign(dq.begin(), dq.end());
  ddq_float.assign(ddq.begin(), ddq.end());
  check_kdl(*this, *kdl, "segment-per-body");
  check_kdl(*this, *kdl_oracle, "fixed-then-joint");
}

// The generated functions on the pool; T picks the double or float variant.
template <class Robot, class T>
void generated_inverse_dynamics(benchmark::State& state, const Workload& w) {
  const T* q = nullptr;
  const T* dq = nullptr;
  const T* ddq = nullptr;
  const T* p = nullptr;
  if constexpr (std::is_same_v<T, float>) {
    q = w.q_float.data(), dq = w.dq_float.data(), ddq = w.ddq_float.data(), p = w.p_float.data();
  } else {
    q = w.q.data(), dq = w.dq.data(), ddq = w.ddq.data(), p = w.p.data();
  }
  T tau[Robot::kDof];
  int s = 0;
  for (auto _ : state) {
    const int offset = s * Robot::kDof;
    Robot::inverse_dynamics(q + offset, dq + offset, ddq + offset, p, tau);
    benchmark::DoNotOptimize(tau);
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
}

template <class Robot, class T>
void generated_regressor(benchmark::State& state, const Workload& w) {
  const T* q = nullptr;
  const T* dq = nullptr;
  const T* ddq = nullptr;
  if constexpr (std::is_same_v<T, float>) {
    q = w.q_float.data(), dq = w.dq_float.data(), ddq = w.ddq_float.data();
  } else {
    q = w.q.data(), dq = w.dq.data(), ddq = w.ddq.data();
  }
  std::vector<T> W(static_cast<std::size_t>(Robot::kDof) * Robot::kParams);
  int s = 0;
  for (auto _ : state) {
    const int offset = s * Robot::kDof;
    Robot::regressor(q + offset, dq + offset, ddq + offset, W.data());
    benchmark::DoNotOptimize(W.data());
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
}

// The base-parameter inverse dynamics (beta from base_from_standard, outside the timing); with
// `given_sincos` the sines and cosines of the pool are computed beforehand by joint_sincos and
// the *_sincos entry point is timed: the cost of the arithmetic alone.
template <class Robot>
void generated_base_inverse_dynamics(benchmark::State& state, const Workload& w,
                                     bool given_sincos) {
  double beta[Robot::kBase];
  Robot::base_from_standard(w.p.data(), beta);
  std::vector<double> sin_q(w.q.size()), cos_q(w.q.size());
  for (int k = 0; k < kPoolSize; ++k) {
    const int offset = k * Robot::kDof;
    Robot::joint_sincos(w.q.data() + offset, sin_q.data() + offset, cos_q.data() + offset);
  }
  double tau[Robot::kDof];
  int s = 0;
  for (auto _ : state) {
    const int offset = s * Robot::kDof;
    Robot::base_inverse_dynamics(w.q.data() + offset,
                                 given_sincos ? sin_q.data() + offset : nullptr,
                                 given_sincos ? cos_q.data() + offset : nullptr,
                                 w.dq.data() + offset, w.ddq.data() + offset, beta, tau);
    benchmark::DoNotOptimize(tau);
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
}

// A base-parameter regressor (IDIM kDof x kBase, or PIM 1 x kBase) on the pool.
template <class Robot, bool kPower>
void generated_base_regressor(benchmark::State& state, const Workload& w) {
  std::vector<double> out(static_cast<std::size_t>(kPower ? 1 : Robot::kDof) * Robot::kBase);
  int s = 0;
  for (auto _ : state) {
    const int offset = s * Robot::kDof;
    if constexpr (kPower) {
      Robot::power_regressor(w.q.data() + offset, w.dq.data() + offset, w.ddq.data() + offset,
                             out.data());
    } else {
      Robot::base_regressor(w.q.data() + offset, w.dq.data() + offset, w.ddq.data() + offset,
                            out.data());
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
}

void kdl_rne(benchmark::State& state, const Workload& w, KdlRne& kdl) {
  KDL::JntArray tau(kdl.num_joints());
  int s = 0;
  for (auto _ : state) {
    const int status = kdl.solve(w.kdl_q[s], w.kdl_dq[s], w.kdl_ddq[s], tau);
    benchmark::DoNotOptimize(status);
    benchmark::DoNotOptimize(tau.data.data());
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
  state.SetLabel(std::to_string(kdl.num_segments()) + " segments");
}

void reference_inverse_dynamics(benchmark::State& state, const Workload& w) {
  int s = 0;
  for (auto _ : state) {
    const test::JointState& x = w.states[s];
    Eigen::VectorXd tau = w.reference.inverse_dynamics(x.q, x.dq, x.ddq, w.p);
    benchmark::DoNotOptimize(tau.data());
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
}

void reference_regressor(benchmark::State& state, const Workload& w) {
  int s = 0;
  for (auto _ : state) {
    const test::JointState& x = w.states[s];
    Eigen::MatrixXd W = w.reference.standard_regressor(x.q, x.dq, x.ddq);
    benchmark::DoNotOptimize(W.data());
    benchmark::ClobberMemory();
    s = (s + 1) & (kPoolSize - 1);
  }
}

// Description file to generated files in memory: load, symbolic Newton-Euler, emission.
void generation(benchmark::State& state, const std::string& path) {
  for (auto _ : state) {
    gen::GeneratedModel generated = gen::generate_from_file(path, {});
    benchmark::DoNotOptimize(generated);
    benchmark::ClobberMemory();
  }
}

std::string benchmark_name(const char* robot, std::string_view what) {
  return "BM_" + std::string(robot) + "_" + std::string(what);
}

template <class Robot>
void register_robot(Workload& w) {
  const auto name = [](std::string_view what) { return benchmark_name(Robot::kName, what); };
  benchmark::RegisterBenchmark(
      name("generated_inverse_dynamics").c_str(),
      [&w](benchmark::State& st) { generated_inverse_dynamics<Robot, double>(st, w); });
  benchmark::RegisterBenchmark(
      name("generated_inverse_dynamics_float").c_str(),
      [&w](benchmark::State& st) { generated_inverse_dynamics<Robot, float>(st, w); });
  benchmark::RegisterBenchmark(
      name("generated_inverse_dynamics_base").c_str(),
      [&w](benchmark::State& st) { generated_base_inverse_dynamics<Robot>(st, w, false); });
  benchmark::RegisterBenchmark(
      name("generated_inverse_dynamics_base_sincos").c_str(),
      [&w](benchmark::State& st) { generated_base_inverse_dynamics<Robot>(st, w, true); });
  benchmark::RegisterBenchmark(
      name("generated_regressor_base").c_str(),
      [&w](benchmark::State& st) { generated_base_regressor<Robot, false>(st, w); });
  benchmark::RegisterBenchmark(
      name("generated_power_regressor_base").c_str(),
      [&w](benchmark::State& st) { generated_base_regressor<Robot, true>(st, w); });
  benchmark::RegisterBenchmark(name("kdl_rne").c_str(),
                               [&w](benchmark::State& st) { kdl_rne(st, w, *w.kdl); });
  benchmark::RegisterBenchmark(name("kdl_rne_oracle_chain").c_str(),
                               [&w](benchmark::State& st) { kdl_rne(st, w, *w.kdl_oracle); });
  benchmark::RegisterBenchmark(name("reference_inverse_dynamics").c_str(),
                               [&w](benchmark::State& st) { reference_inverse_dynamics(st, w); })
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(name("generated_regressor").c_str(), [&w](benchmark::State& st) {
    generated_regressor<Robot, double>(st, w);
  });
  benchmark::RegisterBenchmark(
      name("generated_regressor_float").c_str(),
      [&w](benchmark::State& st) { generated_regressor<Robot, float>(st, w); });
  benchmark::RegisterBenchmark(name("reference_regressor").c_str(), [&w](benchmark::State& st) {
    reference_regressor(st, w);
  })->Unit(benchmark::kMicrosecond);
  const std::string path = test::source_path(Robot::kDescription);
  benchmark::RegisterBenchmark(name("generation").c_str(), [path](benchmark::State& st) {
    generation(st, path);
  })->Unit(benchmark::kMillisecond);
}

// What the summary needs to know about a robot.
struct RobotInfo {
  const char* name;
  int dof;
};

// After the console output, a table of ratios and the targets. Times are CPU time per call: the
// median over the repetitions when there are several, else the single measurement.
class ModelSummary {
 public:
  explicit ModelSummary(std::vector<RobotInfo> robots) : robots_(std::move(robots)) {}

  void operator()(const KeptRuns& runs, std::ostream& out) const {
    const auto get = [&runs](const RobotInfo& robot, std::string_view what) {
      return cpu_ns(runs, benchmark_name(robot.name, what));
    };
    out << "\nCPU time per call, "
        << (runs.any_median() ? "median of the repetitions" : "single run")
        << ".\nID: generated inverse_dynamics_standard (IDf: float). KDL: ChainIdSolver_RNE, one\n"
        << "segment per body (KDL2: the KDL oracle's two). W: generated idim_regressor_standard.\n"
        << "ref: ReferenceDynamics. gen: generate_from_file.\n"
        << printf_string("%-7s %9s %9s %9s %8s %9s %9s %9s %9s %8s %8s\n", "robot", "ID ns",
                         "IDf ns", "KDL ns", "KDL/ID", "KDL2 ns", "refID us", "W ns", "refW us",
                         "refW/W", "gen ms");
    for (const RobotInfo& robot : robots_) {
      const double id = get(robot, "generated_inverse_dynamics");
      const double kdl = get(robot, "kdl_rne");
      const double W = get(robot, "generated_regressor");
      const double ref_W = get(robot, "reference_regressor");
      out << printf_string(
          "%-7s %9s %9s %9s %8s %9s %9s %9s %9s %8s %8s\n", robot.name, format(id, 1).c_str(),
          format(get(robot, "generated_inverse_dynamics_float"), 1).c_str(), format(kdl, 1).c_str(),
          format(kdl / id, 1, "x").c_str(), format(get(robot, "kdl_rne_oracle_chain"), 1).c_str(),
          format(get(robot, "reference_inverse_dynamics") / 1e3, 2).c_str(), format(W, 1).c_str(),
          format(ref_W / 1e3, 1).c_str(), format(ref_W / W, 0, "x").c_str(),
          format(get(robot, "generation") / 1e6, 1).c_str());
    }
    std::string targets;
    for (const RobotInfo& robot : robots_) {
      const double ms_limit = robot.dof <= 6 ? 50 : 100;
      targets += target(robot, "KDL RNE / generated ID",
                        get(robot, "kdl_rne") / get(robot, "generated_inverse_dynamics"), 15, "x");
      targets +=
          target(robot, "reference W / generated W",
                 get(robot, "reference_regressor") / get(robot, "generated_regressor"), 200, "x");
      targets += target(robot, "generation time", get(robot, "generation") / 1e6, ms_limit, " ms");
    }
    if (!targets.empty()) out << "\nTargets\n" << targets;
  }

 private:
  static double nanoseconds_per(benchmark::TimeUnit unit) {
    switch (unit) {
      case benchmark::kNanosecond:
        return 1;
      case benchmark::kMicrosecond:
        return 1e3;
      case benchmark::kMillisecond:
        return 1e6;
      case benchmark::kSecond:
        return 1e9;
    }
    return 1;
  }

  // NaN when the benchmark was filtered out or failed.
  static double cpu_ns(const KeptRuns& runs, const std::string& name) {
    const KeptRuns::Run* run = runs.find(name);
    return run == nullptr ? std::numeric_limits<double>::quiet_NaN()
                          : runs.cpu_time(name) * nanoseconds_per(run->time_unit);
  }

  static std::string format(double value, int decimals, const char* suffix = "") {
    if (std::isnan(value)) return "-";
    return printf_string("%.*f%s", decimals, value, suffix);
  }

  // One line of the target check, empty when a benchmark did not run. Ratios are "at least",
  // times "below".
  static std::string target(const RobotInfo& robot, const char* what, double value, double limit,
                            const char* unit) {
    if (std::isnan(value)) return "";
    const bool ratio = unit[0] == 'x';
    const bool met = ratio ? value >= limit : value < limit;
    return printf_string("  %-7s %-26s %8.1f%-3s (target %s %g%s): %s\n", robot.name, what, value,
                         unit, ratio ? ">=" : "<", limit, unit, met ? "met" : "MISSED");
  }

  std::vector<RobotInfo> robots_;
};

}  // namespace
}  // namespace modelgen::bench

int main(int argc, char** argv) {
  using namespace modelgen::bench;
  std::unique_ptr<Workload> tx40, kr150, iiwa14;
  return run_benchmarks(
      argc, argv, "model_benchmark",
      [&] {
        tx40 = std::make_unique<Workload>(Tx40::kDescription, Tx40::kDof, Tx40::kParams);
        kr150 = std::make_unique<Workload>(Kr150::kDescription, Kr150::kDof, Kr150::kParams);
        iiwa14 = std::make_unique<Workload>(Iiwa14::kDescription, Iiwa14::kDof, Iiwa14::kParams);
        register_robot<Tx40>(*tx40);
        register_robot<Kr150>(*kr150);
        register_robot<Iiwa14>(*iiwa14);
      },
      ModelSummary(
          {{Tx40::kName, Tx40::kDof}, {Kr150::kName, Kr150::kDof}, {Iiwa14::kName, Iiwa14::kDof}}));
}
