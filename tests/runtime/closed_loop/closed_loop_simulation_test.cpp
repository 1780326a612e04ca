// The closed-loop simulation against a discrete PID loop written here on Orocos KDL's
// dynamics with its own integrator; the PID against its formula by hand; the smoothed
// friction against the model's own inverse dynamics away from rest; bad gains refused.

#include "modelgen/closed_loop/closed_loop_simulation.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

PidGains tx40_gains() {
  PidGains gains;
  gains.sample_time = 1e-3;
  gains.kp = (Eigen::VectorXd(6) << 40000, 40000, 20000, 4000, 4000, 2000).finished();
  gains.ki = (Eigen::VectorXd(6) << 80000, 80000, 40000, 8000, 8000, 4000).finished();
  gains.kd = (Eigen::VectorXd(6) << 400, 400, 200, 40, 40, 20).finished();
  return gains;
}

// A smooth reference: one sine per joint around the middle of its range.
Eigen::MatrixXd reference(int samples, double ts, int n) {
  Eigen::MatrixXd qr(samples, n);
  for (int k = 0; k < samples; ++k) {
    for (int j = 0; j < n; ++j) {
      qr(k, j) = 0.3 * std::sin(2 * M_PI * (0.5 + 0.1 * j) * k * ts + j) + 0.1 * j;
    }
  }
  return qr;
}

bool is_coulomb(const std::string& name) { return name.rfind("Fc", 0) == 0; }

TEST(PidController, CommandsFollowTheDiscreteFormula) {
  PidGains gains;
  gains.sample_time = 0.002;
  gains.kp = Eigen::VectorXd::Constant(1, 10);
  gains.ki = Eigen::VectorXd::Constant(1, 3);
  gains.kd = Eigen::VectorXd::Constant(1, 0.5);
  PidController pid(gains);
  const double errors[] = {0.1, 0.25, -0.05};
  double sum = 0, previous = errors[0];
  for (double e : errors) {
    sum += e;
    const double expected = 10 * e + 3 * 0.002 * sum + 0.5 * (e - previous) / 0.002;
    previous = e;
    const Eigen::VectorXd tau =
        pid.command(Eigen::VectorXd::Constant(1, 1.0), Eigen::VectorXd::Constant(1, 1.0 - e));
    EXPECT_NEAR(tau[0], expected, 1e-12);
  }
  pid.reset();
  EXPECT_NEAR(pid.command(Eigen::VectorXd::Constant(1, 0.1), Eigen::VectorXd::Zero(1))[0],
              10 * 0.1 + 3 * 0.002 * 0.1, 1e-12);
}

TEST(PidController, BadGainsAreRefusedNamingJointAndGain) {
  PidGains gains = tx40_gains();
  gains.kd[3] = -1;
  try {
    PidController pid(gains);
    FAIL() << "negative kd accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kd of joint 4"), std::string::npos) << e.what();
  }
  gains = tx40_gains();
  gains.sample_time = 0;
  EXPECT_THROW(PidController{gains}, std::invalid_argument);
  gains = tx40_gains();
  gains.ki.resize(5);
  EXPECT_THROW(PidController{gains}, std::invalid_argument);
  gains = tx40_gains();
  gains.kp[0] = 0;
  EXPECT_THROW(PidController{gains}, std::invalid_argument);
}

// The loop of issue 13 written out: KDL's inverse dynamics for M (column by column) and h,
// RK4 with twice the substeps of the simulation, the PID by its formula.
Eigen::MatrixXd independent_loop(const RigidBodyTree& tree, const Eigen::VectorXd& p,
                                 const PidGains& gains, const Eigen::MatrixXd& qr,
                                 Eigen::VectorXd q, Eigen::VectorXd dq, int substeps,
                                 Eigen::MatrixXd* commands) {
  const int n = static_cast<int>(q.size());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  auto acceleration = [&](const Eigen::VectorXd& qq, const Eigen::VectorXd& vv,
                          const Eigen::VectorXd& tau) {
    const Eigen::VectorXd h = test::kdl_inverse_dynamics(tree, qq, vv, zero, p);
    const Eigen::VectorXd g = test::kdl_inverse_dynamics(tree, qq, zero, zero, p);
    Eigen::MatrixXd M(n, n);
    for (int c = 0; c < n; ++c) {
      M.col(c) = test::kdl_inverse_dynamics(tree, qq, zero, Eigen::VectorXd::Unit(n, c), p) - g;
    }
    return Eigen::VectorXd(M.partialPivLu().solve(tau - h));
  };
  Eigen::MatrixXd q_out(qr.rows(), n);
  commands->resize(qr.rows(), n);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), previous = qr.row(0).transpose() - q;
  const double ts = gains.sample_time, h = ts / substeps;
  for (Eigen::Index k = 0; k < qr.rows(); ++k) {
    q_out.row(k) = q.transpose();
    const Eigen::VectorXd e = qr.row(k).transpose() - q;
    sum += e;
    const Eigen::VectorXd tau = gains.kp.cwiseProduct(e) + ts * gains.ki.cwiseProduct(sum) +
                                gains.kd.cwiseProduct(e - previous) / ts;
    previous = e;
    commands->row(k) = tau.transpose();
    for (int s = 0; s < substeps; ++s) {
      const Eigen::VectorXd a1 = acceleration(q, dq, tau);
      const Eigen::VectorXd v2 = dq + h / 2 * a1, a2 = acceleration(q + h / 2 * dq, v2, tau);
      const Eigen::VectorXd v3 = dq + h / 2 * a2, a3 = acceleration(q + h / 2 * v2, v3, tau);
      const Eigen::VectorXd v4 = dq + h * a3, a4 = acceleration(q + h * v3, v4, tau);
      q += h / 6 * (dq + 2 * v2 + 2 * v3 + v4);
      dq += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    }
  }
  return q_out;
}

TEST(ClosedLoopSimulation, EqualsAnIndependentPidLoopOnKdl) {
  const RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
  const std::unique_ptr<IdentificationModel> model = internal::make_shipped_model("tx40");
  ASSERT_NE(model, nullptr);
  test::Random random(21);
  Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
  // No Coulomb friction: the simulation smooths it, the loop here would not.
  for (int k = 0; k < p.size(); ++k) {
    if (is_coulomb(model->standard_param_names()[k])) p[k] = 0;
  }
  std::vector<double> beta(model->num_base_params());
  model->base_from_standard(p.data(), beta.data());
  const PidGains gains = tx40_gains();
  const Eigen::MatrixXd qr = reference(200, gains.sample_time, 6);
  const Eigen::VectorXd q0 = qr.row(0).transpose() + Eigen::VectorXd::Constant(6, 0.01);
  const Eigen::VectorXd dq0 = Eigen::VectorXd::Constant(6, 0.2);
  PidController pid(gains);
  const ClosedLoopRun run =
      simulate_closed_loop(*model, beta, pid, qr, q0, dq0, ClosedLoopOptions{});
  Eigen::MatrixXd commands;
  const Eigen::MatrixXd q = independent_loop(description.tree, p, gains, qr, q0, dq0, 8, &commands);
  EXPECT_LT((run.q - q).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((run.tau_command - commands).cwiseAbs().maxCoeff(), 1e-6 * commands.cwiseAbs().maxCoeff());
  EXPECT_EQ(run.q_measured, run.q);   // no measurement model: the controller sees the truth
  EXPECT_EQ(run.tau_recorded, run.tau_command);
  EXPECT_NEAR(run.t[199], 0.199, 1e-15);
  // The loop does something: the 0.01 rad initial error is being corrected.
  EXPECT_GT((run.q.row(199) - run.q.row(0)).norm(), 0.05);
}

TEST(ClosedLoopSimulation, AwayFromRestThePlantObeysTheModelWithItsFriction) {
  // TX-40 with Coulomb friction on the joints and on the coupled motor 6 (Fcm6): where every
  // velocity is far above the smoothing scale, the recorded state and command satisfy the
  // model's own inverse dynamics with sign(v) friction.
  const RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
  const std::unique_ptr<IdentificationModel> model = internal::make_shipped_model("tx40");
  test::Random random(3);
  Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
  std::vector<double> beta(model->num_base_params());
  model->base_from_standard(p.data(), beta.data());
  PidController pid(tx40_gains());
  const Eigen::MatrixXd qr = reference(1500, 1e-3, 6);
  const ClosedLoopRun run = simulate_closed_loop(*model, beta, pid, qr, qr.row(0).transpose(),
                                                 Eigen::VectorXd::Zero(6), ClosedLoopOptions{});
  const Eigen::VectorXd motor6 = run.dq.col(4) + run.dq.col(5);
  int checked = 0;
  for (Eigen::Index k = 0; k < run.t.size(); ++k) {
    if (run.dq.row(k).cwiseAbs().minCoeff() < 0.2 || std::abs(motor6[k]) < 0.2) continue;
    const Eigen::VectorXd q = run.q.row(k), dq = run.dq.row(k), ddq = run.ddq.row(k);
    Eigen::VectorXd tau(6);
    model->inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    EXPECT_LT((tau - run.tau_command.row(k).transpose()).norm(), 1e-6 * (1 + tau.norm()))
        << "t = " << run.t[k];
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // And the joints track the reference.
  EXPECT_LT((run.q - qr).cwiseAbs().maxCoeff(), 0.1);
}

TEST(ClosedLoopSimulation, MeasurementsAreQuantisedAndNoisyAsAsked) {
  const std::unique_ptr<IdentificationModel> model = internal::make_shipped_model("tx40");
  const RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
  test::Random random(8);
  const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
  std::vector<double> beta(model->num_base_params());
  model->base_from_standard(p.data(), beta.data());
  PidController pid(tx40_gains());
  const Eigen::MatrixXd qr = reference(2000, 1e-3, 6);
  ClosedLoopOptions options;
  options.encoder_resolution = Eigen::VectorXd::Constant(6, 1e-4);
  options.tau_noise = Eigen::VectorXd::Constant(6, 0.5);
  const ClosedLoopRun run =
      simulate_closed_loop(*model, beta, pid, qr, qr.row(0).transpose(), Eigen::VectorXd::Zero(6),
                           options);
  const Eigen::MatrixXd counts = run.q_measured / 1e-4;
  EXPECT_LT((counts - counts.array().round().matrix()).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LE((run.q_measured - run.q).cwiseAbs().maxCoeff(), 0.5e-4 + 1e-12);
  const Eigen::MatrixXd noise = run.tau_recorded - run.tau_command;
  const double sd = std::sqrt(noise.squaredNorm() / static_cast<double>(noise.size()));
  EXPECT_NEAR(sd, 0.5, 0.02);
}

TEST(ClosedLoopSimulation, AnUnstableLoopIsStoppedNamingTheTime) {
  const std::unique_ptr<IdentificationModel> model = internal::make_shipped_model("tx40");
  const RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
  test::Random random(8);
  const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
  std::vector<double> beta(model->num_base_params());
  model->base_from_standard(p.data(), beta.data());
  PidGains gains = tx40_gains();
  gains.kd *= 1e4;  // a derivative gain far beyond what a 1 kHz loop can take
  PidController pid(gains);
  const Eigen::MatrixXd qr = reference(3000, 1e-3, 6);
  try {
    simulate_closed_loop(*model, beta, pid, qr, qr.row(0).transpose() + Eigen::VectorXd::Constant(6, 0.01),
                         Eigen::VectorXd::Zero(6), ClosedLoopOptions{});
    FAIL() << "an unstable loop was simulated to the end";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("stopped at t = "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace modelgen
