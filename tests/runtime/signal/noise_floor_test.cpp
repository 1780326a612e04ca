// The noise floor of a torque comparison (modelgen/signal/noise_floor.hpp) against the
// signals it is made of: a periodic torque of a known excitation, white noise of a known
// variance and a large content far above the band. The expected figures are computed here
// from those parts: the white noise puts sigma^2 on every line, (2 L + 1) sigma^2 in a band of
// L lines per axis.

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/noise_floor.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

constexpr double kPeriod = 2.0, kDt = 0.002, kSigma = 0.02;
constexpr int kPeriods = 3;

struct Record {
  Trajectory motion;
  Eigen::MatrixXd truth, above, noise;  // the torque, what lies far above the band, white noise
  Eigen::MatrixXd measured() const { return truth + above + noise; }
};

// Three periods of the excitation (harmonics up to 5 / 2 s = 2.5 Hz), a torque in its band,
// and tones at 61.3 Hz and 143.7 Hz (not on a DFT line: they leak) ten times its energy.
Record make_record(std::uint64_t seed) {
  Record r;
  const FourierTrajectory f = three_axis_excitation(kPeriod);
  r.motion = sample(f, kDt, kPeriods * kPeriod);
  r.truth = torque_of(r.motion);
  const Eigen::Index n = r.truth.rows();
  r.above = Eigen::MatrixXd::Zero(n, 3);
  const double rms = std::sqrt(r.truth.squaredNorm() / static_cast<double>(r.truth.size()));
  for (Eigen::Index s = 0; s < n; ++s) {
    const double t = r.motion.t[s];
    for (Eigen::Index j = 0; j < 3; ++j) {
      r.above(s, j) =
          3.0 * rms * (std::sin(2 * kPi * 61.3 * t + j) + std::cos(2 * kPi * 143.7 * t + 2.0 * j));
    }
  }
  r.noise = Eigen::MatrixXd::Zero(n, 3);
  std::mt19937_64 engine(seed);
  add_noise(r.noise, kSigma, engine);
  return r;
}

ExcitationBand band_of_series() {
  return band_of_fourier(three_axis_excitation(kPeriod), "excitation.yaml");
}

// The in-band relative error of white noise of kSigma: (2 L + 1) lines per axis of sigma^2
// each, over the in-band torque (all of the torque here).
double expected_noise_ratio(const Record& r, double band_hz) {
  const double lines = 2.0 * std::floor(band_hz * kPeriods * kPeriod + 1e-9) + 1.0;
  return std::sqrt(3.0 * lines * kSigma * kSigma / r.truth.squaredNorm());
}

TEST(BandOfFourier, IsTwiceTheTopHarmonic) {
  const ExcitationBand band = band_of_series();
  EXPECT_DOUBLE_EQ(band.band_hz, 2.0 * 5.0 / kPeriod);
  EXPECT_DOUBLE_EQ(band.period, kPeriod);
  FourierTrajectory none = three_axis_excitation(kPeriod);
  none.a.setZero();
  none.b.setZero();
  EXPECT_THROW(band_of_fourier(none, "flat.yaml"), DataError);
}

TEST(BandOfPositions, FindsThePeriodAndABandAtMostTwiceTheTopHarmonic) {
  const Record r = make_record(1);
  const ExcitationBand band = band_of_positions(r.motion);
  EXPECT_NEAR(band.period, kPeriod, 0.01);
  EXPECT_GT(band.band_hz, 2.0 * 1.0 / kPeriod);  // above twice the fundamental
  // At most twice the top harmonic, 2.5 Hz, and a line of the 4096-point FFT (0.12 Hz).
  EXPECT_LE(band.band_hz, 2.0 * (5.0 / kPeriod + 0.13));
}

TEST(NoiseFloor, TheTruthIsAtTheFloorInTheBandWhenMostEnergyLiesAbove) {
  const Record r = make_record(2);
  const ExcitationBand band = band_of_series();
  const Eigen::MatrixXd tau = r.measured();
  const NoiseFloor f = noise_floor({band_energies(tau, tau - r.truth, kDt, band)});
  // Above the band: the tones and the white noise's lines there.
  const double n = static_cast<double>(tau.rows());
  const double lines = 2.0 * std::floor(band.band_hz * kPeriods * kPeriod) + 1.0;
  const double above = r.above.squaredNorm() + r.noise.squaredNorm() * (1.0 - lines / n);
  EXPECT_NEAR(f.out_of_band_fraction, above / tau.squaredNorm(), 0.01);
  EXPECT_GT(f.out_of_band_fraction, 0.9);
  EXPECT_TRUE(f.in_band_headline);
  EXPECT_NEAR(f.full_band, (tau - r.truth).norm() / tau.norm(), 1e-12);
  const double expected = expected_noise_ratio(r, band.band_hz);
  EXPECT_NEAR(f.in_band, expected, 0.25 * expected);
  EXPECT_NEAR(f.floor, expected, 0.25 * expected);
  EXPECT_NEAR(f.floor_rms, std::sqrt(lines / n) * kSigma, 0.25 * std::sqrt(lines / n) * kSigma);
}

TEST(NoiseFloor, AWrongModelStandsAboveTheFloorByItsError) {
  const Record r = make_record(3);
  const ExcitationBand band = band_of_series();
  const Eigen::MatrixXd tau = r.measured();
  // 5% too much torque: 0.05 of the in-band torque, the noise besides.
  const NoiseFloor f = noise_floor({band_energies(tau, tau - 1.05 * r.truth, kDt, band)});
  const double noise = expected_noise_ratio(r, band.band_hz);
  const double expected = std::sqrt(0.05 * 0.05 + noise * noise);
  EXPECT_NEAR(f.in_band, expected, 0.05 * expected);
  EXPECT_NEAR(f.floor, noise, 0.25 * noise);  // the floor is the record's, not the model's
}

TEST(NoiseFloor, WithoutAPeriodTheQuartileOfTheSpectrumGivesTheFloor) {
  // One record has some 60 lines per axis in the band: the mean of 20 records tells the bias.
  ExcitationBand band = band_of_series();
  band.period = 0;
  double noise = 0;
  constexpr int kRecords = 20;
  for (int seed = 100; seed < 100 + kRecords; ++seed) {
    const Record r = make_record(seed);
    const Eigen::MatrixXd tau = r.measured();
    const BandEnergies energies = band_energies(tau, tau - r.truth, kDt, band);
    EXPECT_NE(energies.noise_origin.find("quartile"), std::string::npos) << energies.noise_origin;
    noise += energies.noise_in_band / kRecords;
  }
  const double lines = 2.0 * std::floor(band.band_hz * kPeriods * kPeriod + 1e-9) + 1.0;
  const double expected = 3.0 * lines * kSigma * kSigma;
  EXPECT_NEAR(noise, expected, 0.25 * expected);
}

TEST(NoiseFloor, CleanDataKeepTheFullBandHeadline) {
  const Record r = make_record(5);
  const Eigen::MatrixXd tau = r.truth + r.noise;
  const NoiseFloor f =
      noise_floor({band_energies(tau, tau - 1.02 * r.truth, kDt, band_of_series())});
  EXPECT_LT(f.out_of_band_fraction, 0.01);
  EXPECT_FALSE(f.in_band_headline);
  EXPECT_NEAR(f.full_band, (0.02 * r.truth - r.noise).norm() / tau.norm(), 1e-12);
}

TEST(NoiseFloor, PoolsRecordsAndRefusesMismatchedShapes) {
  const Record a = make_record(6), b = make_record(7);
  const ExcitationBand band = band_of_series();
  const Eigen::MatrixXd ta = a.measured(), tb = b.measured();
  const BandEnergies ea = band_energies(ta, ta - a.truth, kDt, band);
  const BandEnergies eb = band_energies(tb, tb - b.truth, kDt, band);
  const NoiseFloor pooled = noise_floor({ea, eb});
  EXPECT_NEAR(pooled.full_band,
              std::sqrt((ea.error + eb.error) / (ta.squaredNorm() + tb.squaredNorm())), 1e-12);
  EXPECT_THROW(band_energies(ta, ta.leftCols(2), kDt, band), std::invalid_argument);
  EXPECT_THROW(band_energies(ta, ta, 0.0, band), std::invalid_argument);
}

}  // namespace
}  // namespace modelgen
