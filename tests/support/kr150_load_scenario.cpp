// The simulated KR150 load-identification experiment (Swevers et al. 2002, Tables 1-2, eq. 3, 15):
// trajectory, true parameters, noisy motor torques, and approach 3's unknowns and start.

#include "tests/support/kr150_load_scenario.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {

void table1_state(double t, bool move_axis3, Eigen::VectorXd& q, Eigen::VectorXd& dq,
                  Eigen::VectorXd& ddq) {
  struct Term {
    int axis, harmonic;
    double a, b;
  };
  const std::vector<Term> terms = {{2, 25, 8.72e-2, -4.62e-3}, {3, 1, 1.57, 0},
                                   {3, 18, 4.60e-1, -1.76e-2}, {4, 1, -8.38e-1, 1.78e-3},
                                   {4, 19, -2.10e-1, 8.52e-3}, {5, 1, 0, 1.57},
                                   {5, 15, 2.56e-2, 1.57}};
  const double wf = 2 * std::numbers::pi / Kr150LoadScenario::kPeriod;
  q = Eigen::VectorXd::Zero(6);
  dq = Eigen::VectorXd::Zero(6);
  ddq = Eigen::VectorXd::Zero(6);
  q[1] = -std::numbers::pi / 2;
  q[2] = 1.57;
  for (const Term& term : terms) {
    if (term.axis == 2 && !move_axis3) continue;
    const double w = wf * term.harmonic, s = std::sin(w * t), c = std::cos(w * t);
    q[term.axis] += term.a * s + term.b * c;
    dq[term.axis] += w * (term.a * c - term.b * s);
    ddq[term.axis] += -w * w * (term.a * s + term.b * c);
  }
}

LoadParameters table2_load() {
  LoadParameters load;
  load.mass = 125.46;
  load.com = {0.088, -0.032, 0.140};
  load.inertia = {38.21, 6.55, 37.13, 7.28, 1.49, -1.23};
  return load;
}

Kr150LoadScenario::Kr150LoadScenario(bool move_axis3, int samples)
    : description(modelgen::load_robot(source_path("robots/kr150.yaml"))) {
  DriveChain drive = DriveChain::identity(6);
  drive.motor_from_joint = description.drives.motor_from_joint;
  model = std::make_unique<ReferenceDriveModel>(description.tree, drive);
  names = ml_param_names(*model);
  // Known link parameters: physical random values; link 7 (the flange) carries only the load.
  Random random(2002);
  const Eigen::VectorXd p = random_physical_parameters(description.tree, random);
  std::map<std::string, double> standard;
  for (size_t k = 0; k < description.tree.params.size(); ++k) {
    standard[description.tree.params[k].name] = p[static_cast<Eigen::Index>(k)];
  }
  truth = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(names.size()));
  const std::array<double, kLoadParams> load = table2_load().to_vector();
  for (size_t k = 0; k < names.size(); ++k) {
    const std::string& name = names[k];
    const int j = name.back() - '1';
    double& v = truth[static_cast<Eigen::Index>(k)];
    if (k >= names.size() - kLoadParams) {
      v = load[k - (names.size() - kLoadParams)];
    } else if (name.back() == '7') {
      v = 0;  // link 7's own parameters: negligible against the load (Swevers section 2)
    } else if (name.compare(0, 2, "JM") == 0) {
      v = kJM[j];
    } else if (name.compare(0, 2, "Rv") == 0) {
      v = kRv[j];
    } else if (name.compare(0, 2, "Rc") == 0) {
      v = kRc[j];
    } else if (name.compare(0, 2, "Rz") == 0) {
      v = kRz[j];
    } else {
      v = standard.at(name);
    }
  }
  data.source = move_axis3 ? "axes3-6" : "wrist";
  data.q.resize(samples, 6);
  data.dq.resize(samples, 6);
  data.ddq.resize(samples, 6);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd q, dq, ddq;
    table1_state(kPeriod * s / samples, move_axis3, q, dq, ddq);
    data.q.row(s) = q.transpose();
    data.dq.row(s) = dq.transpose();
    data.ddq.row(s) = ddq.transpose();
  }
  // Motor torques of the true model plus noise.
  model->set_samples(data.q, data.dq, data.ddq);
  Eigen::VectorXd theta = truth.head(model->num_params());
  const std::array<double, 10> load_standard = standard_from_load(table2_load());
  for (int m = 0; m < 10; ++m) theta[model->num_params() - 24 - 10 + m] += load_standard[m];
  data.tau_M.resize(samples, 6);
  data.sigma = Eigen::Map<const Eigen::VectorXd>(kSigma, 6);
  for (int s = 0; s < samples; ++s) {
    double tau[6];
    model->torque(s, theta.data(), tau);
    for (int i = 0; i < 6; ++i) data.tau_M(s, i) = tau[i] + kSigma[i] * random.normal();
  }
}

std::vector<std::string> Kr150LoadScenario::unknowns(const std::vector<int>& axes) const {
  std::vector<std::string> out = load_param_names();
  for (const char* stem : {"Rv", "Rc", "Rz"}) {
    for (const int i : axes) out.push_back(stem + std::to_string(i + 1));
  }
  return out;
}

Eigen::VectorXd Kr150LoadScenario::start(const std::vector<std::string>& unknown) const {
  Eigen::VectorXd values = truth;
  for (size_t k = 0; k < names.size(); ++k) {
    if (std::find(unknown.begin(), unknown.end(), names[k]) == unknown.end()) continue;
    const std::string& name = names[k];
    double& v = values[static_cast<Eigen::Index>(k)];
    if (name == "load_m") {
      v = 100;
    } else if (name.compare(0, 7, "load_cx") == 0 || name == "load_cy" || name == "load_cz") {
      v = 0;
    } else if (name == "load_Ixx" || name == "load_Iyy" || name == "load_Izz") {
      v = 10;
    } else if (name.compare(0, 5, "load_") == 0) {
      v = 0;
    } else if (name.compare(0, 2, "Rz") == 0) {
      v = 1;
    } else {
      v = 0;
    }
  }
  return values;
}

}  // namespace modelgen::test
