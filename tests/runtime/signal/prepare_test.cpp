// prepare_experiment's glue: jittered time stamps resampled on a uniform grid (linear
// interpolation, checked against the signal sampled there), decimate_trajectory keeping rows
// 0, n_d, 2 n_d, ..., and the summaries naming what was done.

#include <cmath>

#include <gtest/gtest.h>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/prepare.hpp"
#include "modelgen/signal/sampling.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

double signal(double t) { return 0.3 * t + std::sin(2.0 * t); }

Trajectory jittered(int samples, double dt, double jitter) {
  test::Random random(12);
  Trajectory x;
  x.source = "jittered.csv";
  x.t.resize(samples);
  x.q.resize(samples, 1);
  x.tau.resize(samples, 1);
  x.dq = Eigen::MatrixXd::Zero(samples, 1);
  x.ddq = Eigen::MatrixXd::Zero(samples, 1);
  for (int s = 0; s < samples; ++s) {
    x.t[s] = s * dt + (s > 0 && s + 1 < samples ? random.uniform(-jitter, jitter) : 0.0);
    x.q(s, 0) = signal(x.t[s]);
    x.tau(s, 0) = 2.0 * signal(x.t[s]);
  }
  return x;
}

TEST(Prepare, ResampledSignalsMatchTheSignalOnTheNewGrid) {
  const Trajectory x = jittered(2001, 0.001, 0.0003);
  const Trajectory y = resample_uniform(x, 0.001);
  ASSERT_EQ(y.t.size(), 2001);
  for (Eigen::Index s = 0; s < y.t.size(); ++s) {
    EXPECT_NEAR(y.t[s], 0.001 * s, 1e-12);
    // Linear interpolation of a smooth signal: error <= max|q''| h^2 / 8 with h <= 1.6 ms.
    EXPECT_NEAR(y.q(s, 0), signal(y.t[s]), 4.0 * 1.6e-3 * 1.6e-3 / 8 + 1e-12) << s;
    EXPECT_NEAR(y.tau(s, 0), 2.0 * signal(y.t[s]), 2 * (4.0 * 1.6e-3 * 1.6e-3 / 8) + 1e-12);
  }
  EXPECT_THROW(resample_uniform(x, 0.0), DataError);
}

TEST(Prepare, AFarTimeStampIsRefusedNotResampledOntoAHugeGrid) {
  // A last time stamp of 1e9 s after 1 ms steps: a uniform grid over it would hold 1e12
  // points (the fuzzer's crash in resample_uniform).
  Trajectory x = jittered(100, 0.001, 0.0);
  x.source = "far.csv";
  x.t[99] = 1e9;
  try {
    resample_uniform(x, 0.001);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("far.csv: error: resampling 100 samples over 1e+09 s", 0),
              0u)
        << e.what();
  }
}

TEST(Prepare, JitteredStampsAreResampledBeforeFiltering) {
  Trajectory x = jittered(4001, 0.001, 0.0003);
  PreparationOptions options;
  options.bandwidth_hz = 1.0;
  const PreparedExperiment prepared = prepare_experiment(x, DriveChain::identity(1), options);
  EXPECT_NE(prepared.summary.find("resampled on a uniform grid of 1 ms"), std::string::npos)
      << prepared.summary;
  EXPECT_NE(prepared.summary.find("parallel decimation by 200"), std::string::npos)
      << prepared.summary;
  // Uniform afterwards: every step 1 ms.
  for (Eigen::Index s = 1; s < prepared.data.t.size(); ++s) {
    EXPECT_NEAR(prepared.data.t[s] - prepared.data.t[s - 1], 0.001, 1e-12);
  }
  // dq of the filtered, resampled positions is the signal's derivative away from the edges.
  for (Eigen::Index s = 0; s < prepared.data.t.size(); ++s) {
    const double t = prepared.data.t[s];
    EXPECT_NEAR(prepared.data.dq(s, 0), 0.3 + 2.0 * std::cos(2.0 * t), 1e-3) << t;
  }
}

TEST(Prepare, DecimatedTrajectoriesKeepEveryNthTime) {
  Trajectory x = jittered(1000, 0.001, 0.0);
  x.has_velocity = true;
  decimate_trajectory(x, 10);
  // Rows 0, 10, 20, ... of the record, those at the edges dropped (decimated_interior).
  const DecimatedRange kept = decimated_interior(1000, 10);
  ASSERT_EQ(x.t.size(), kept.count);
  EXPECT_GE(kept.count, 90);
  for (Eigen::Index s = 0; s < kept.count; ++s) {
    EXPECT_NEAR(x.t[s], 0.01 * static_cast<double>(kept.first + s), 1e-12);
  }
  // A slow signal passes the decimation filter, away from the edges, within the Chebyshev
  // pass band's ripple (0.05 dB at the band edge; ~5e-5 this close to DC).
  for (Eigen::Index s = 10; s < 85; ++s) EXPECT_NEAR(x.q(s, 0), signal(x.t[s]), 1e-4);
  // A fast one (250 Hz, above the 40 Hz cut-off) does not, once the start-up transient of the
  // filter's edges (which it excites: the edges follow the first two samples' slope) is over.
  Trajectory y = jittered(3000, 0.001, 0.0);
  for (Eigen::Index s = 0; s < 3000; ++s) y.q(s, 0) += std::sin(2 * M_PI * 250 * y.t[s]);
  decimate_trajectory(y, 10);
  for (Eigen::Index s = 100; s < 200; ++s) EXPECT_NEAR(y.q(s, 0), signal(y.t[s]), 1e-4);
}

}  // namespace
}  // namespace modelgen

namespace modelgen {
namespace {

TEST(Prepare, HeldTorqueCommandsArePairedHalfASampleLater) {
  // A 20 Hz torque command held over each 1 ms sample acts, in its band, as the command
  // delayed by half a sample: sin(w (t - Ts / 2)). As recorded it is off by w Ts / 2 = 0.063;
  // with torque_hold by the linear interpolation's (w Ts)^2 / 8 = 2e-3 only.
  const double ts = 1e-3, w = 2 * M_PI * 20;
  Trajectory x;
  x.source = "held.csv";
  const Eigen::Index n = 200;
  x.t = Eigen::VectorXd::LinSpaced(n, 0, ts * static_cast<double>(n - 1));
  x.q = Eigen::MatrixXd::Zero(n, 1);
  x.dq = x.q;
  x.ddq = x.q;
  x.tau = (w * x.t).array().sin().matrix();
  x.has_velocity = true;
  PreparationOptions options;
  const PreparedExperiment as_sampled = prepare_experiment(x, DriveChain::identity(1), options);
  options.torque_hold = true;
  const PreparedExperiment held = prepare_experiment(x, DriveChain::identity(1), options);
  const Eigen::VectorXd acting = (w * (x.t.array() - ts / 2)).sin().matrix();
  EXPECT_GT((as_sampled.data.tau.col(0) - acting).cwiseAbs().maxCoeff(), 0.06);
  EXPECT_LT((held.data.tau.col(0) - acting).cwiseAbs().maxCoeff(), 2.1e-3);
  EXPECT_NE(held.summary.find("held over each sample"), std::string::npos) << held.summary;
}

}  // namespace
}  // namespace modelgen

namespace modelgen {
namespace {

// A periodic record (period 1 s, 200 samples each) whose first period carries a decaying start
// transient on the torque, as a controller's integrator settling would.
Trajectory periodic_with_transient(int periods) {
  const int per = 200;
  const double dt = 1.0 / per;
  Trajectory x;
  x.source = "transient.csv";
  const int n = periods * per;
  x.t.resize(n);
  x.q.resize(n, 1);
  x.tau.resize(n, 1);
  for (int s = 0; s < n; ++s) {
    const double t = s * dt, w = 2 * M_PI;
    x.t[s] = t;
    x.q(s, 0) = 0.5 * std::sin(w * t) + 0.2 * std::cos(2 * w * t);
    x.tau(s, 0) = 3.0 * std::cos(w * t) + 5.0 * std::exp(-t / 0.1);  // transient gone by t = 1
  }
  return x;
}

TEST(Prepare, SkippedPeriodsLeaveTheStartTransientOutOfTheAverage) {
  PreparationOptions options;
  options.periodic = true;
  options.period = 1.0;
  options.harmonics = 2;
  const PreparedExperiment all =
      prepare_experiment(periodic_with_transient(4), DriveChain::identity(1), options);
  options.skip_periods = 1;
  const PreparedExperiment skipped =
      prepare_experiment(periodic_with_transient(4), DriveChain::identity(1), options);
  // Averaged over periods 2-4 only, the torque is the periodic part (the transient has decayed
  // to 5 e^-10 = 2.3e-4 at t = 1 s), and its spread over the periods is that remainder.
  double worst = 0;
  for (Eigen::Index s = 0; s < skipped.data.t.size(); ++s) {
    const double clean = 3.0 * std::cos(2 * M_PI * skipped.data.t[s]);
    worst = std::max(worst, std::abs(skipped.data.tau(s, 0) - clean));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(skipped.tau_noise_variance[0], 1e-7);
  // With the transient averaged in, it is noise: a variance orders of magnitude larger.
  EXPECT_GT(all.tau_noise_variance[0], 1e3 * skipped.tau_noise_variance[0]);
  EXPECT_NE(skipped.summary.find("first 1 period(s) (200 samples) left out"), std::string::npos)
      << skipped.summary;
  EXPECT_NE(skipped.summary.find("3 periods of 200 samples"), std::string::npos) << skipped.summary;
}

TEST(Prepare, PredictionRowsLeaveTheSkippedPeriodsOutToo) {
  PreparationOptions options;
  options.periodic = true;
  options.period = 1.0;
  options.harmonics = 2;
  options.skip_periods = 1;
  options.every_sample = true;
  const PreparedExperiment rows =
      prepare_experiment(periodic_with_transient(4), DriveChain::identity(1), options);
  ASSERT_EQ(rows.data.t.size(), 600);
  EXPECT_DOUBLE_EQ(rows.data.t[0], 1.0);
  // The measured torques of the kept rows are the file's own, transient decayed.
  EXPECT_NEAR(rows.data.tau(0, 0), 3.0 + 5.0 * std::exp(-10.0), 1e-12);
  EXPECT_NEAR(rows.data.q(0, 0), 0.2, 1e-9);  // the series at t = 1: 0.5 sin 2pi + 0.2 cos 4pi
}

TEST(Prepare, SkippingAllButOnePeriodIsRefusedNamingTheOption) {
  PreparationOptions options;
  options.periodic = true;
  options.period = 1.0;
  options.skip_periods = 2;
  try {
    prepare_experiment(periodic_with_transient(3), DriveChain::identity(1), options);
    FAIL() << "expected a DataError";
  } catch (const DataError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("transient.csv"), std::string::npos) << message;
    EXPECT_NE(message.find("--skip-periods"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace modelgen
