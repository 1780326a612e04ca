// Instructions per forward-dynamics call on every shipped 6-axis robot (issue 28: >= 10x fewer
// than KDL's ChainFdSolver_RNE): modelgen::ForwardDynamics over the generated model, and KDL on
// a one-segment-per-body chain of the same random physical parameters (rigid bodies only, so KDL
// does a little less work). Each kernel runs `calls` times on a pool of seeded random states
// inside measured(), which forward_dynamics_instruction_counts.sh runs under callgrind with
// collection toggled on that function alone; `loop` is the cycling over the states alone.
//
//   build/bin/forward_dynamics_instruction_count <kernel> <calls> | list

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <kdl/chainfdsolver_recursive_newton_euler.hpp>
#include <kdl/jntarray.hpp>

#include "generated/comau_smart_six/comau_smart_six.hpp"
#include "generated/kr150/kr150.hpp"
#include "generated/kuka_kr150_2/kuka_kr150_2.hpp"
#include "generated/tx40/tx40.hpp"
#include "generated/ur5/ur5.hpp"
#include "modelgen/closed_loop/forward_dynamics.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/benchmarks/kdl_setup.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::bench {
namespace {

constexpr int kPool = 64;

// One robot: random physical parameters, a pool of states and torques, the generated forward
// dynamics and KDL's, each set up once.
class Robot {
 public:
  Robot(const std::string& description, std::unique_ptr<IdentificationModel> generated)
      : model_(load_robot(test::source_path(description))), generated_(std::move(generated)) {
    test::Random random(2024);
    p_ = test::random_physical_parameters(model_.tree, random);
    std::vector<double> beta(generated_->num_base_params());
    generated_->base_from_standard(p_.data(), beta.data());
    plant_ = std::make_unique<ForwardDynamics>(*generated_, beta);
    kdl_ = std::make_unique<KdlRne>(model_.tree, p_, KdlChainShape::kSegmentPerBody);
    const RigidBodyTree& tree = model_.tree;
    kdl_fd_ = std::make_unique<KDL::ChainFdSolver_RNE>(
        kdl_->chain(), KDL::Vector(tree.gravity[0], tree.gravity[1], tree.gravity[2]));
    for (int k = 0; k < kPool; ++k) {
      const test::JointState s = test::random_state(model_, random);
      const Eigen::VectorXd tau = random.vector(tree.dof, -50, 50);
      q_.push_back(s.q);
      dq_.push_back(s.dq);
      tau_.push_back(tau);
      kq_.push_back(kdl_->to_kdl(s.q));
      kdq_.push_back(kdl_->to_kdl(s.dq));
      ktau_.push_back(kdl_->to_kdl(tau));
    }
    ddq_.resize(tree.dof);
    kddq_.resize(kdl_->num_joints());
    no_external_.assign(kdl_->num_segments(), KDL::Wrench::Zero());
  }

  void generated(int k) {
    plant_->accelerations(q_[k].data(), dq_[k].data(), tau_[k].data(), ddq_.data());
  }
  void kdl(int k) { kdl_fd_->CartToJnt(kq_[k], kdq_[k], ktau_[k], no_external_, kddq_); }
  void loop(int k) { ddq_[0] += q_[k][0]; }

 private:
  RobotModel model_;
  std::unique_ptr<IdentificationModel> generated_;
  Eigen::VectorXd p_, ddq_;
  std::unique_ptr<ForwardDynamics> plant_;
  std::unique_ptr<KdlRne> kdl_;
  std::unique_ptr<KDL::ChainFdSolver_RNE> kdl_fd_;
  std::vector<Eigen::VectorXd> q_, dq_, tau_;
  std::vector<KDL::JntArray> kq_, kdq_, ktau_;
  KDL::JntArray kddq_;
  KDL::Wrenches no_external_;
};

using Factory = std::function<std::unique_ptr<Robot>()>;

template <typename Model>
Factory robot(const std::string& description) {
  return [description] {
    return std::make_unique<Robot>(description, std::make_unique<GeneratedModel<Model>>());
  };
}

const std::map<std::string, Factory>& robots() {
  static const std::map<std::string, Factory> all = {
      {"tx40", robot<tx40::Model>("robots/tx40.yaml")},
      {"kr150", robot<kr150::Model>("robots/kr150.yaml")},
      {"comau_smart_six", robot<comau_smart_six::Model>("robots/comau_smart_six.yaml")},
      {"ur5", robot<ur5::Model>("robots/urdf/ur5.urdf")},
      {"kuka_kr150_2", robot<kuka_kr150_2::Model>("robots/urdf/kuka_kr150_2.urdf")},
  };
  return all;
}

}  // namespace

// Not inlined, not in an anonymous namespace: the script toggles callgrind on this symbol.
__attribute__((noinline)) void measured(const std::function<void(int)>& kernel, int calls) {
  for (int c = 0; c < calls; ++c) kernel(c & (kPool - 1));
}

}  // namespace modelgen::bench

// Kernels are <what>_<robot>, what one of loop, generated, kdl.
int main(int argc, char** argv) {
  using namespace modelgen::bench;
  const std::vector<std::string> what = {"loop", "generated", "kdl"};
  if (argc == 2 && std::string(argv[1]) == "list") {
    for (const auto& [name, factory] : robots()) {
      for (const std::string& w : what) std::printf("%s_%s\n", w.c_str(), name.c_str());
    }
    return 0;
  }
  const std::string kernel = argc == 3 ? argv[1] : "";
  const std::size_t cut = kernel.find('_');
  const std::string w = kernel.substr(0, cut);
  const std::string name = cut == std::string::npos ? "" : kernel.substr(cut + 1);
  if (robots().count(name) == 0 || (w != "loop" && w != "generated" && w != "kdl")) {
    std::fprintf(stderr, "usage: forward_dynamics_instruction_count <kernel> <calls> | list\n");
    return 2;
  }
  const std::unique_ptr<Robot> r = robots().at(name)();
  // Chosen once, so that every kernel pays the same call overhead as `loop`.
  void (Robot::*const member)(int) =
      w == "loop" ? &Robot::loop : (w == "generated" ? &Robot::generated : &Robot::kdl);
  const std::function<void(int)> run = [&](int k) { (r.get()->*member)(k); };
  measured(run, std::atoi(argv[2]));
  return 0;
}
