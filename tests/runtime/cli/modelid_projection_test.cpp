// modelid fit --method pm as a user runs it, on the compiled-in TX-40 simulated under a PID
// along its bundled design (all joints move): the report names M, the decorrelation test and
// the discarded torque per joint, and the warning that a multi-joint run loses torque the FIR
// cannot make; --fir-lags forces M; usage and data errors.

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/tx40_truth.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

const std::string kDesign = "robots/data/tx40/design.yaml";

class ModelidProjection : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = test_folder();
    controller_ = folder_ / "pid.yaml";
    write_text(controller_,
               "type: pid\nsample_time: 0.001\n"
               "kp: [18000, 18000, 3000, 400, 400, 200]\n"
               "ki: [1.8e5, 1.8e5, 3.0e4, 4000, 4000, 2000]\n"
               "kd: [260, 260, 40, 5, 5, 2.5]\n");
    nlohmann::json truth;
    for (const NamedValue& v : tx40_true_base()) truth["base"][v.name] = v.value;
    truth_ = folder_ / "truth.json";
    write_text(truth_, truth.dump());
    data_ = folder_ / "run.csv";
    const CliRun run = modelid(
        "simulate --robot tx40 --params " + quoted(truth_) + " --trajectory " +
        quoted_source(kDesign) + " --controller " + quoted(controller_) + " --noise-tau 0.2 " +
        "--encoder-resolution 1.5e-6 --seed 3 --ignore-limits -o " + quoted(data_));
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }

  fs::path folder_, controller_, truth_, data_;
};

TEST_F(ModelidProjection, ReportsTheProjectionAndWarnsOnAMultiJointRun) {
  const fs::path estimate = folder_ / "pm.json";
  const std::string fit = "fit --robot tx40 --data " + quoted(data_) +
                          " --method pm --cutoff 100 --decimate 10 --torque-hold zoh -o " +
                          quoted(estimate);
  CliRun run = modelid(fit);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("non-causal FIR of lags -"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("friction compensated first (Bona & Curatella 3.4)"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("M chosen by the decorrelation and residual tests"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("decorrelation test: largest |correlation|"), std::string::npos);
  EXPECT_NE(run.out.find("torque discarded by the projection"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("modelid: warning: the projection discards"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("Move one joint at a time"), std::string::npos) << run.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(estimate))["method"], "PM (projection, IDIM-WLS)");
  // The discarded fraction over all joints is above the 3 % of the warning.
  const std::size_t at = run.out.find("; all joints ");
  ASSERT_NE(at, std::string::npos) << run.out;
  EXPECT_GT(std::stod(run.out.substr(at + 13)), 3.0) << run.out;

  run = modelid(fit + " --fir-lags 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("non-causal FIR of lags -2..2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("M given by --fir-lags"), std::string::npos) << run.out;
}

TEST_F(ModelidProjection, Errors) {
  const std::string fit = "fit --robot tx40 --data " + quoted(data_);
  CliRun run = modelid(fit + " --method wls --fir-lags 3");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--fir-lags belongs to the projection method"), std::string::npos)
      << run.err;
  run = modelid(fit + " --method pm --fir-lags -1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--fir-lags must be a whole number >= 0"), std::string::npos) << run.err;
  // More lags than the rows carry: refused before the lagged references are built (they would
  // take gigabytes), with the largest M that fits.
  run = modelid(fit + " --method pm --fir-lags 2000000000");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("M = 2000000000 lags need"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("choose M <= "), std::string::npos) << run.err;
  run = modelid(fit + " --method pm --controller " + quoted(controller_));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--controller belongs to the closed-loop methods"), std::string::npos)
      << run.err;
  // An open-loop file has no reference columns.
  const fs::path open_loop = folder_ / "open.csv";
  ASSERT_EQ(
      modelid("simulate --robot tx40 --params " + quoted(truth_) + " --trajectory " +
              quoted_source(kDesign) + " --noise 0.01 --ignore-limits -o " + quoted(open_loop))
          .exit_code,
      0);
  run = modelid("fit --robot tx40 --data " + quoted(open_loop) + " --method pm");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find(open_loop.string() +
                         ": error: the projection method (--method pm) "
                         "needs the reference positions of the record, columns qr1..qr6"),
            std::string::npos)
      << run.err;
}

}  // namespace
}  // namespace modelgen::test
