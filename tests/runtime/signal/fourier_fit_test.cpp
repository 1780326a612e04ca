// Fourier re-estimation of an averaged period (modelgen/signal/fourier_fit.hpp): coefficients
// against the known series and their statistical error, the choice of harmonics against
// coloured noise (Swevers 2002, eq. 15-17).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/QR>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/fourier_fit.hpp"
#include "modelgen/signal/period.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

TEST(FitFourier, RecoversTheCoefficientsOfANoiseFreePeriod) {
  // A prime number of samples per period (Bluestein's transform) and a power of two (plain
  // FFT); the record starts at t = 0.37 s, so the phase of every line must be corrected.
  for (const int samples : {997, 1024}) {
    const double period = 2.0, dt = period / samples;
    const FourierTrajectory f = three_axis_excitation(period);
    Trajectory x = sample(f, dt, 3 * period);
    x.t.array() += 0.37;
    apply_fourier(x, f);  // positions at the shifted times
    const PeriodicAverage avg = average_periods(x, period);
    EXPECT_EQ(select_harmonics(avg), 5) << samples;
    const FourierTrajectory fit = fit_fourier(avg.averaged, avg.period, 5);
    EXPECT_LT((fit.q0 - f.q0).cwiseAbs().maxCoeff(), 1e-10) << samples;
    EXPECT_LT((fit.a - f.a).cwiseAbs().maxCoeff(), 1e-10) << samples;
    EXPECT_LT((fit.b - f.b).cwiseAbs().maxCoeff(), 1e-10) << samples;
    // Harmonics that are not in the signal come out zero.
    const FourierTrajectory wide = fit_fourier(avg.averaged, avg.period, 9);
    EXPECT_LT(wide.a.rightCols(4).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT(wide.b.rightCols(4).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(FitFourier, NoisyAverageGivesCoefficientsWithinTheirStatisticalError) {
  const double period = 2.0, dt = 0.002;
  const int periods = 10, n = 1000;
  const double sigma_q = 2e-3;
  const FourierTrajectory f = three_axis_excitation(period);
  const Trajectory exact = sample(f, dt, periods * period);
  Trajectory noisy = exact;
  noisy.has_velocity = false;
  std::mt19937_64 engine(77);
  add_noise(noisy.q, sigma_q, engine);

  const PeriodicAverage avg = average_periods(noisy, period);
  EXPECT_EQ(select_harmonics(avg), 5);
  const FourierTrajectory fit = fit_fourier(avg.averaged, avg.period, 5);
  // Averaged noise v = sigma^2 / K per sample; each part of a DFT line 2 X / N then has
  // variance 2 v / N, and a = l wf (part), q0 = X_0 / N has variance v / N. 5 sigma bounds.
  const double v = sigma_q * sigma_q / periods;
  const double wf = 2 * kPi / period;
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(fit.q0[j], f.q0[j], 5 * std::sqrt(v / n));
    for (int l = 1; l <= 5; ++l) {
      const double bound = 5 * l * wf * std::sqrt(2 * v / n);
      EXPECT_NEAR(fit.a(j, l - 1), f.a(j, l - 1), bound) << j << " " << l;
      EXPECT_NEAR(fit.b(j, l - 1), f.b(j, l - 1), bound) << j << " " << l;
    }
  }
  // Analytic velocities and accelerations from the fit, against the true ones.
  Trajectory smooth = avg.averaged;
  apply_fourier(smooth, fit);
  EXPECT_TRUE(smooth.has_velocity);
  const double dq_scale = exact.dq.cwiseAbs().maxCoeff();
  EXPECT_LT((smooth.dq - exact.dq.topRows(n)).cwiseAbs().maxCoeff(), 5e-3 * dq_scale);
  // Dropping the noise lines makes the fitted positions closer than the raw averages.
  EXPECT_LT(rms((smooth.q - exact.q.topRows(n)).reshaped()),
            0.3 * rms((avg.averaged.q - exact.q.topRows(n)).reshaped()));
}

// Noise concentrated in a band, as a closed loop's response to its encoder noise is (around
// the loop's bandwidth): white noise through a resonance at `centre_hz`, per column.
Eigen::MatrixXd resonant_noise(Eigen::Index rows, Eigen::Index cols, double dt, double centre_hz,
                               double sigma, std::mt19937_64& engine) {
  std::normal_distribution<double> white(0.0, 1.0);
  const double r = 0.995, w = 2 * kPi * centre_hz * dt;
  Eigen::MatrixXd out(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    double y1 = 0, y2 = 0;
    for (Eigen::Index k = -2000; k < rows; ++k) {  // settled before the record starts
      const double y = 2 * r * std::cos(w) * y1 - r * r * y2 + white(engine);
      y2 = y1;
      y1 = y;
      if (k >= 0) out(k, j) = y;
    }
    out.col(j) *= sigma / std::sqrt(out.col(j).squaredNorm() / static_cast<double>(rows));
  }
  return out;
}

TEST(SelectHarmonics, ColouredNoiseIsNotTakenForSignal) {
  // Five harmonics (0.5 Hz to 2.5 Hz) under noise whose power sits around 20 Hz (harmonic 40):
  // averaged over the periods it is far below the excitation, but a line there is some 25
  // times the mean noise line, and a threshold from the per-axis variance (white) took the
  // lines up to about harmonic 45 for signal. The variance line by line does not.
  const double period = 2.0, dt = 0.002;
  const int periods = 8;
  const FourierTrajectory f = three_axis_excitation(period);
  Trajectory x = sample(f, dt, periods * period);
  x.source = "loop.csv";
  x.tau = torque_of(x);
  std::mt19937_64 engine(17);
  x.q += resonant_noise(x.q.rows(), 3, dt, 20.0, 2e-3, engine);
  const PeriodicAverage avg = average_periods(x, period);
  ASSERT_EQ(avg.q_line_variance.rows(), 501);
  EXPECT_EQ(select_harmonics(avg), 5);
  // The per-axis (white) rule, as select_harmonics applied it before, on the same average.
  PeriodicAverage white = avg;
  white.q_line_variance.resize(0, 0);
  EXPECT_GT(select_harmonics(white), 20);
  // The line variances follow the colour: around 20 Hz (line 40) far above those at 100 Hz.
  EXPECT_GT(avg.q_line_variance.row(40).mean(), 20 * avg.q_line_variance.row(200).mean());
}

TEST(KeepHarmonics, TheAveragedTorqueKeepsItsBandOnly) {
  // A torque with content at harmonics 2 and 7 and a controller's at 60: keep_harmonics(10)
  // leaves exactly the first two; select_torque_harmonics keeps the band that stands out of
  // the torque's noise (7 here), at least the positions' count.
  const double period = 2.0, dt = 0.002;
  const int periods = 6;
  Trajectory x = sample(three_axis_excitation(period), dt, periods * period);
  x.source = "torque.csv";
  const Eigen::ArrayXd w = 2 * kPi / period * x.t.array();
  const Eigen::VectorXd band = (2 * w).sin() + 0.5 * (7 * w).cos();
  const Eigen::VectorXd above = 3.0 * (60 * w + 0.4).sin();
  x.tau = Eigen::MatrixXd(x.t.size(), 3);
  x.tau << band, band + above, band;
  std::mt19937_64 engine(5);
  add_noise(x.tau, 0.05, engine);
  const PeriodicAverage avg = average_periods(x, period);
  EXPECT_EQ(select_torque_harmonics(avg, 5), 60);  // the content at 60 is periodic: signal
  EXPECT_EQ(select_torque_harmonics(avg, 80), 80);
  Trajectory one = avg.averaged;
  keep_harmonics(one, one.tau, 10);
  const Eigen::Index n = one.t.size();
  const double expected_noise = 0.05 / std::sqrt(periods) * std::sqrt(21.0 / n);  // 21 of n lines
  EXPECT_LT(rms(one.tau.col(1) - band.head(n)), 5 * expected_noise);
  EXPECT_GT(rms(avg.averaged.tau.col(1) - band.head(n)), 2.0);
  EXPECT_THROW(keep_harmonics(one, one.tau, 500), DataError);
}

TEST(FitFourier, RejectsTooManyHarmonicsAndAWrongPeriod) {
  Trajectory x = sample(three_axis_excitation(1.0), 0.1, 1.0);  // 10 samples
  x.source = "one.csv";
  EXPECT_NO_THROW(fit_fourier(x, 1.0, 4));
  expect_data_error([&] { fit_fourier(x, 1.0, 5); }, "one.csv", "between 1 and 4");
  expect_data_error([&] { fit_fourier(x, 1.0, 0); }, "one.csv", "between 1 and 4");
  expect_data_error([&] { fit_fourier(x, 1.3, 2); }, "one.csv", "expected one period");
  FourierTrajectory two_axes = three_axis_excitation(1.0);
  two_axes.q0.conservativeResize(2);
  expect_data_error([&] { apply_fourier(x, two_axes); }, "one.csv", "3 axes");
}

}  // namespace
}  // namespace modelgen
