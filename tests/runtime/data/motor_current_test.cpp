// Motor torque from current (Swevers 2002 eq. 4): closed-form values, odd symmetry, and the
// errors for non-finite currents and a wrong number of polynomials.

#include "modelgen/data/motor_current.hpp"
#include "modelgen/data/data_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace modelgen {
namespace {

TEST(MotorCurrent, ThirdOrderSignSymmetricPolynomial) {
  CurrentTorquePolynomial motor;
  motor.ratio = 3;
  motor.c = {1, 2, 0.5, 0.1};
  // 3 (1 + 2 * 2 + 0.5 * 4 + 0.1 * 8) = 23.4
  EXPECT_NEAR(motor_torque_from_current(2, motor), 23.4, 1e-12);
  EXPECT_NEAR(motor_torque_from_current(-2, motor), -23.4, 1e-12);
  EXPECT_EQ(motor_torque_from_current(0, motor), 0.0);
  EXPECT_NEAR(motor_torque_from_current(0.5, motor), 3 * (1 + 1 + 0.125 + 0.0125), 1e-12);
}

TEST(MotorCurrent, MatrixOfCurrents) {
  CurrentTorquePolynomial linear;
  linear.c = {0, 4, 0, 0};
  CurrentTorquePolynomial cubic;
  cubic.ratio = -2;
  cubic.c = {0, 0, 0, 1};
  Eigen::MatrixXd currents(2, 2);
  currents << 1, 2, -3, -1;
  const Eigen::MatrixXd tau = motor_torques_from_currents(currents, {linear, cubic}, "run.csv");
  EXPECT_DOUBLE_EQ(tau(0, 0), 4);
  EXPECT_DOUBLE_EQ(tau(1, 0), -12);
  EXPECT_DOUBLE_EQ(tau(0, 1), -16);
  EXPECT_DOUBLE_EQ(tau(1, 1), 2);
}

TEST(MotorCurrent, ErrorsNameSourceSampleAndColumn) {
  Eigen::MatrixXd currents = Eigen::MatrixXd::Ones(3, 2);
  currents(2, 1) = std::nan("");
  try {
    motor_torques_from_currents(currents, {{}, {}}, "run.csv");
    FAIL() << "expected DataError";
  } catch (const DataError& error) {
    EXPECT_EQ(std::string(error.what()),
              "run.csv: sample 2 (column i2): error: current is NaN or infinite");
  }
  EXPECT_THROW(motor_torques_from_currents(Eigen::MatrixXd::Ones(3, 2), {{}}, "run.csv"),
               DataError);
}

}  // namespace
}  // namespace modelgen
