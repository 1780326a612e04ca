// fit's residual against the record's noise (issue 31) on a TX-40 simulated here in open loop
// (3 periods, 0.05 N m of torque noise, exact dq and ddq in the file): the clean record gets
// no warning; the same record with an error the model cannot explain, written into one joint's
// torque column here (a cubic friction, a delay of the torque), gets one warning naming that
// joint and no other. The same on the averaged period (--periodic: IDIM-WLS and ML-EIV), whose
// noise comes from the spread of the three periods.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "tests/runtime/cli/modelid_cli_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

const std::string kWarning = "in the excitation band the residual";

class ModelidResidualCheck : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(test_folder("residual_check"));
    const CliRun run =
        modelid("simulate --robot tx40 --params " + quoted_source("robots/data/tx40/true.json") +
                " --trajectory " + quoted_source("robots/data/tx40/design.yaml") +
                " --noise 0.05 --periods 3 --ignore-limits -o " + quoted(clean()));
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  static void TearDownTestSuite() { delete folder_; }
  static fs::path clean() { return *folder_ / "clean.csv"; }

  // The clean record with `change(table)` applied, written to `name`.
  static fs::path changed(const std::string& name, const std::function<void(CsvTable&)>& change) {
    CsvTable table = read_csv(clean());
    change(table);
    const fs::path path = *folder_ / name;
    std::ofstream out(path);
    for (std::size_t c = 0; c < table.header.size(); ++c) {
      out << (c ? "," : "") << table.header[c];
    }
    out << "\n";
    char number[32];
    for (const std::vector<double>& row : table.rows) {
      for (std::size_t c = 0; c < row.size(); ++c) {
        std::snprintf(number, sizeof number, "%.17g", row[c]);
        out << (c ? "," : "") << number;
      }
      out << "\n";
    }
    return path;
  }

  static CliRun fit(const fs::path& data, const std::string& options = "--method wls") {
    return modelid("fit --robot tx40 --data " + quoted(data) + " " + options);
  }

  // A cubic friction on joint 3 (see AFrictionTheModelLacksIsNamedOnItsJoint).
  static fs::path cubic() {
    return changed("cubic.csv", [](CsvTable& table) {
      const int dq = table.column("dq3"), tau = table.column("tau3");
      double largest = 0;
      for (const auto& row : table.rows) largest = std::max(largest, std::abs(row[dq]));
      for (auto& row : table.rows) row[tau] += 3.0 * std::pow(row[dq] / largest, 3);
    });
  }

  // Joint 2's torque recorded 3 samples (30 ms) late.
  static fs::path delayed() {
    return changed("delay.csv", [](CsvTable& table) {
      const int tau = table.column("tau2");
      for (std::size_t k = table.rows.size(); k-- > 3;) table.rows[k][tau] = table.rows[k - 3][tau];
    });
  }

  // The joints the residual warnings name.
  static std::vector<int> named_joints(const std::string& err) {
    std::vector<int> joints;
    const std::regex line("warning: joint ([0-9]+): " + kWarning);
    for (auto it = std::sregex_iterator(err.begin(), err.end(), line); it != std::sregex_iterator();
         ++it) {
      joints.push_back(std::stoi((*it)[1]));
    }
    return joints;
  }

  static fs::path* folder_;
};

fs::path* ModelidResidualCheck::folder_ = nullptr;

TEST_F(ModelidResidualCheck, CleanDataGiveNoWarning) {
  const CliRun run = fit(clean());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err.find(kWarning), std::string::npos) << run.err;
}

TEST_F(ModelidResidualCheck, AFrictionTheModelLacksIsNamedOnItsJoint) {
  // 3 N m times (dq3 / max |dq3|)^3: viscous and Coulomb friction absorb its linear and
  // sign-like parts, not the rest.
  const CliRun run = fit(cubic());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(named_joints(run.err), std::vector<int>{3}) << run.err;
  EXPECT_NE(run.err.find("misses something on this joint"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("--torque-hold"), std::string::npos) << run.err;
}

TEST_F(ModelidResidualCheck, ATorqueDelayIsNamedOnItsJoint) {
  const CliRun run = fit(delayed());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(named_joints(run.err), std::vector<int>{2}) << run.err;
}

// The averaged period: the three periods' spread is the noise.
TEST_F(ModelidResidualCheck, AveragedPeriodsAreCheckedToo) {
  for (const std::string method : {"wls", "ml-eiv"}) {
    const std::string options = "--method " + method + " --periodic";
    const CliRun clean_run = fit(clean(), options);
    ASSERT_EQ(clean_run.exit_code, 0) << clean_run.err;
    EXPECT_EQ(clean_run.err.find(kWarning), std::string::npos) << method << clean_run.err;
    const CliRun cubic_run = fit(cubic(), options);
    ASSERT_EQ(cubic_run.exit_code, 0) << cubic_run.err;
    EXPECT_EQ(named_joints(cubic_run.err), std::vector<int>{3}) << method << cubic_run.err;
    EXPECT_NE(cubic_run.err.find("spread of 3 periods"), std::string::npos) << cubic_run.err;
  }
  const CliRun delay_run = fit(delayed(), "--method wls --periodic");
  ASSERT_EQ(delay_run.exit_code, 0) << delay_run.err;
  EXPECT_EQ(named_joints(delay_run.err), std::vector<int>{2}) << delay_run.err;
}

}  // namespace
}  // namespace modelgen::test
