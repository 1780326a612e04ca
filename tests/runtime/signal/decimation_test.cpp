// Parallel decimation (modelgen/signal/decimation.hpp): the low sine kept and the high one
// removed, linearity so that Y and W stay consistent, stages of at most ten, and the rows the
// end samples dominate (Gautier & Briot eq. 13-14).

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
#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/lowpass.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

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

}  // namespace
}  // namespace modelgen
