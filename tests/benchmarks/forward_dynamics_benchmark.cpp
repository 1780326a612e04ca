// Forward dynamics of the TX-40 (issue 13): ddq = M^-1 (tau - h) through the generated
// mass_matrix_and_bias with an LDL^T solve (modelgen::ForwardDynamics), the same
// through the numeric reference, and Orocos KDL's ChainFdSolver_RNE, on the same random states
// and parameters. KDL's chain has the rigid bodies only (no drive inertia or friction), so it
// does a little less work than the others. The summary prints the ratios; target: 10x KDL.

#include <memory>
#include <ostream>
#include <vector>

#include <benchmark/benchmark.h>
#include <kdl/chainfdsolver_recursive_newton_euler.hpp>

#include "generated/tx40/tx40.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/closed_loop/forward_dynamics.hpp"
#include "tests/benchmarks/benchmark_summary.hpp"
#include "tests/benchmarks/kdl_setup.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::bench {
namespace {

constexpr int kStates = 256;

struct Workload {
  RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
  GeneratedModel<tx40::Model> generated;
  ReferenceModel reference{description.name, description.tree};
  Eigen::VectorXd p;
  std::vector<test::JointState> states;
  std::vector<Eigen::VectorXd> torques;
  std::unique_ptr<KdlRne> kdl;

  Workload() {
    test::Random random(42);
    p = test::random_physical_parameters(description.tree, random);
    for (int i = 0; i < kStates; ++i) {
      states.push_back(test::random_state(description, random));
      torques.push_back(random.vector(description.tree.dof, -50, 50));
    }
    kdl = std::make_unique<KdlRne>(description.tree, p, KdlChainShape::kSegmentPerBody);
  }

  std::vector<double> beta(const IdentificationModel& model) const {
    std::vector<double> b(model.num_base_params());
    model.base_from_standard(p.data(), b.data());
    return b;
  }
};

Workload* workload = nullptr;

void run_model(benchmark::State& state, const IdentificationModel& model) {
  ForwardDynamics plant(model, workload->beta(model));
  Eigen::VectorXd ddq(model.dof());
  int i = 0;
  for (auto _ : state) {
    const test::JointState& s = workload->states[i];
    plant.accelerations(s.q.data(), s.dq.data(), workload->torques[i].data(), ddq.data());
    benchmark::DoNotOptimize(ddq.data());
    i = (i + 1) % kStates;
  }
}

void BM_tx40_fd_generated(benchmark::State& state) { run_model(state, workload->generated); }
void BM_tx40_fd_reference(benchmark::State& state) { run_model(state, workload->reference); }

void BM_tx40_fd_kdl(benchmark::State& state) {
  const RigidBodyTree& tree = workload->description.tree;
  KDL::ChainFdSolver_RNE solver(workload->kdl->chain(),
                                KDL::Vector(tree.gravity[0], tree.gravity[1], tree.gravity[2]));
  std::vector<KDL::JntArray> q, dq, tau;
  for (int i = 0; i < kStates; ++i) {
    q.push_back(workload->kdl->to_kdl(workload->states[i].q));
    dq.push_back(workload->kdl->to_kdl(workload->states[i].dq));
    tau.push_back(workload->kdl->to_kdl(workload->torques[i]));
  }
  const KDL::Wrenches no_external(workload->kdl->chain().getNrOfSegments(), KDL::Wrench::Zero());
  KDL::JntArray ddq(workload->kdl->num_joints());
  int i = 0;
  for (auto _ : state) {
    if (solver.CartToJnt(q[i], dq[i], tau[i], no_external, ddq) < 0) {
      state.SkipWithError("KDL forward dynamics failed");
      break;
    }
    benchmark::DoNotOptimize(ddq.data.data());
    i = (i + 1) % kStates;
  }
}

void register_all() {
  benchmark::RegisterBenchmark("BM_tx40_fd_generated", BM_tx40_fd_generated);
  benchmark::RegisterBenchmark("BM_tx40_fd_reference", BM_tx40_fd_reference);
  benchmark::RegisterBenchmark("BM_tx40_fd_kdl", BM_tx40_fd_kdl);
}

void print_summary(const KeptRuns& runs, std::ostream& out) {
  const double generated = runs.real_time("BM_tx40_fd_generated");
  const double reference = runs.real_time("BM_tx40_fd_reference");
  const double kdl = runs.real_time("BM_tx40_fd_kdl");
  out << "\nTX-40 forward dynamics per state: generated " << generated << " ns, reference "
      << reference << " ns, KDL " << kdl << " ns\n"
      << printf_string("generated vs KDL: %.1fx faster (target 10x); vs reference: %.1fx\n",
                       kdl / generated, reference / generated);
}

}  // namespace
}  // namespace modelgen::bench

int main(int argc, char** argv) {
  using namespace modelgen::bench;
  return run_benchmarks(argc, argv, "forward_dynamics_benchmark", workload, register_all,
                        print_summary);
}
