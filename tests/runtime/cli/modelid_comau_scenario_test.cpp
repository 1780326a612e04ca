// The bundled COMAU Smart Six scenario of README.md, as a user runs it: 40 s under the bundled
// PID along the bundled design, with torque noise and encoder quantisation; IDIM-WLS, IDIM-IV
// and DIDIM put every base parameter they identify under 10 %std within 3 standard deviations of
// the truth, the truth's base parameters computed here from true.json's standard parameters by
// the numeric reference; each estimate validates on a second design as well as the truth does
// (the noise floor); the projection method warns about the torque it discards.

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/runtime/cli/modelid_cli_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = "robots/data/comau_smart_six/";

// Base parameters by name from the standard set of true.json, by the numeric reference.
std::map<std::string, double> true_base() {
  const RobotModel description = load_robot(source_path("robots/comau_smart_six.yaml"));
  const ReferenceModel reference(description.name, description.tree);
  const nlohmann::json truth = nlohmann::json::parse(read_text(source_path(kData + "true.json")));
  const std::vector<std::string>& standard = reference.standard_param_names();
  std::vector<double> p(standard.size(), 0.0);
  for (std::size_t k = 0; k < standard.size(); ++k) {
    if (truth["standard"].contains(standard[k])) p[k] = truth["standard"][standard[k]];
  }
  std::vector<double> beta(static_cast<std::size_t>(reference.num_base_params()));
  reference.base_from_standard(p.data(), beta.data());
  std::map<std::string, double> out;
  for (std::size_t k = 0; k < beta.size(); ++k) out[reference.base_param_names()[k]] = beta[k];
  return out;
}

// rms torque error per joint printed by validate.
std::vector<double> validation_torque_rms(const std::string& out) {
  std::istringstream lines(out);
  std::vector<double> rms;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    int joint = 0;
    double rms_deg = 0, max_deg = 0, rms_torque = 0;
    if (fields >> joint >> rms_deg >> max_deg >> rms_torque) rms.push_back(rms_torque);
  }
  return rms;
}

class ModelidComauScenario : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(test_folder());
    const std::string common = "simulate --robot comau_smart_six --params " +
                               quoted_source(kData + "true.json") + " --controller " +
                               quoted_source(kData + "controller.yaml") +
                               " --noise-tau 0.1 --encoder-resolution 5e-7 ";
    CliRun run = modelid(common + "--trajectory " + quoted_source(kData + "design.yaml") +
                         " --periods 4 --seed 1 -o " + quoted(*folder_ / "id.csv"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = modelid(common + "--trajectory " + quoted_source(kData + "validation.yaml") +
                  " --seed 2 -o " + quoted(*folder_ / "val.csv"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  static void TearDownTestSuite() { delete folder_; }

  static CliRun validate(const std::string& params) {
    return modelid("validate --robot comau_smart_six --params " + params + " --controller " +
                   quoted_source(kData + "controller.yaml") + " --data " +
                   quoted(*folder_ / "val.csv"));
  }

  static fs::path* folder_;
};

fs::path* ModelidComauScenario::folder_ = nullptr;

TEST_F(ModelidComauScenario, WlsIvAndDidimWithinThreeSdAndAtTheNoiseFloor) {
  const std::map<std::string, double> truth = true_base();
  const CliRun truth_run = validate(quoted_source(kData + "true.json"));
  ASSERT_EQ(truth_run.exit_code, 0) << truth_run.err;
  const std::vector<double> floor = validation_torque_rms(truth_run.out);
  ASSERT_EQ(floor.size(), 6u) << truth_run.out;
  // Still the options tuned on the bundled records: this record's encoder noise is a 5e-7 rad
  // count, so the wide band the 100 Hz filter and the decimation by 10 keep carries the loop's
  // own motion and little noise. The planned preparation (decimation by 180, rows bound) left 3
  // (WLS) and 4 (IV) of 64 beyond 3 sd (ZZ2R 5.0 sd), median error 0.16 % against 0.02 % here;
  // keeping 4x the band (160) 7 and 2 (issue 31).
  for (const std::string method : {"wls", "iv", "didim"}) {
    const fs::path estimate = *folder_ / (method + ".json");
    const std::string controller =
        method == "wls" ? "" : " --controller " + quoted_source(kData + "controller.yaml");
    const CliRun fit = modelid("fit --robot comau_smart_six --data " + quoted(*folder_ / "id.csv") +
                               " --method " + method + controller +
                               " --cutoff 100 --decimate 10 --min-speed 0.1 --torque-hold zoh -o " +
                               quoted(estimate));
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const nlohmann::json json = nlohmann::json::parse(read_text(estimate));
    int checked = 0;
    for (const nlohmann::json& p : json["parameters"]) {
      if (p["rel_std"].is_null() || p["rel_std"].get<double>() > 10) continue;
      const std::string name = p["name"];
      ASSERT_EQ(truth.count(name), 1u) << name;
      const double value = p["value"], sd = p["std"];
      EXPECT_LT(std::abs(value - truth.at(name)), 3 * sd) << method << " " << name;
      ++checked;
    }
    EXPECT_GE(checked, 50) << method;
    const CliRun run = validate(quoted(estimate));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::vector<double> rms = validation_torque_rms(run.out);
    ASSERT_EQ(rms.size(), 6u) << run.out;
    for (std::size_t j = 0; j < 6; ++j) {
      EXPECT_LT(rms[j], 1.02 * floor[j]) << method << " joint " << j + 1 << "\n" << run.out;
    }
  }
}

TEST_F(ModelidComauScenario, ProjectionWarnsAboutTheTorqueItDiscards) {
  const CliRun fit = modelid("fit --robot comau_smart_six --data " + quoted(*folder_ / "id.csv") +
                             " --method pm --cutoff 100 --decimate 10 --torque-hold zoh");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.err.find("of the torque norm (more than 3%)"), std::string::npos) << fit.err;
}

}  // namespace
}  // namespace modelgen::test
