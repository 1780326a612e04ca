// Issue 31, "standard deviations that hold", under a controller: the TX-40 simulated under a
// 1 kHz PID (simulate_closed_loop) along a Fourier reference, with encoder noise that the D
// term turns into torque and torque measurement noise, prepared as the closed-loop test does
// (positions filtered at 100 Hz, decimation by 10, held torques), then IDIM-WLS, IDIM-IV and
// DIDIM. Over independent noise (one simulation per run), each method's reported standard
// deviations must match the spread of its estimates (tests/support/monte_carlo_spread.hpp).

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "modelgen/closed_loop/closed_loop_identification.hpp"
#include "modelgen/closed_loop/closed_loop_simulation.hpp"
#include "modelgen/closed_loop/pid_controller.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/monte_carlo_spread.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/tx40_truth.hpp"

namespace modelgen {
namespace {

constexpr int kRuns = 100;

// Gains for about 15 Hz of position bandwidth on the TX-40's inertias.
PidGains tx40_gains() {
  PidGains gains;
  gains.sample_time = 1e-3;
  gains.kp = (Eigen::VectorXd(6) << 18000, 18000, 3000, 400, 400, 200).finished();
  gains.ki = (Eigen::VectorXd(6) << 1.8e5, 1.8e5, 3e4, 4000, 4000, 2000).finished();
  gains.kd = (Eigen::VectorXd(6) << 260, 260, 40, 5, 5, 2.5).finished();
  return gains;
}

class ClosedLoopCovarianceMonteCarlo : public testing::Test {
 protected:
  void SetUp() override {
    model_ = internal::make_shipped_model("tx40");
    truth_ = test::tx40_true_base(model_->base_param_names());
    gains_ = tx40_gains();
    FourierTrajectory fourier;
    fourier.period = 5.0;
    test::Random random(7);
    fourier.q0 = random.vector(6, -0.3, 0.3);
    fourier.a.resize(6, 5);
    fourier.b.resize(6, 5);
    for (Eigen::Index j = 0; j < 6; ++j) {
      for (Eigen::Index l = 0; l < 5; ++l) {
        fourier.a(j, l) = random.uniform(-0.4, 0.4);
        fourier.b(j, l) = random.uniform(-0.4, 0.4);
      }
    }
    qr_ = sample(fourier, gains_.sample_time, 2 * fourier.period).q;
  }

  // One noisy closed-loop record, prepared.
  ClosedLoopRecord record(std::uint64_t seed) const {
    PidController controller(gains_);
    ClosedLoopOptions options;
    options.encoder_resolution = Eigen::VectorXd::Constant(6, 2 * M_PI / (1 << 17) / 32);
    options.q_noise = Eigen::VectorXd::Constant(6, 2e-5);
    options.tau_noise = Eigen::VectorXd::Constant(6, 0.2);
    options.seed = seed;
    const std::vector<double> beta(truth_.data(), truth_.data() + truth_.size());
    const ClosedLoopRun run = simulate_closed_loop(
        *model_, beta, controller, qr_, qr_.row(0).transpose(), Eigen::VectorXd::Zero(6), options);
    Trajectory raw;
    raw.source = "simulated TX-40 under PID";
    raw.t = run.t;
    raw.q = run.q_measured;
    raw.tau = run.tau_recorded;
    raw.dq = raw.ddq = Eigen::MatrixXd::Zero(run.t.size(), 6);
    PreparationOptions preparation;
    preparation.cutoff_hz = 100;
    preparation.decimation = 10;
    preparation.torque_hold = true;
    const PreparedExperiment prepared = prepare_experiment(raw, model_->drive_chain(), preparation);
    ClosedLoopRecord r;
    r.prepared = prepared.data;
    r.decimation = prepared.decimation;
    r.torque_hold = true;
    r.first_row = std::lround((prepared.data.t[0] - run.t[0]) / gains_.sample_time);
    r.qr = qr_;
    r.q0 = run.q_measured.row(0).transpose();
    r.dq0 = Eigen::VectorXd::Zero(6);
    return r;
  }

  // `runs` records, each fitted by `method`: IDIM-WLS on the prepared, decimated record (as fit
  // --method wls does), IDIM-IV or DIDIM.
  void check(const std::string& method, int runs) {
    test::SpreadCheck spread(truth_.size());
    for (int run = 0; run < runs; ++run) {
      const ClosedLoopRecord r = record(100 + static_cast<std::uint64_t>(run));
      LeastSquaresResult fit;
      if (method == "IDIM-WLS") {
        IdentifyOptions options;
        options.decimation = {r.decimation};
        fit = identify(*model_, {r.prepared}, Method::kWls, options).fit;
      } else {
        const ClosedLoopMethod m =
            method == "IDIM-IV" ? ClosedLoopMethod::kIv : ClosedLoopMethod::kDidim;
        fit = identify_closed_loop(*model_, m, gains_, {r}).id.fit;
      }
      spread.add(fit.value, fit.std_dev);
    }
    spread.expect_covered(method + ", closed loop");
  }

  std::unique_ptr<IdentificationModel> model_;
  Eigen::VectorXd truth_;
  PidGains gains_;
  Eigen::MatrixXd qr_;
};

TEST_F(ClosedLoopCovarianceMonteCarlo, WeightedLeastSquares) { check("IDIM-WLS", kRuns); }

TEST_F(ClosedLoopCovarianceMonteCarlo, InstrumentalVariables) { check("IDIM-IV", kRuns); }

TEST_F(ClosedLoopCovarianceMonteCarlo, Didim) { check("DIDIM", kRuns); }

}  // namespace
}  // namespace modelgen
