// Every error modelgen reports to its user is a modelgen::Error: a program can catch that one
// type, print what() and read where(). Each error here is raised by the real function on a real
// bad input, not constructed by hand.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "modelgen/data/data_error.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/model/command_line.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace modelgen::io;  // the data CSV (modelgen/io/experiment/trajectory_csv.hpp)

TEST(ErrorHierarchy, ADescriptionErrorIsAnErrorWithFileAndLine) {
  const std::string path = test::source_path("tests/bad_inputs/yaml/unknown_key.yaml");
  try {
    load_robot(path);
    ADD_FAILURE() << path << " was accepted";
  } catch (const Error& e) {
    EXPECT_NE(dynamic_cast<const InputError*>(&e), nullptr);
    EXPECT_EQ(e.where().file, path);
    EXPECT_GT(e.where().line, 0);
    EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
  }
}

TEST(ErrorHierarchy, ADataErrorIsAnErrorWithFileLineAndColumnName) {
  const std::string path = test::source_path("tests/bad_inputs/data/nan_value.csv");
  try {
    read_trajectory_csv(path, 2);
    ADD_FAILURE() << path << " was accepted";
  } catch (const Error& e) {
    EXPECT_NE(dynamic_cast<const DataError*>(&e), nullptr);
    EXPECT_EQ(e.where().file, path);
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.where().field, "q2");
  }
}

TEST(ErrorHierarchy, AnEstimationErrorIsAnError) {
  // Two identical columns: rank deficient, the data cannot tell them apart.
  Eigen::MatrixXd W(4, 2);
  W << 1, 1, 2, 2, 3, 3, 4, 4;
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(4, 1, 4);
  try {
    fit_ols(W, y, {"a", "b"});
    ADD_FAILURE() << "a rank-deficient W was fitted";
  } catch (const Error& e) {
    EXPECT_NE(dynamic_cast<const EstimationError*>(&e), nullptr);
  }
}

TEST(ErrorHierarchy, AUsageErrorIsAnError) {
  const char* argv[] = {"modelid", "fit", "--robot"};
  try {
    parse_command_line(3, const_cast<char**>(argv), 2, "fit", {{"--robot", OptionKind::kOnce}});
    ADD_FAILURE() << "--robot without a value was accepted";
  } catch (const Error& e) {
    EXPECT_NE(dynamic_cast<const UsageError*>(&e), nullptr);
    EXPECT_EQ(std::string(e.what()), "--robot needs a value");
  }
}

}  // namespace
}  // namespace modelgen
