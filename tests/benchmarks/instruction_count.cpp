// Instructions per call, the stable measure where times are not (a shared machine moves them by
// 10-30 %): one kernel (a generated function of the TX-40, the numeric reference's, or KDL's
// recursive Newton-Euler) called `calls` times on a pool of seeded random states inside
// measured(), which instruction_counts.sh runs under valgrind's callgrind with collection
// toggled on that function alone. `instruction_count list` prints the kernels; `loop` is the
// cycling over the states alone, subtracted by the script.
//
//   build/bin/instruction_count <kernel> <calls>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <kdl/jntarray.hpp>

#include "generated/tx40/tx40.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/benchmarks/kdl_setup.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::bench {
namespace {

constexpr int kPool = 64;

struct State {
  double q[tx40::kDof], dq[tx40::kDof], ddq[tx40::kDof], sin_q[tx40::kDof], cos_q[tx40::kDof];
};

struct Fixture {
  RobotModel model = load_robot(test::source_path("robots/tx40.yaml"));
  std::vector<State> states;
  std::vector<Eigen::VectorXd> q, dq, ddq;
  std::vector<KDL::JntArray> kq, kdq, kddq;
  Eigen::VectorXd p;
  std::vector<double> beta = std::vector<double>(tx40::kBaseParams);
  std::vector<double> theta;
  // Output arrays zeroed once: generated functions never write their always-zero entries.
  std::vector<double> W = std::vector<double>(tx40::kDof * tx40::kStandardParams, 0.0);
  std::vector<double> J = std::vector<double>(tx40::kDof * tx40::kDriveParams, 0.0);
  double tau[tx40::kDof] = {};
  ReferenceDynamics reference{model.tree};
  KdlRne kdl;
  ReferenceDriveModel reference_drive;
  GeneratedDriveModel<tx40::Model> generated_drive;

  explicit Fixture(test::Random random = test::Random(2024))
      : p(test::random_physical_parameters(model.tree, random)),
        kdl(model.tree, p, KdlChainShape::kSegmentPerBody),
        reference_drive(model.tree, model.drives) {
    tx40::base_from_standard(p.data(), beta.data());
    Eigen::MatrixXd Q(kPool, tx40::kDof), DQ(kPool, tx40::kDof), DDQ(kPool, tx40::kDof);
    for (int k = 0; k < kPool; ++k) {
      const test::JointState s = test::random_state(model, random);
      State st{};
      for (int i = 0; i < tx40::kDof; ++i) {
        st.q[i] = s.q[i];
        st.dq[i] = s.dq[i];
        st.ddq[i] = s.ddq[i];
        st.sin_q[i] = std::sin(s.q[i]);
        st.cos_q[i] = std::cos(s.q[i]);
      }
      states.push_back(st);
      q.push_back(s.q);
      dq.push_back(s.dq);
      ddq.push_back(s.ddq);
      kq.push_back(kdl.to_kdl(s.q));
      kdq.push_back(kdl.to_kdl(s.dq));
      kddq.push_back(kdl.to_kdl(s.ddq));
      Q.row(k) = s.q.transpose();
      DQ.row(k) = s.dq.transpose();
      DDQ.row(k) = s.ddq.transpose();
    }
    reference_drive.set_samples(Q, DQ, DDQ);
    generated_drive.set_samples(Q, DQ, DDQ);
    for (const std::string& name : reference_drive.param_names()) {
      theta.push_back(name.rfind("Rz", 0) == 0 ? 0.9 : 0.5);
    }
  }
};

using Kernel = std::function<void(Fixture&, int)>;

std::map<std::string, Kernel> kernels() {
  return {
      {"loop", [](Fixture& f, int k) { f.tau[0] += f.states[k].q[0]; }},
      {"generated_base_regressor_sincos",
       [](Fixture& f, int k) {
         const State& s = f.states[k];
         tx40::idim_regressor_sincos(s.q, s.sin_q, s.cos_q, s.dq, s.ddq, f.W.data());
       }},
      {"generated_base_regressor",
       [](Fixture& f, int k) {
         const State& s = f.states[k];
         tx40::idim_regressor(s.q, s.dq, s.ddq, f.W.data());
       }},
      {"generated_standard_regressor_sincos",
       [](Fixture& f, int k) {
         const State& s = f.states[k];
         tx40::idim_regressor_standard_sincos(s.q, s.sin_q, s.cos_q, s.dq, s.ddq, f.W.data());
       }},
      {"generated_inverse_dynamics_sincos",
       [](Fixture& f, int k) {
         const State& s = f.states[k];
         tx40::inverse_dynamics_sincos(s.q, s.sin_q, s.cos_q, s.dq, s.ddq, f.beta.data(), f.tau);
       }},
      {"generated_inverse_dynamics",
       [](Fixture& f, int k) {
         const State& s = f.states[k];
         tx40::inverse_dynamics(s.q, s.dq, s.ddq, f.beta.data(), f.tau);
       }},
      {"generated_inverse_dynamics_standard",
       [](Fixture& f, int k) {
         const State& s = f.states[k];
         tx40::inverse_dynamics_standard(s.q, s.dq, s.ddq, f.p.data(), f.tau);
       }},
      {"reference_standard_regressor",
       [](Fixture& f, int k) {
         const Eigen::MatrixXd W = f.reference.standard_regressor(f.q[k], f.dq[k], f.ddq[k]);
         f.tau[0] += W(0, 0);
       }},
      {"reference_inverse_dynamics",
       [](Fixture& f, int k) {
         f.tau[0] += f.reference.inverse_dynamics(f.q[k], f.dq[k], f.ddq[k], f.p)[0];
       }},
      {"kdl_rne",
       [](Fixture& f, int k) {
         static KDL::JntArray tau(tx40::kDof);
         f.kdl.solve(f.kq[k], f.kdq[k], f.kddq[k], tau);
       }},
      {"generated_drive_jacobian",
       [](Fixture& f, int k) {
         f.generated_drive.torque_jacobian(k, f.theta.data(), f.tau, f.J.data());
       }},
      {"reference_drive_jacobian",
       [](Fixture& f, int k) {
         f.reference_drive.torque_jacobian(k, f.theta.data(), f.tau, f.J.data());
       }},
  };
}

}  // namespace

// Not inlined, not in an anonymous namespace: the script toggles callgrind on this symbol.
__attribute__((noinline)) void measured(const Kernel& kernel, Fixture& fixture, int calls) {
  for (int c = 0; c < calls; ++c) kernel(fixture, c & (kPool - 1));
}

}  // namespace modelgen::bench

int main(int argc, char** argv) {
  using namespace modelgen::bench;
  const std::map<std::string, Kernel> all = kernels();
  if (argc == 2 && std::string(argv[1]) == "list") {
    for (const auto& [name, kernel] : all) std::printf("%s\n", name.c_str());
    return 0;
  }
  if (argc != 3 || all.count(argv[1]) == 0) {
    std::fprintf(stderr, "usage: instruction_count <kernel> <calls> | list\n");
    return 2;
  }
  Fixture fixture;
  const int calls = std::atoi(argv[2]);
  measured(all.at(argv[1]), fixture, calls);
  std::printf("%g\n", fixture.tau[0]);
  return 0;
}
