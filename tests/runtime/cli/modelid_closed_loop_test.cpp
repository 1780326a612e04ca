// modelid simulate --controller and fit --method iv|didim as a user runs them, on the compiled-in
// TX-40 along its bundled design: the written reference equals the Fourier series evaluated
// here; the robot tracks it; IV and DIDIM converge within 4 sd of the truth; validate with the
// truth leaves the measurement noise; usage errors.

#include <cmath>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/tx40_truth.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

const std::string kDesign = "robots/data/tx40/design.yaml";

// The series of the design (form: position), read and summed here: Swevers 2002 eq. 15.
double reference(const YAML::Node& design, int joint, double t) {
  const double w = 2 * M_PI / design["period"].as<double>();
  const YAML::Node j = design["joints"][joint - 1];
  double q = j["q0"].as<double>();
  for (std::size_t l = 0; l < j["a"].size(); ++l) {
    const double lwt = static_cast<double>(l + 1) * w * t;
    q += j["a"][l].as<double>() * std::sin(lwt) + j["b"][l].as<double>() * std::cos(lwt);
  }
  return q;
}

class ModelidClosedLoop : public testing::Test {
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
    const CliRun run = modelid("simulate --robot tx40 --params " + quoted(truth_) +
                               " --trajectory " + quoted_source(kDesign) + " --controller " +
                               quoted(controller_) + " --noise-tau 0.2 " +
                               "--encoder-resolution 1.5e-6 --seed 3 --ignore-limits -o " +
                               quoted(data_));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("largest tracking error per joint"), std::string::npos) << run.err;
  }

  fs::path folder_, controller_, truth_, data_;
};

TEST_F(ModelidClosedLoop, SimulateWritesMeasuredTorqueAndReference) {
  const CsvTable table = read_csv(data_);
  std::vector<std::string> header = {"t"};
  for (const char* prefix : {"q", "tau", "qr"}) {
    for (int j = 1; j <= 6; ++j) header.push_back(prefix + std::to_string(j));
  }
  EXPECT_EQ(table.header, header);
  ASSERT_EQ(table.rows.size(), 10000u);  // one period of 10 s at the controller's 1 kHz
  const YAML::Node design = YAML::LoadFile(source_path(kDesign));
  double worst = 0;
  for (std::size_t k = 0; k < table.rows.size(); k += 7) {
    const double t = table.at(k, "t");
    EXPECT_NEAR(t, 0.001 * static_cast<double>(k), 1e-12);
    for (int j = 1; j <= 6; ++j) {
      const std::string n = std::to_string(j);
      EXPECT_NEAR(table.at(k, "qr" + n), reference(design, j, t), 1e-12) << "t = " << t;
      worst = std::max(worst, std::abs(table.at(k, "q" + n) - table.at(k, "qr" + n)));
    }
  }
  EXPECT_LT(worst, 0.05);  // the PID tracks its reference
  EXPECT_GT(worst, 1e-5);  // and the measured positions are not the reference copied
}

TEST_F(ModelidClosedLoop, IvAndDidimConvergeNearTheTruth) {
  for (const std::string method : {"iv", "didim"}) {
    const fs::path estimate = folder_ / (method + ".json");
    const CliRun fit =
        modelid("fit --robot tx40 --data " + quoted(data_) + " --method " + method +
                " --controller " + quoted(controller_) + " --min-speed 0.1 --torque-hold zoh" +
                " --truth " + quoted(truth_) + " -o " + quoted(estimate));
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    EXPECT_NE(fit.out.find(method == "iv" ? "IDIM-IV from IDIM-WLS" : "DIDIM from IDIM-WLS"),
              std::string::npos)
        << fit.out;
    EXPECT_NE(fit.out.find(", converged,"), std::string::npos) << fit.out;
    EXPECT_NE(fit.out.find("--min-speed: "), std::string::npos) << fit.out;
    const nlohmann::json json = nlohmann::json::parse(read_text(estimate));
    EXPECT_EQ(json["method"], method == "iv" ? "IDIM-IV" : "DIDIM");
    // As the library test: every parameter under 10 %std within 4 sd of the truth. The planned
    // preparation (6.1 Hz, decimation by 42: 20 rows per parameter of this 10 s record) leaves
    // 37 (IV) and 46 (DIDIM) under 10 %std; --cutoff 100 --decimate 10, tuned on this record,
    // left more, but breaks on records with more encoder noise (issue 31).
    int checked = 0;
    for (const nlohmann::json& p : json["parameters"]) {
      if (p["rel_std"].is_null() || p["rel_std"].get<double>() > 10) continue;
      const double value = p["value"], sd = p["std"], truth = p["truth"];
      EXPECT_LT(std::abs(value - truth), 4 * sd) << method << " " << p["name"];
      ++checked;
    }
    EXPECT_GE(checked, method == "iv" ? 34 : 42) << method;
  }
}

TEST_F(ModelidClosedLoop, ValidatingTheTruthLeavesTheMeasurementNoise) {
  // The record's own robot simulated under the same controller: what differs is the noise
  // added to the torques (0.2 N m) and what the recording controller made of the encoder's
  // counts (its D term turns a count of 1.5e-6 rad into 260 * 1.5e-6 / 1 ms = 0.4 N m on
  // joints 1-2), which validate's controller, on the simulated positions, does not see.
  const fs::path plots = folder_ / "plots";
  const CliRun run = modelid("validate --robot tx40 --params " + quoted(truth_) + " --controller " +
                             quoted(controller_) + " --data " + quoted(data_) + " --plot " +
                             quoted(plots));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream lines(run.out);
  std::string line;
  int joints = 0;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    int joint = 0;
    double rms_deg = 0, max_deg = 0, rms_torque = 0, max_torque = 0;
    if (!(fields >> joint >> rms_deg >> max_deg >> rms_torque >> max_torque)) continue;
    ++joints;
    EXPECT_GT(rms_torque, 0.18) << line;
    EXPECT_LT(rms_torque, 0.3) << line;
    EXPECT_LT(max_deg, 5e-3) << line;
  }
  EXPECT_EQ(joints, 6) << run.out;
  const CsvTable positions = read_csv(plots / "positions.csv");
  EXPECT_EQ(positions.rows.size(), 10000u);
  EXPECT_TRUE(fs::exists(plots / "torques.csv"));
}

TEST_F(ModelidClosedLoop, UsageErrors) {
  const std::string fit = "fit --robot tx40 --data " + quoted(data_);
  CliRun run = modelid(fit + " --method iv");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("give --controller C.yaml"), std::string::npos) << run.err;
  run = modelid(fit + " --method wls --controller " + quoted(controller_));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--controller belongs to the closed-loop methods"), std::string::npos)
      << run.err;
  // An open-loop file has no reference.
  const fs::path open_loop = folder_ / "open.csv";
  ASSERT_EQ(modelid("simulate --robot tx40 --params " + quoted(truth_) + " --trajectory " +
                    quoted_source(kDesign) + " --noise 0.01 --ignore-limits -o " +
                    quoted(open_loop))
                .exit_code,
            0);
  run = modelid("fit --robot tx40 --data " + quoted(open_loop) + " --method didim --controller " +
                quoted(controller_));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("needs the reference positions of the record, columns qr1..qr6"),
            std::string::npos)
      << run.err;
  run = modelid("simulate --robot tx40 --params " + quoted(truth_) + " --trajectory " +
                quoted_source(kDesign) + " --controller " +
                quoted(controller_) + " --noise 1 --ignore-limits -o " +
                quoted(folder_ / "x.csv"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--noise-tau"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(folder_ / "x.csv"));
  // Fewer than the 3 samples a record needs.
  run = modelid("simulate --robot tx40 --params " + quoted(truth_) + " --trajectory " +
                quoted_source(kDesign) + " --controller " + quoted(controller_) +
                " --periods 0.0001 --ignore-limits -o " + quoted(folder_ / "x.csv"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--periods must give from 3 to"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(folder_ / "x.csv"));
  // A record of motor currents: validate compares torques and says so.
  std::string text = read_text(data_);
  for (int j = 1; j <= 6; ++j) {
    const std::string from = "tau" + std::to_string(j) + ",", to = "i" + std::to_string(j) + ",";
    text.replace(text.find(from), from.size(), to);
  }
  const fs::path currents = folder_ / "currents.csv";
  write_text(currents, text);
  run = modelid("validate --robot tx40 --params " + quoted(truth_) + " --controller " +
                quoted(controller_) + " --data " + quoted(currents));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("validate compares joint torques"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace modelgen::test
