// The bundled COMAU Smart Six scenario of README.md, as a user runs it: 40 s under the bundled
// PID along the bundled design, with torque noise and encoder quantisation; IDIM-WLS, IDIM-IV
// and DIDIM put every base parameter they identify under 10 %std within 3 standard deviations of
// the truth, the truth's base parameters computed here from true.json's standard parameters by
// the numeric reference; each estimate validates on a second design as well as the truth does
// (the noise floor); the projection method warns about the torque it discards; ML-EIV refuses
// the closed-loop record, and the reasons it gives are measured here on the record and against
// the truth (issue 31).

#include <algorithm>
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
  // The default preparation (6.1 Hz, decimation by 180) and the default minimum speed, chosen
  // from the record (modelgen/signal/reversal_speed.hpp), below which each joint's equations
  // near a reversal are weighted down before the decimation (modelgen/signal/reversal_mask.hpp;
  // the README's --min-speed 0.1, tuned on the TX-40 record, gave 0/0/0 too). Before that weighting the defaults left 3 (WLS) and
  // 4 (IV) of 64 beyond 3 sd (ZZ2R 5.0 sd), and the test ran --cutoff 100 --decimate 10, tuned
  // on this record (issue 31).
  for (const std::string method : {"wls", "iv", "didim"}) {
    const fs::path estimate = *folder_ / (method + ".json");
    const std::string controller =
        method == "wls" ? "" : " --controller " + quoted_source(kData + "controller.yaml");
    const CliRun fit =
        modelid("fit --robot comau_smart_six --data " + quoted(*folder_ / "id.csv") + " --method " +
                method + controller + " --torque-hold zoh -o " + quoted(estimate));
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

// Per joint, over the periods after the first (the transient), the deviations of each period
// from their mean: the rms of the positions' deviations and the correlation of the torques'
// deviations with the D term's response to the positions' deviations, -(d_k - d_k-1).
struct PeriodSpread {
  std::vector<double> q_rms, d_response_correlation;
};

PeriodSpread period_spread(const CsvTable& record, int samples_per_period, int dof) {
  const int periods = static_cast<int>(record.rows.size()) / samples_per_period;
  PeriodSpread out;
  for (int j = 1; j <= dof; ++j) {
    const int qc = record.column("q" + std::to_string(j));
    const int tc = record.column("tau" + std::to_string(j));
    std::vector<double> mean_q(samples_per_period, 0.0), mean_tau(samples_per_period, 0.0);
    for (int p = 1; p < periods; ++p) {
      for (int k = 0; k < samples_per_period; ++k) {
        mean_q[k] += record.rows[p * samples_per_period + k][qc] / (periods - 1);
        mean_tau[k] += record.rows[p * samples_per_period + k][tc] / (periods - 1);
      }
    }
    double qq = 0, dd = 0, tt = 0, dt = 0;
    long count = 0;
    for (int p = 1; p < periods; ++p) {
      const auto& rows = record.rows;
      for (int k = 1; k < samples_per_period; ++k) {
        const std::size_t i = static_cast<std::size_t>(p * samples_per_period + k);
        const double q = rows[i][qc] - mean_q[k], q_before = rows[i - 1][qc] - mean_q[k - 1];
        const double tau = rows[i][tc] - mean_tau[k], response = -(q - q_before);
        qq += q * q;
        dd += response * response;
        tt += tau * tau;
        dt += response * tau;
        ++count;
      }
    }
    out.q_rms.push_back(std::sqrt(qq / count));
    out.d_response_correlation.push_back(dt / std::sqrt(dd * tt));
  }
  return out;
}

TEST_F(ModelidComauScenario, ErrorsInVariablesRefusesTheClosedLoopForTheReasonsItGives) {
  const std::string options = " --method ml-eiv --periodic --period 10 --skip-periods 1";
  const CliRun refused =
      modelid("fit --robot comau_smart_six --data " + quoted(*folder_ / "id.csv") + options);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("--method ml-eiv refuses a closed-loop record"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--method iv or didim with --controller"), std::string::npos);

  // The reasons, measured on the record. 5e-7 rad counts leave an error of 5e-7 / sqrt(12)
  // rms; independent from period to period, the deviation from the mean of 3 periods would
  // be sqrt(2/3) of it. The loop repeats most of it: the spread shows under half its variance
  // (measured: 0.43-0.61 of its rms).
  const CsvTable record = read_csv(*folder_ / "id.csv");
  const PeriodSpread spread = period_spread(record, 10000, 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_LT(spread.q_rms[j], 0.7 * std::sqrt(2.0 / 3.0) * 5e-7 / std::sqrt(12.0)) << j + 1;
  }
  // The D term makes the torque's spread follow the positions' on the stiff axes 1-3.
  for (int j = 0; j < 3; ++j) EXPECT_GT(spread.d_response_correlation[j], 0.25) << j + 1;

  // Without its reference columns the record is recognised as closed loop from the data: the
  // torque's deviations follow the position's on joints 1-3. The correlation it prints is that
  // of the best response in each band of lines, so at least about that of the D term's
  // response measured here in the time domain.
  std::string text = read_text(*folder_ / "id.csv"), stripped;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::size_t cut = 0;  // the comma after tau6: the 13th
    for (int c = 0; c < 13; ++c) cut = line.find(',', c == 0 ? 0 : cut + 1);
    stripped += line.substr(0, cut) + "\n";
  }
  ASSERT_EQ(stripped.substr(0, stripped.find('\n')),
            "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6");
  write_text(*folder_ / "id_no_reference.csv", stripped);
  const CliRun fit = modelid("fit --robot comau_smart_six --data " +
                             quoted(*folder_ / "id_no_reference.csv") + options);
  EXPECT_NE(fit.exit_code, 0);
  const std::string refusal = "on joint(s) ";
  const std::size_t at = fit.err.find(refusal);
  ASSERT_NE(at, std::string::npos) << fit.err;
  EXPECT_NE(fit.err.find("eq. 16 takes the errors of q and tau as independent"), std::string::npos);
  EXPECT_NE(fit.err.find("--method iv or didim with --controller"), std::string::npos);
  // "on joint(s) 1, 2, 3 (correlation a, b, c; ...": joints 1-3 at least, and their values.
  std::istringstream named(fit.err.substr(at + refusal.size()));
  std::vector<int> joints;
  std::string token;
  while (named >> token && token != "(correlation") joints.push_back(std::stoi(token));
  std::vector<double> correlation;
  for (std::size_t k = 0; k < joints.size() && named >> token; ++k) {
    correlation.push_back(std::stod(token));
  }
  ASSERT_EQ(correlation.size(), joints.size()) << fit.err;
  for (int j = 1; j <= 3; ++j) {
    const auto found = std::find(joints.begin(), joints.end(), j);
    ASSERT_NE(found, joints.end()) << j << " not named: " << fit.err;
    EXPECT_GT(correlation[found - joints.begin()], 0.9 * spread.d_response_correlation[j - 1])
        << j << "\n"
        << fit.err;
  }
}

}  // namespace
}  // namespace modelgen::test
