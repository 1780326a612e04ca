// CSV trajectories: a broken file gives its message with file, line and column; central
// differences reproduce analytic derivatives of a smooth trajectory.

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/signal/differentiation.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace modelgen::io;  // the data CSV (modelgen/io/experiment/trajectory_csv.hpp)

// The broken files of tests/bad_inputs/data/ and their messages are run through modelid by
// tests/bad_inputs/bad_inputs_test.cpp; here the library's side of one of them.
TEST(TrajectoryCsv, BadFileThrowsDataErrorWithFileLineAndColumn) {
  const std::string path = test::source_path("tests/bad_inputs/data/nan_value.csv");
  try {
    read_trajectory_csv(path, 2);
    ADD_FAILURE() << path << " was accepted";
  } catch (const DataError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":3 (column q2): error: value is NaN or infinite");
  }
}

TEST(TrajectoryCsv, WriteThenReadGivesTheSameNumbers) {
  FourierTrajectory f;
  f.period = 4.0;
  f.q0 = Eigen::Vector2d(0.1, -0.2);
  f.a = Eigen::MatrixXd::Constant(2, 3, 0.3);
  f.b = Eigen::MatrixXd::Constant(2, 3, -0.2);
  Trajectory x = sample(f, 0.01, 4.0);
  x.tau = x.q * 3.0;
  const std::string path = testing::TempDir() + "trajectory_roundtrip.csv";
  write_trajectory_csv(path, x);
  const Trajectory y = read_trajectory_csv(path, 2);
  EXPECT_TRUE(y.has_velocity);
  EXPECT_EQ(y.q, x.q);  // shortest round-trip text: exact
  EXPECT_EQ(y.ddq, x.ddq);
  EXPECT_EQ(y.tau, x.tau);
}

// Currents are read as they are, flagged for to_joint_side; a file without effort columns is
// accepted only when the caller says torques are optional (prediction).
TEST(TrajectoryCsv, CurrentColumnsAndOptionalTorques) {
  const std::string currents = testing::TempDir() + "currents.csv";
  std::ofstream(currents) << "t,q1,q2,i1,i2\n0,0.1,0.2,1.5,-2\n0.1,0.1,0.2,1.5,-2\n0.2,0.1,0.2,1.5,-2\n";
  const Trajectory x = read_trajectory_csv(currents, 2);
  EXPECT_EQ(x.measured, Measured::kCurrent);
  EXPECT_EQ(x.tau(2, 0), 1.5);
  EXPECT_EQ(x.tau(1, 1), -2.0);

  const std::string positions = testing::TempDir() + "positions_only.csv";
  std::ofstream(positions) << "t,q1,q2\n0,0.1,0.2\n0.1,0.1,0.2\n0.2,0.1,0.2\n";
  EXPECT_THROW(read_trajectory_csv(positions, 2), DataError);
  const Trajectory y = read_trajectory_csv(positions, 2, EffortColumns::kOptional);
  EXPECT_EQ(y.measured, Measured::kNothing);
  EXPECT_EQ(y.tau.rows(), 3);
  EXPECT_EQ(y.tau.cwiseAbs().maxCoeff(), 0.0);
}

TEST(TrajectoryCsv, CentralDifferencesMatchTheAnalyticDerivatives) {
  FourierTrajectory f;
  f.period = 5.0;
  f.q0 = Eigen::Vector2d(0.0, 0.5);
  f.a = (Eigen::MatrixXd(2, 2) << 0.4, -0.2, 0.1, 0.3).finished();
  f.b = (Eigen::MatrixXd(2, 2) << 0.2, 0.1, -0.3, 0.2).finished();
  const Trajectory exact = sample(f, 0.001, 5.0);
  Trajectory numeric = exact;
  numeric.has_velocity = false;
  differentiate(numeric);
  ASSERT_EQ(numeric.t.size(), exact.t.size() - 2);
  // Second-order differences with h = 1 ms: errors of order h^2 times the third derivative.
  EXPECT_LT((numeric.dq - exact.dq.middleRows(1, exact.t.size() - 2)).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LT((numeric.ddq - exact.ddq.middleRows(1, exact.t.size() - 2)).cwiseAbs().maxCoeff(), 1e-3);
}

}  // namespace
}  // namespace modelgen
