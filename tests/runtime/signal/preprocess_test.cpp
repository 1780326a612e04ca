// Data preparation: period averaging, noise variance and Fourier re-estimation checked against
// the known trajectory and noise they were simulated with (Swevers 2002, eq. 15-17); filters
// against the analytic Butterworth and Chebyshev responses with bilinear pre-warping, zero
// phase, derivatives of filtered signals against analytic ones, and the decimation's
// linearity (Gautier & Briot eq. 13-14).

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/differentiation.hpp"
#include "modelgen/signal/filter_plan.hpp"
#include "modelgen/signal/fourier_fit.hpp"
#include "modelgen/signal/lowpass.hpp"
#include "modelgen/signal/period.hpp"

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

#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr double kPi = std::numbers::pi;

// Three axes, five harmonics, offsets; axis 3 moves little.
FourierTrajectory three_axis_excitation(double period) {
  FourierTrajectory f;
  f.period = period;
  f.q0 = Eigen::Vector3d(0.3, -1.2, 0.05);
  f.a = (Eigen::MatrixXd(3, 5) << 0.8, -0.3, 0.2, 0.1, 0.1,  //
         0.4, 0.5, -0.2, 0.0, 0.15,                          //
         0.02, 0.0, 0.01, -0.01, 0.005)
            .finished();
  f.b = (Eigen::MatrixXd(3, 5) << -0.2, 0.4, 0.0, -0.1, 0.05,  //
         0.3, -0.1, 0.25, 0.1, -0.1,                           //
         0.0, 0.01, 0.0, 0.005, -0.01)
            .finished();
  return f;
}

// A torque that depends on the motion, so that it is periodic like it.
Eigen::MatrixXd torque_of(const Trajectory& x) { return 5.0 * x.q + 0.2 * x.ddq; }

void add_noise(Eigen::MatrixXd& m, double sigma, std::mt19937_64& engine) {
  std::normal_distribution<double> noise(0.0, sigma);
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index s = 0; s < m.rows(); ++s) m(s, j) += noise(engine);
  }
}

// Least-squares fit y(t) = A sin(w t) + B cos(w t) + C: amplitude and phase of the sine,
// an estimate independent of the filters.
struct SineFit {
  double amplitude, phase;
};
SineFit fit_sine(const Eigen::VectorXd& t, const Eigen::VectorXd& y, double frequency_hz) {
  Eigen::MatrixXd basis(t.size(), 3);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    basis(k, 0) = std::sin(2 * kPi * frequency_hz * t[k]);
    basis(k, 1) = std::cos(2 * kPi * frequency_hz * t[k]);
    basis(k, 2) = 1.0;
  }
  const Eigen::Vector3d c = basis.colPivHouseholderQr().solve(y);
  return {std::hypot(c[0], c[1]), std::atan2(c[1], c[0])};
}

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / v.size()); }

// Expects `call` to throw DataError starting with the source name and containing `phrase`.
template <typename Call>
void expect_data_error(Call call, const std::string& source, const std::string& phrase) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one containing '" << phrase << "'";
  } catch (const DataError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(source + ": error: ", 0), 0u) << what;
    EXPECT_NE(what.find(phrase), std::string::npos) << what;
  }
}

// ---------------------------------------------------------------------------------------------
// Periodic excitation

TEST(AveragePeriods, AveragesAndNoiseVarianceMatchTheSimulatedNoise) {
  const double period = 2.0, dt = 0.002;  // N = 1000
  const int periods = 10;
  const double sigma_q = 2e-3, sigma_tau = 0.5;
  const FourierTrajectory f = three_axis_excitation(period);
  const Trajectory exact = sample(f, dt, periods * period);
  Trajectory noisy = exact;
  noisy.source = "run1.csv";
  noisy.has_velocity = false;
  noisy.tau = torque_of(exact);
  std::mt19937_64 engine(20240611);
  add_noise(noisy.q, sigma_q, engine);
  add_noise(noisy.tau, sigma_tau, engine);

  const PeriodicAverage avg = average_periods(noisy, period);
  ASSERT_EQ(avg.periods, periods);
  ASSERT_EQ(avg.samples_per_period, 1000);
  EXPECT_EQ(avg.dropped_samples, 0);
  EXPECT_EQ(avg.averaged.source, "run1.csv");
  EXPECT_NEAR(avg.period, period, 1e-12);
  const Eigen::Index n = avg.samples_per_period;
  const Eigen::MatrixXd q_true = exact.q.topRows(n), tau_true = torque_of(exact).topRows(n);
  for (int j = 0; j < 3; ++j) {
    // The average of K samples has noise sigma / sqrt(K); the rms over 1000 samples estimates
    // it to about 2% (1 / sqrt(2 N)), so 10% is a 4.5-sigma bound.
    const double q_expected = sigma_q / std::sqrt(periods);
    const double tau_expected = sigma_tau / std::sqrt(periods);
    EXPECT_NEAR(rms(avg.averaged.q.col(j) - q_true.col(j)) / q_expected, 1.0, 0.1) << j;
    EXPECT_NEAR(rms(avg.averaged.tau.col(j) - tau_true.col(j)) / tau_expected, 1.0, 0.1) << j;
    // N (P - 1) = 9000 degrees of freedom: relative standard deviation sqrt(2 / 9000) = 1.5%;
    // 6% is 4 sigma, and tight enough to reject the (P - 1) / P = 0.9 bias of dividing by
    // P (P N - 1).
    EXPECT_NEAR(avg.q_noise_variance[j] / (q_expected * q_expected), 1.0, 0.06) << j;
    EXPECT_NEAR(avg.tau_noise_variance[j] / (tau_expected * tau_expected), 1.0, 0.06) << j;
  }
}

TEST(AveragePeriods, NoiseFreeRecordAveragesToOnePeriodExactly) {
  const FourierTrajectory f = three_axis_excitation(1.5);
  Trajectory x = sample(f, 0.005, 4 * 1.5);  // 300 per period
  x.tau = torque_of(x);
  const PeriodicAverage avg = average_periods(x, 1.5);
  ASSERT_EQ(avg.averaged.q.rows(), 300);
  EXPECT_LT((avg.averaged.q - x.q.topRows(300)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((avg.averaged.ddq - x.ddq.topRows(300)).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT(avg.q_noise_variance.maxCoeff(), 1e-26);
  EXPECT_EQ(avg.averaged.t, x.t.head(300));
}

TEST(AveragePeriods, ReportsTheDroppedHalfPeriod) {
  const double period = 2.0, dt = 0.01;
  Trajectory x = sample(three_axis_excitation(period), dt, 2.5 * period);  // 500 samples
  const PeriodicAverage avg = average_periods(x, period);
  EXPECT_EQ(avg.periods, 2);
  EXPECT_EQ(avg.samples_per_period, 200);
  EXPECT_EQ(avg.dropped_samples, 100);
  EXPECT_NEAR(avg.dropped_seconds, 0.5 * period, 1e-12);
}

TEST(AveragePeriods, RejectsBadRecordsWithTheFileName) {
  const double period = 2.0, dt = 0.01;
  Trajectory x = sample(three_axis_excitation(period), dt, 4 * period);
  x.source = "data/run7.csv";

  Trajectory jitter = x;
  jitter.t[123] += 0.3 * dt;
  expect_data_error([&] { average_periods(jitter, period); }, x.source, "not uniform");
  expect_data_error([&] { average_periods(jitter, period); }, x.source, "sample 124");
  // 200.5 samples per period: misaligned by 2 samples after 4 periods.
  expect_data_error([&] { average_periods(x, 200.5 * dt); }, x.source,
                    "not a whole number of samples");
  Trajectory short_record = sample(three_axis_excitation(period), dt, 1.5 * period);
  short_record.source = x.source;
  expect_data_error([&] { average_periods(short_record, period); }, x.source,
                    "at least 2 whole periods");
  expect_data_error([&] { average_periods(x, 0.0); }, x.source, "positive");
  Trajectory nan = x;
  nan.tau(17, 1) = std::nan("");
  expect_data_error([&] { average_periods(nan, period); }, x.source, "column 'tau2'");
}

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

TEST(DetectPeriod, FindsTheCommonPeriodOfMultiSinesWithAWeakFundamental) {
  // Axis 1 is mostly its third harmonic, axis 2 its second and fifth: the dominant lines
  // suggest T/3 and T/2, only T brings both back into phase.
  FourierTrajectory f;
  f.period = 2.0;
  f.q0 = Eigen::Vector2d(0.1, 0.2);
  f.a = (Eigen::MatrixXd(2, 5) << 0.05, 0, 1.0, 0, 0, 0, 0.8, 0, 0, 0.6).finished();
  f.b = (Eigen::MatrixXd(2, 5) << 0.02, 0, 0.3, 0, 0, 0, 0.1, 0, 0, -0.4).finished();
  const double dt = 0.002;
  for (const double period : {2.0, 2.0 + 0.37 * dt}) {  // on and off the sample grid
    f.period = period;
    Trajectory x = sample(f, dt, 4.3 * period);
    std::mt19937_64 engine(5);
    add_noise(x.q, 1e-3, engine);
    EXPECT_NEAR(detect_period(x), period, 0.02 * dt) << period;
  }
  // Dense sampling (5 kHz, 20000 samples per period, 6 periods): the peaks are flat over
  // many lags, yet the period is found closely enough to average the record with it directly.
  const FourierTrajectory slow = three_axis_excitation(4.0);
  Trajectory dense = sample(slow, 0.0002, 6 * slow.period);
  std::mt19937_64 engine(6);
  add_noise(dense.q, 1e-4, engine);
  const double period = detect_period(dense);
  EXPECT_NEAR(period, slow.period, 0.01 * 0.0002);
  const PeriodicAverage avg = average_periods(dense, period);
  EXPECT_EQ(avg.samples_per_period, 20000);
  EXPECT_EQ(avg.periods, 6);
}

TEST(DetectPeriod, NoPeriodOrTooFewPeriodsAreErrors) {
  Trajectory noise = sample(three_axis_excitation(2.0), 0.01, 10.0);
  noise.source = "noise.csv";
  noise.q.setZero();
  std::mt19937_64 engine(9);
  add_noise(noise.q, 1.0, engine);
  expect_data_error([&] { detect_period(noise); }, "noise.csv", "no period found");

  Trajectory still = noise;
  still.q.setConstant(0.4);
  expect_data_error([&] { detect_period(still); }, "noise.csv", "do not move");

  Trajectory ramp = noise;
  for (Eigen::Index s = 0; s < ramp.q.rows(); ++s) ramp.q.row(s).setConstant(0.01 * s);
  expect_data_error([&] { detect_period(ramp); }, "noise.csv", "never decorrelate");

  Trajectory short_record = sample(three_axis_excitation(2.0), 0.01, 1.6 * 2.0);
  short_record.source = "short.csv";
  expect_data_error([&] { detect_period(short_record); }, "short.csv", "at least 2 periods");
}

// ---------------------------------------------------------------------------------------------
// Filters

// |H| of the digital Butterworth low-pass made by the pre-warped bilinear transform.
double butterworth_gain(double f, double fc, double fs, int order) {
  const double w = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
  return 1.0 / std::sqrt(1.0 + std::pow(w, 2.0 * order));
}

double chebyshev_polynomial(int n, double w) {
  return w <= 1.0 ? std::cos(n * std::acos(w)) : std::cosh(n * std::acosh(w));
}

TEST(Butterworth, ResponseMatchesTheAnalyticMagnitude) {
  const double fs = 1000, fc = 50;
  for (int order = 1; order <= 9; ++order) {
    const LowPassFilter filter = butterworth_lowpass(order, fc, fs);
    EXPECT_NEAR(std::abs(filter.response(0.0)), 1.0, 1e-14);
    EXPECT_NEAR(20 * std::log10(std::abs(filter.response(fc))), -3.0103, 1e-4) << order;
    for (const double f : {5.0, 25.0, 49.0, 51.0, 80.0, 150.0, 300.0, 499.0}) {
      const double expected = butterworth_gain(f, fc, fs, order);
      EXPECT_NEAR(std::abs(filter.response(f)) / expected, 1.0, 1e-9) << order << " " << f;
    }
  }
}

TEST(Butterworth, FilteredSinesHaveTheExpectedGainOnceAndTwice) {
  const double fs = 1000, fc = 50;
  const int order = 4;
  const LowPassFilter filter = butterworth_lowpass(order, fc, fs);
  const Eigen::Index n = 20000;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  for (const double f : {10.0, 50.0, 120.0}) {
    Eigen::MatrixXd x(n, 2);
    x.col(0) = (2 * kPi * f * t).array().sin();
    x.col(1) = x.col(0);
    filter_causal(filter, x.col(0));
    filtfilt(filter, x.col(1));
    // Steady state, far from both ends; a whole number of cycles of every frequency here.
    const Eigen::Index from = 5000, len = 10000;
    const SineFit once = fit_sine(t.segment(from, len), x.col(0).segment(from, len), f);
    const SineFit twice = fit_sine(t.segment(from, len), x.col(1).segment(from, len), f);
    const double gain = butterworth_gain(f, fc, fs, order);
    EXPECT_NEAR(once.amplitude / gain, 1.0, 1e-6) << f;
    EXPECT_NEAR(twice.amplitude / (gain * gain), 1.0, 1e-6) << f;
    EXPECT_NEAR(twice.phase, 0.0, 1e-6) << f;  // zero phase: not shifted
  }
  // -3 dB after one pass, -6 dB after filtfilt at the cut-off.
  EXPECT_NEAR(20 * std::log10(butterworth_gain(fc, fc, fs, order)), -3.0103, 1e-4);
}

TEST(Chebyshev, ResponseMatchesTheAnalyticMagnitude) {
  const double fs = 1.0, fc = 0.04, ripple = 0.05;
  const double eps2 = std::pow(10.0, ripple / 10) - 1;
  for (const int order : {3, 8}) {
    const LowPassFilter filter = chebyshev1_lowpass(order, ripple, fc, fs);
    // Unit DC gain: an even order is scaled up from its ripple minimum at DC.
    const double g = order % 2 == 0 ? 1 + eps2 : 1.0;
    for (const double f : {0.0, 0.01, 0.02, 0.035, 0.04, 0.05, 0.1, 0.3, 0.49}) {
      const double w = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
      const double tn = chebyshev_polynomial(order, w);
      const double expected = std::sqrt(g / (1 + eps2 * tn * tn));
      EXPECT_NEAR(std::abs(filter.response(f)) / expected, 1.0, 1e-9) << order << " " << f;
    }
  }
}

TEST(Filtfilt, KeepsConstantsRampsAndLowOrderPolynomialsAwayFromTheEdges) {
  const double fs = 1000;
  const LowPassFilter filter = butterworth_lowpass(4, 20, fs);
  const Eigen::Index n = 4000;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  Eigen::MatrixXd x(n, 3);
  x.col(0).setConstant(2.5);
  x.col(1) = 0.3 - 1.7 * t.array();
  x.col(2) = 0.2 + t.array() * (0.5 + t.array() * (-0.8 + 0.3 * t.array()));
  const Eigen::MatrixXd before = x;
  filtfilt(filter, x);
  EXPECT_LT((x.col(0) - before.col(0)).cwiseAbs().maxCoeff(), 1e-12);
  // Odd reflection continues a ramp exactly: no end effect at all.
  EXPECT_LT((x.col(1) - before.col(1)).cwiseAbs().maxCoeff(), 1e-9);
  // |H|^2 = 1 - O(w^8): polynomials below degree 8 pass unchanged inside the record; the
  // reflected curvature disturbs the ends only.
  EXPECT_LT((x.col(2) - before.col(2)).segment(500, n - 1000).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(FilterPositions, CentralDifferencesOfFilteredSignalsMatchTheAnalyticDerivatives) {
  const double fs = 1000, h = 1 / fs, f = 1.3, w = 2 * kPi * f;
  const Eigen::Index n = 5000;
  Trajectory x;
  x.source = "sine.csv";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q.resize(n, 2);
  x.q.col(0) = 0.7 * (w * x.t.array()).sin() + 0.2;
  x.q.col(1) = 0.1 + x.t.array() * (0.4 + x.t.array() * (-0.3 + 0.05 * x.t.array()));
  x.tau = Eigen::MatrixXd::Zero(n, 2);
  auto errors = [&](const Trajectory& y) {
    const Eigen::ArrayXd t = y.t.array();
    const Eigen::Index from = 500, len = n - 2 - 1000;  // away from the edges
    const Eigen::ArrayXd dq0 = 0.7 * w * (w * t).cos(), ddq0 = -0.7 * w * w * (w * t).sin();
    const Eigen::ArrayXd dq1 = 0.4 + t * (-0.6 + 0.15 * t), ddq1 = -0.6 + 0.3 * t;
    return Eigen::Vector4d((y.dq.col(0).array() - dq0).segment(from, len).abs().maxCoeff(),
                           (y.ddq.col(0).array() - ddq0).segment(from, len).abs().maxCoeff(),
                           (y.dq.col(1).array() - dq1).segment(from, len).abs().maxCoeff(),
                           (y.ddq.col(1).array() - ddq1).segment(from, len).abs().maxCoeff());
  };
  // Noise-free: the filter passes 1.3 Hz (|H|^2 = 1 - 3e-10 at a 20 Hz cut-off) and cubics
  // unchanged; what remains is the central differences' h^2 q''' / 6 on dq and h^2 q'''' / 12
  // on ddq (zero for the cubic).
  Trajectory clean = x;
  filter_positions(clean, 20.0);
  ASSERT_EQ(clean.t.size(), n - 2);
  ASSERT_TRUE(clean.has_velocity);
  const Eigen::Vector4d e = errors(clean);
  EXPECT_LT(e[0], 1.2 * h * h * 0.7 * std::pow(w, 3) / 6);
  EXPECT_LT(e[1], 1.2 * h * h * 0.7 * std::pow(w, 4) / 12);
  EXPECT_LT(e[2], 1.2 * h * h * 0.3 / 6);
  EXPECT_LT(e[3], 1e-5);

  // Encoder-like noise of 1e-6 rad: low-passed at 20 Hz its derivatives have a standard
  // deviation of about sigma sqrt(2 fc / fs) (2 pi fc)^k / sqrt(2k + 1), k = 1, 2; 6 sigma.
  Trajectory noisy = x;
  std::mt19937_64 engine(3);
  add_noise(noisy.q, 1e-6, engine);
  filter_positions(noisy, 20.0);
  const double band = 1e-6 * std::sqrt(2 * 20 / fs), wc = 2 * kPi * 20;
  const Eigen::Vector4d en = errors(noisy);
  EXPECT_LT(en[0], e[0] + 6 * band * wc / std::sqrt(3.0));
  EXPECT_LT(en[1], e[1] + 6 * band * wc * wc / std::sqrt(5.0));
  EXPECT_LT(en[2], e[2] + 6 * band * wc / std::sqrt(3.0));
  EXPECT_LT(en[3], e[3] + 6 * band * wc * wc / std::sqrt(5.0));
  std::printf("derivative errors noise-free %.3g %.3g %.3g %.3g, noisy %.3g %.3g %.3g %.3g\n", e[0],
              e[1], e[2], e[3], en[0], en[1], en[2], en[3]);

  expect_data_error([&] { filter_positions(x, 600.0); }, "sine.csv", "Nyquist frequency 500 Hz");
}

// ---------------------------------------------------------------------------------------------
// Decimation

TEST(Decimate, KeepsTheLowSineAndRemovesTheHighOne) {
  const double fs = 1000;
  const int factor = 10;  // new Nyquist 50 Hz, filter cut-off 40 Hz
  const Eigen::Index n = 20001;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  const double low = 5, high = 170;
  const Eigen::VectorXd slow = (2 * kPi * low * t).array().sin();
  const Eigen::VectorXd y = slow + 0.8 * (2 * kPi * high * t).array().sin().matrix();
  const Eigen::MatrixXd out = decimate(y, factor);
  ASSERT_EQ(out.rows(), 2001);
  ASSERT_EQ(decimated_rows(n, factor), 2001);
  // The pass band gain of the zero-phase Chebyshev filter at 5 Hz, from its analytic form.
  const double eps2 = std::pow(10.0, 0.005) - 1;
  const double wn = std::tan(kPi * low / fs) / std::tan(kPi * 0.04);
  const double tn = chebyshev_polynomial(8, wn);
  const double gain2 = (1 + eps2) / (1 + eps2 * tn * tn);
  double worst = 0;
  for (Eigen::Index i = 50; i < out.rows() - 50; ++i) {
    worst = std::max(worst, std::abs(out(i, 0) - gain2 * slow[i * factor]));
  }
  EXPECT_LT(worst, 1e-6);
  // The whole record, ends included, stays close to the slow sine.
  EXPECT_LT((out.col(0) - gain2 * slow(Eigen::seq(0, n - 1, factor))).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Decimate, IsLinearSoYAndWStayConsistent) {
  // Gautier & Briot eq. 14: decimating Y = W chi column by column keeps Y = W chi.
  const Eigen::Index n = 30000;
  std::mt19937_64 engine(11);
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, 6);
  add_noise(w, 1.0, engine);
  for (Eigen::Index s = 0; s < n; ++s) w(s, 2) += std::sin(0.001 * s);
  const Eigen::VectorXd chi = (Eigen::VectorXd(6) << 1.5, -2, 0.3, 4, -0.7, 0.01).finished();
  const Eigen::VectorXd y = w * chi;
  for (const int factor : {1, 3, 25}) {
    const Eigen::MatrixXd wd = decimate(w, factor);
    const Eigen::MatrixXd yd = decimate(y, factor);
    EXPECT_LT((yd - wd * chi).cwiseAbs().maxCoeff(), 1e-11 * y.cwiseAbs().maxCoeff()) << factor;
  }
  // Blocks of rows of a larger matrix, decimated in place into blocks of the output.
  Eigen::MatrixXd out(decimated_rows(n / 2, 4), 6);
  decimate(w.middleRows(n / 2, n / 2), 4, out);
  EXPECT_LT((out - decimate(Eigen::MatrixXd(w.bottomRows(n / 2)), 4)).cwiseAbs().maxCoeff(), 1e-15);
  Eigen::MatrixXd wrong(10, 6);
  EXPECT_THROW(decimate(w, 4, wrong), std::invalid_argument);
}

TEST(Decimate, WorksOnOneJointsRowsOfAnInterleavedRegressor) {
  // W stacked sample by sample, joint by joint (row s n + i), as the IDIM is assembled: joint
  // i's rows are every n-th row. Decimated through strided views, in and out, without copies.
  const Eigen::Index samples = 4000, joints = 3, nb = 5;
  const int factor = 8;
  std::mt19937_64 engine(13);
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(samples * joints, nb);
  add_noise(w, 1.0, engine);
  const Eigen::Index rows = decimated_rows(samples, factor);
  Eigen::MatrixXd out(rows * joints, nb);
  using Stride = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
  for (Eigen::Index i = 0; i < joints; ++i) {
    const Eigen::Map<const Eigen::MatrixXd, 0, Stride> joint(w.data() + i, samples, nb,
                                                             Stride(w.outerStride(), joints));
    Eigen::Map<Eigen::MatrixXd, 0, Stride> joint_out(out.data() + i, rows, nb,
                                                     Stride(out.outerStride(), joints));
    decimate(joint, factor, joint_out);
    // The same joint's rows copied into a plain matrix first.
    Eigen::MatrixXd plain(samples, nb);
    for (Eigen::Index s = 0; s < samples; ++s) plain.row(s) = w.row(s * joints + i);
    const Eigen::MatrixXd expected = decimate(plain, factor);
    for (Eigen::Index s = 0; s < rows; ++s) {
      EXPECT_EQ(out.row(s * joints + i), expected.row(s)) << i << " " << s;
    }
  }
  EXPECT_EQ(decimate(Eigen::MatrixXd(0, 4), factor).rows(), 0);
}

TEST(DecimationStages, SplitFactorsIntoStagesOfAtMostTen) {
  EXPECT_EQ(decimation_stages(1), std::vector<int>{});
  EXPECT_EQ(decimation_stages(7), std::vector<int>{7});
  EXPECT_EQ(decimation_stages(100), (std::vector<int>{10, 10}));
  EXPECT_EQ(decimation_stages(384), (std::vector<int>{8, 8, 6}));
  EXPECT_EQ(decimation_stages(1000), (std::vector<int>{10, 10, 10}));
  for (int factor = 2; factor <= 5000; ++factor) {
    if (decimation_factor_below(factor) != factor) continue;
    int product = 1;
    for (int stage : decimation_stages(factor)) {
      EXPECT_LE(stage, 10) << factor;
      product *= stage;
    }
    EXPECT_EQ(product, factor);
  }
  // A prime above 10 cannot be a stage: refused, with the nearest factors that can.
  try {
    decimation_stages(385);
    ADD_FAILURE() << "385 = 5 x 7 x 11 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("prime factor 11"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("use 384 or 392"), std::string::npos) << e.what();
  }
  EXPECT_THROW(decimate(Eigen::VectorXd::Zero(100), 11), std::invalid_argument);
  EXPECT_EQ(decimation_factor_below(71), 70);
  EXPECT_EQ(decimation_factor_below(13), 12);
}

TEST(Decimate, StagedKeepsAnInBandSineAndRemovesBroadbandContent) {
  // 1 kHz, factor 100 (10 x 10): a 1 Hz sine under a multi-sine of 200 lines from 20 Hz to the
  // Nyquist frequency, three times its amplitude (torque content a D term puts above the band).
  const double fs = 1000, fin = 1.0;
  const int factor = 100;
  const Eigen::Index n = 40001;
  std::mt19937_64 engine(3);
  std::uniform_real_distribution<double> phase(0, 2 * kPi);
  Eigen::VectorXd x(n), slow(n);
  std::vector<double> phases(200);
  for (double& p : phases) p = phase(engine);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / fs;
    slow[k] = std::sin(2 * kPi * fin * t + 0.3);
    double out_of_band = 0;
    for (int l = 0; l < 200; ++l) out_of_band += std::sin(2 * kPi * (20 + 2.4 * l) * t + phases[l]);
    x[k] = slow[k] + 3 * std::sqrt(2.0 / 200) * out_of_band;
  }
  // Expected gain at 1 Hz: the two stages' zero-phase gains |H|^2, each from the analytic
  // Chebyshev magnitude at its own rate (cut-offs 40 Hz at 1 kHz, 4 Hz at 100 Hz).
  const double eps2 = std::pow(10.0, 0.005) - 1;
  double gain = 1;
  for (const double rate : {1000.0, 100.0}) {
    const double w = std::tan(kPi * fin / rate) / std::tan(kPi * 0.04);
    const double tn = chebyshev_polynomial(8, w);
    gain *= (1 + eps2) / (1 + eps2 * tn * tn);
  }
  const Eigen::VectorXd out = decimate(x, factor);
  double worst = 0;
  // Away from the ends (whose pinned samples decay over some ten rows).
  for (Eigen::Index i = out.size() / 4; i < 3 * out.size() / 4; ++i) {
    worst = std::max(worst, std::abs(out[i] - gain * slow[i * factor]));
  }
  EXPECT_LT(worst, 1e-4);
  // The same operation on every column: eq. 14 still holds through the stages.
  Eigen::MatrixXd w(n, 3);
  w << x, slow, Eigen::VectorXd::LinSpaced(n, -1, 1);
  const Eigen::Vector3d chi(0.7, -2, 5);
  const Eigen::VectorXd y = w * chi;
  EXPECT_LT((decimate(y, factor) - decimate(w, factor) * chi).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(DecimatedInterior, DropsTheRowsTheEndSamplesDominate) {
  // White noise: filtfilt's odd reflection pins each end to its end sample, so row 0 carries
  // that sample's full-band noise. The kept rows carry no more than 1.5 x the noise of the
  // rows in the middle (averaged over seeds); rows 0 and last, which do, are dropped.
  for (const int factor : {10, 100, 1000}) {
    const Eigen::Index n = 100 * factor + 1;
    const DecimatedRange kept = decimated_interior(n, factor);
    const Eigen::Index rows = decimated_rows(n, factor);
    EXPECT_GT(kept.first, 0) << factor;
    EXPECT_LT(kept.first + kept.count, rows) << factor;
    EXPECT_GT(kept.count, rows * 8 / 10) << factor;
    Eigen::VectorXd power = Eigen::VectorXd::Zero(rows);
    const int seeds = 40;
    for (int seed = 0; seed < seeds; ++seed) {
      std::mt19937_64 engine(seed);
      Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(n, 1);
      add_noise(noise, 1.0, engine);
      power += decimate(noise, factor).col(0).array().square().matrix() / seeds;
    }
    const double middle = power.segment(rows / 4, rows / 2).mean();
    EXPECT_GT(power[0], 5 * middle) << factor;
    for (Eigen::Index i = kept.first; i < kept.first + kept.count; ++i) {
      EXPECT_LT(power[i], 1.5 * 1.5 * middle) << factor << " row " << i;
    }
    // decimate_interior is decimate's rows [first, first + count).
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, 1);
    std::mt19937_64 engine(99);
    add_noise(x, 1.0, engine);
    EXPECT_EQ(decimate_interior(x, factor), decimate(x, factor).middleRows(kept.first, kept.count));
  }
}

// ---------------------------------------------------------------------------------------------
// Choosing the filters

TEST(PlanFiltering, FollowsTheDocumentedRule) {
  const FilterPlan plan = plan_filtering(5000, 5);
  EXPECT_DOUBLE_EQ(plan.position_cutoff_hz, 50);
  EXPECT_EQ(plan.decimation_factor, 200);  // 0.8 * 2500 / 200 = 10 Hz = 2 x 5 Hz
  EXPECT_DOUBLE_EQ(plan.decimation_cutoff_hz, 10);
  EXPECT_NE(plan.explanation.find("decimated by 200"), std::string::npos) << plan.explanation;

  const FilterPlan fast = plan_filtering(5000, 300);  // 10 x 300 > 0.8 x 2500
  EXPECT_DOUBLE_EQ(fast.position_cutoff_hz, 2000);
  EXPECT_EQ(fast.decimation_factor, 3);  // 2000 / 3 = 667 Hz >= 600 Hz; 2000 / 4 < 600
  EXPECT_NE(fast.explanation.find("0.8 x Nyquist"), std::string::npos) << fast.explanation;

  EXPECT_EQ(plan_filtering(1000, 300).decimation_factor, 1);
  // The rule's 71 (400 / 71 = 5.6 Hz >= 2 x 2.8 Hz) has a prime above 10: 70 = 10 x 7 runs in
  // stages, and the explanation shows them.
  const FilterPlan staged = plan_filtering(1000, 2.81);
  EXPECT_EQ(staged.decimation_factor, 70);
  EXPECT_NE(staged.explanation.find("stages 10 x 7"), std::string::npos) << staged.explanation;
  EXPECT_THROW(plan_filtering(1000, 600), std::invalid_argument);
  EXPECT_THROW(plan_filtering(0, 1), std::invalid_argument);
}

TEST(EstimateBandwidth, FindsTheHighestExcitedFrequency) {
  // Velocity lines of equal amplitude at 1, 2 and 3 Hz: 99% of the energy lies below 3 Hz plus
  // the Hann window's main lobe (2 / 20 s = 0.1 Hz).
  const double fs = 1000;
  const Eigen::Index n = 20000;
  Trajectory x;
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q = Eigen::MatrixXd::Zero(n, 2);
  x.tau = x.q;
  for (const double f : {1.0, 2.0, 3.0}) {
    x.q.col(0) += ((2 * kPi * f * x.t).array().sin() / (2 * kPi * f)).matrix();
  }
  x.q.col(1) = 0.3 * ((2 * kPi * 1.5 * x.t).array().cos()).matrix();
  const double bandwidth = estimate_bandwidth(x);
  EXPECT_GT(bandwidth, 2.9);
  EXPECT_LT(bandwidth, 3.1);
}

TEST(EstimateBandwidth, IgnoresSensorNoiseAndQuantization) {
  // The same motion with sensor noise (0.5e-3 rad) read by an encoder with 1e-3 rad steps:
  // differentiated, noise and steps would hold most of the velocity energy, at high
  // frequencies; the noise floor is subtracted.
  const double fs = 1000;
  const Eigen::Index n = 20000;
  Trajectory x;
  x.source = "quantized.csv";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q = Eigen::MatrixXd::Zero(n, 1);
  x.tau = x.q;
  for (const double f : {1.0, 2.0, 3.0}) {
    x.q.col(0) += ((2 * kPi * f * x.t).array().sin() / (2 * kPi * f)).matrix();
  }
  std::mt19937_64 engine(21);
  add_noise(x.q, 0.5e-3, engine);
  x.q = (x.q.array() / 1e-3).round() * 1e-3;
  const double bandwidth = estimate_bandwidth(x);
  EXPECT_GT(bandwidth, 2.9);
  EXPECT_LT(bandwidth, 3.1);

  x.q.setConstant(0.25);
  expect_data_error([&] { estimate_bandwidth(x); }, "quantized.csv", "do not move");
}

// A slow five-harmonic excitation as the Panda run's (period 13.35 s, top harmonic 0.375 Hz),
// sampled at 1 kHz for 20 s.
Trajectory slow_excitation(Eigen::Index axes) {
  const double fs = 1000, period = 13.35;
  const Eigen::Index n = 20000;
  Trajectory x;
  x.source = "slow.csv";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q = Eigen::MatrixXd::Zero(n, axes);
  x.tau = x.q;
  for (Eigen::Index j = 0; j < axes; ++j) {
    for (int l = 1; l <= 5; ++l) {
      const double w = 2 * kPi * l / period;
      x.q.col(j) += (0.3 / l * ((w * x.t).array() + 0.7 * (j + l)).sin()).matrix();
    }
  }
  return x;
}

TEST(EstimateBandwidth, IgnoresColouredNoise) {
  // Noise that falls with frequency (white noise through a 100 Hz low-pass, as timing jitter or
  // interpolated, held positions give): a noise floor taken from the top of the band sees only
  // its tail, and the velocity weighting (2 pi f)^2 then makes the noise between 1 and 100 Hz
  // the "bandwidth" (the Panda run gave 80.4 Hz). The motion ends at 0.375 Hz, plus the Hann
  // main lobe (2 / 32.8 s).
  Trajectory x = slow_excitation(3);
  std::mt19937_64 engine(17);
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(x.q.rows(), x.q.cols());
  add_noise(noise, 2e-3, engine);
  filter_causal(butterworth_lowpass(2, 100, 1000), noise);
  x.q += noise;
  const double bandwidth = estimate_bandwidth(x);
  EXPECT_GT(bandwidth, 0.35);
  EXPECT_LT(bandwidth, 0.5);
}

TEST(EstimateBandwidth, KeepsTheTorquesBandWhenItIsWider) {
  // Torques reach above the motion (here sin(5 q), as the dynamics' sines of q give):
  // the decimation must keep both sides of tau = W beta, so the bandwidth is the torques'.
  Trajectory x = slow_excitation(1);
  x.tau.col(0) = (4.0 * (5.0 * x.q.col(0).array()).sin()).matrix();
  const ExcitationBands bands = estimate_bands(x);
  EXPECT_LT(bands.velocity_hz, 0.5);
  EXPECT_GT(bands.torque_hz, bands.velocity_hz);
  EXPECT_EQ(bands.bandwidth_hz, bands.torque_hz);
  // Without measured torques (predict on positions only), the motion's band alone.
  x.measured = Measured::kNothing;
  EXPECT_EQ(estimate_bands(x).torque_hz, 0);
  EXPECT_EQ(estimate_bandwidth(x), estimate_bands(x).velocity_hz);
}

// ---------------------------------------------------------------------------------------------
// Real data (../shared/datasets, see SOURCES.md there)

std::vector<double> read_numbers(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> values;
  double v = 0;
  while (in >> v) values.push_back(v);
  return values;
}

TEST(RealData, PandaExcitationRepeatsButHoldsFewerThanTwoPeriods) {
  const std::string dir = test::shared_path("datasets/panda-gaz2019/");
  const std::vector<double> time = read_numbers(dir + "exciting_traj_time.txt");
  const std::vector<double> positions = read_numbers(dir + "exciting_traj_positions.txt");
  if (time.empty()) GTEST_SKIP() << "no Panda data set in " << dir;
  ASSERT_EQ(positions.size(), 7 * time.size());
  // The log's time steps jitter (0.7 to 8.8 ms): resample linearly on a 1 ms grid.
  const double dt = 1e-3;
  const auto n = static_cast<Eigen::Index>(time.back() / dt) + 1;
  Trajectory x;
  x.source = "panda";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) * dt);
  x.q.resize(n, 7);
  x.tau = Eigen::MatrixXd::Zero(n, 7);
  std::size_t k = 0;
  for (Eigen::Index s = 0; s < n; ++s) {
    while (k + 2 < time.size() && time[k + 1] < x.t[s]) ++k;
    const double a = std::clamp((x.t[s] - time[k]) / (time[k + 1] - time[k]), 0.0, 1.0);
    for (int j = 0; j < 7; ++j) {
      x.q(s, j) = (1 - a) * positions[7 * k + j] + a * positions[7 * (k + 1) + j];
    }
  }
  double period = 0;
  try {
    detect_period(x);
    ADD_FAILURE() << "21 s of a 13 s periodic motion accepted";
  } catch (const DataError& e) {
    const std::string what = e.what();
    const std::size_t at = what.find("period of ");
    ASSERT_NE(at, std::string::npos) << what;
    period = std::stod(what.substr(at + 10));
    EXPECT_NE(what.find("(1.57"), std::string::npos) << what;
  }
  // Independently: q(t + T) repeats q(t) to a few percent of the motion at the period found,
  // and not half a second away from it.
  auto mismatch = [&](double lag) {
    const auto m = static_cast<Eigen::Index>(std::llround(lag / dt));
    const Eigen::Index from = 1000;  // after the start from rest
    const Eigen::MatrixXd a = x.q.middleRows(from, n - m - from);
    const Eigen::MatrixXd b = x.q.middleRows(from + m, n - m - from);
    const Eigen::RowVectorXd mean = a.colwise().mean();
    return (b - a).norm() / (a.rowwise() - mean).norm();
  };
  EXPECT_GT(period, 13.0);
  EXPECT_LT(period, 13.7);
  EXPECT_LT(mismatch(period), 0.05);
  EXPECT_GT(mismatch(period - 0.5), 0.2);
  EXPECT_GT(mismatch(period + 0.5), 0.2);
}

}  // namespace
}  // namespace modelgen
