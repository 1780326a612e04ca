// Shared by the signal tests: a known excitation, noise, an independent sine fit and the
// expectation of a positioned DataError.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/QR>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"

namespace modelgen::signal_test {

inline constexpr double kPi = std::numbers::pi;

// Three axes, five harmonics, offsets; axis 3 moves little.
inline FourierTrajectory three_axis_excitation(double period) {
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
inline Eigen::MatrixXd torque_of(const Trajectory& x) { return 5.0 * x.q + 0.2 * x.ddq; }

inline void add_noise(Eigen::MatrixXd& m, double sigma, std::mt19937_64& engine) {
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
inline SineFit fit_sine(const Eigen::VectorXd& t, const Eigen::VectorXd& y, double frequency_hz) {
  Eigen::MatrixXd basis(t.size(), 3);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    basis(k, 0) = std::sin(2 * kPi * frequency_hz * t[k]);
    basis(k, 1) = std::cos(2 * kPi * frequency_hz * t[k]);
    basis(k, 2) = 1.0;
  }
  const Eigen::Vector3d c = basis.colPivHouseholderQr().solve(y);
  return {std::hypot(c[0], c[1]), std::atan2(c[1], c[0])};
}

inline double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / v.size()); }

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

// |H| of the digital Butterworth low-pass made by the pre-warped bilinear transform.
inline double butterworth_gain(double f, double fc, double fs, int order) {
  const double w = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
  return 1.0 / std::sqrt(1.0 + std::pow(w, 2.0 * order));
}

inline double chebyshev_polynomial(int n, double w) {
  return w <= 1.0 ? std::cos(n * std::acos(w)) : std::cosh(n * std::acosh(w));
}

}  // namespace modelgen::signal_test
