// modelid simulate --drive (Swevers et al. 2002, eq. 12 with the efficiency branch eq. 8) as a
// user runs it, against independent computations: with all efficiencies 1 its torques are those
// of `simulate --params` on the equivalent standard parameters (drive inertia and friction mapped
// to the joint side by hand here, an independent code path through the base parameters); with
// efficiencies below 1, eq. 8 worked out per sample from the --params torques; a load adds what
// KDL computes for it on the payload link; the noise is on the motor side; usage errors; and the
// bundled KR150 load-identification scenario (robots/data/kr150/load) with `fit --method ml`.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

constexpr int kDof = 6;
// Drive values of the simple checks (motor side): rotor inertia, viscous and Coulomb friction.
constexpr double kJM[kDof] = {2.0, 3.0, 1.5, 0.4, 0.3, 0.2};
constexpr double kRv[kDof] = {8.0, 9.0, 4.0, 1.2, 1.0, 0.8};
constexpr double kRc[kDof] = {15.0, 14.0, 9.0, 3.0, 2.5, 2.0};
// Gear ratios with both signs (add_drive_values maps the drive values to the joint side).
constexpr double kRatio[kDof] = {3.0, -2.0, 1.5, -4.0, 2.5, 1.2};

// robots/kr150.yaml with its `drives:` block replaced by `drives` (YAML lines).
std::string kr150_with_drives(const std::string& drives) {
  const std::string text = read_text(source_path("robots/kr150.yaml"));
  const std::size_t begin = text.find("drives:\n"), end = text.find("friction:");
  EXPECT_NE(begin, std::string::npos);
  EXPECT_NE(end, std::string::npos);
  return text.substr(0, begin) + drives + text.substr(end);
}

// robots/kr150.yaml without its payload line.
std::string kr150_without_payload() {
  std::string text = read_text(source_path("robots/kr150.yaml"));
  const std::string line = "payload: {link: 7}\n";
  const std::size_t at = text.find(line);
  EXPECT_NE(at, std::string::npos);
  return text.erase(at, line.size());
}

std::string ratio_drives() {
  std::string line = "drives:\n  ratio: [";
  for (int j = 0; j < kDof; ++j) line += (j ? ", " : "") + std::to_string(kRatio[j]);
  return line + "]\n";
}

// Inertial parameters XXj..Mj of every body, physically meaningful (KDL oracle's generator).
std::map<std::string, double> link_values(const modelgen::RobotModel& description,
                                          std::uint64_t seed) {
  Random random(seed);
  const Eigen::VectorXd p = random_physical_parameters(description.tree, random);
  std::map<std::string, double> values;
  for (std::size_t k = 0; k < description.tree.params.size(); ++k) {
    const StandardParam& param = description.tree.params[k];
    if (is_inertial(param.kind)) values[param.name] = p[static_cast<Eigen::Index>(k)];
  }
  return values;
}

void write_json(const fs::path& path, const nlohmann::json& json) {
  write_text(path, json.dump(2) + "\n");
}

nlohmann::json standard_file(const std::map<std::string, double>& values) {
  return {{"standard", values}};
}

// A periodic trajectory of the KR150's six joints (position form, Swevers eq. 15): joint 1 held
// at 0.3 rad (motor standing still), the others moving through both signs of velocity.
std::string trajectory_text() {
  return "period: 4\nform: position\njoints:\n"
         "  - {q0: 0.3, terms: []}\n"
         "  - {q0: -1.2, terms: [{l: 1, a: 0.3, b: 0.1}, {l: 3, a: -0.05, b: 0.04}]}\n"
         "  - {q0: 0.8, terms: [{l: 1, a: -0.25, b: 0.2}, {l: 2, a: 0.1, b: -0.05}]}\n"
         "  - {q0: 0.0, terms: [{l: 1, a: 0.6, b: -0.3}, {l: 2, a: 0.2, b: 0.3}]}\n"
         "  - {q0: 0.3, terms: [{l: 1, a: 0.5, b: 0.25}, {l: 3, a: -0.1, b: 0.1}]}\n"
         "  - {q0: 0.0, terms: [{l: 1, a: 0.7, b: 0.4}, {l: 2, a: -0.3, b: 0.2}]}\n";
}

// JM, Rv, Rc of every motor into `theta` and their joint-side equivalent into `standard`: on
// the diagonal chain of ratio_drives() Ia = k^2 JM, Fv = k^2 Rv, Fc = |k| Rc (tau = k tau_M,
// dq_M = k dq); on the KR150's coupled wrist (ratios 1) motors 5 and 6, which turn with several
// joints, as the coupled motor's Iam, Fvm, Fcm (Gautier & Briot eq. 26).
void add_drive_values(nlohmann::json& theta, std::map<std::string, double>& standard,
                      bool coupled_wrist) {
  for (int j = 0; j < kDof; ++j) {
    const std::string n = std::to_string(j + 1);
    const double k = coupled_wrist ? 1.0 : kRatio[j];
    const std::string stem = coupled_wrist && j >= 4 ? "m" : "";
    theta["JM" + n] = kJM[j];
    theta["Rv" + n] = kRv[j];
    theta["Rc" + n] = kRc[j];
    standard["Ia" + stem + n] = k * k * kJM[j];
    standard["Fv" + stem + n] = k * k * kRv[j];
    standard["Fc" + stem + n] = std::abs(k) * kRc[j];
  }
}

CliRun simulate(const fs::path& robot, const std::string& mode, const fs::path& values,
                const fs::path& trajectory, const std::string& noise, const fs::path& out) {
  return modelid("simulate --robot " + quoted(robot) + " " + mode + " " + quoted(values) +
                 " --trajectory " + quoted(trajectory) + " --noise " + noise +
                 " --seed 7 --sample-time 0.02 -o " + quoted(out));
}

// The column `prefix` (q, dq, ddq, tau) of joint j (1-based) of a CSV.
std::vector<double> column(const CsvTable& table, const std::string& prefix, int j) {
  const int c = table.column(prefix + std::to_string(j));
  std::vector<double> out;
  for (const std::vector<double>& row : table.rows) out.push_back(row[c]);
  return out;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Every tau column of `a` equals `b`'s to 1e-9 of the column's largest torque; q, dq, ddq equal.
void expect_same_torques(const CsvTable& a, const CsvTable& b) {
  ASSERT_EQ(a.header, b.header);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (int j = 1; j <= kDof; ++j) {
    for (const char* prefix : {"q", "dq", "ddq"}) {
      EXPECT_EQ(column(a, prefix, j), column(b, prefix, j)) << prefix << j;
    }
    const std::vector<double> ta = column(a, "tau", j), tb = column(b, "tau", j);
    const double scale = std::max(1.0, max_abs(tb));
    for (std::size_t s = 0; s < ta.size(); ++s) {
      ASSERT_NEAR(ta[s], tb[s], 1e-9 * scale) << "tau" << j << " sample " << s;
    }
  }
}

// With every efficiency 1 (Rz not given: 1), a diagonal drive chain with gear ratios of both
// signs: the drive model's joint-side torques K^T tau_M equal the standard model's with
// Ia = k^2 JM, Fv = k^2 Rv, Fc = |k| Rc.
TEST(ModelidSimulate, DriveTorquesEqualTheStandardModelWithGearRatios) {
  const fs::path dir = test_folder();
  write_text(dir / "robot.yaml", kr150_with_drives(ratio_drives()));
  write_text(dir / "traj.yaml", trajectory_text());
  const modelgen::RobotModel description = modelgen::load_robot((dir / "robot.yaml").string());
  ASSERT_EQ(description.drives.motor_from_joint(1, 1), -2.0);
  const std::map<std::string, double> links = link_values(description, 11);

  nlohmann::json theta(links);
  std::map<std::string, double> standard = links;
  add_drive_values(theta, standard, false);
  write_json(dir / "theta.json", theta);
  write_json(dir / "standard.json", standard_file(standard));

  const CliRun drive = simulate(dir / "robot.yaml", "--drive", dir / "theta.json",
                                dir / "traj.yaml", "0", dir / "drive.csv");
  ASSERT_EQ(drive.exit_code, 0) << drive.err;
  const CliRun params = simulate(dir / "robot.yaml", "--params", dir / "standard.json",
                                 dir / "traj.yaml", "0", dir / "params.csv");
  ASSERT_EQ(params.exit_code, 0) << params.err;
  const CsvTable a = read_csv(dir / "drive.csv"), b = read_csv(dir / "params.csv");
  ASSERT_EQ(a.rows.size(), 200u);
  expect_same_torques(a, b);
  // The Rz defaults are reported once, compactly; no load was given.
  EXPECT_NE(drive.err.find("Rz1 Rz2 Rz3 Rz4 Rz5 Rz6"), std::string::npos) << drive.err;
  EXPECT_NE(drive.err.find("no load"), std::string::npos) << drive.err;
  EXPECT_EQ(std::count(drive.err.begin(), drive.err.end(), '\n'), 2) << drive.err;
}

// The KR150's coupled wrist (K = V^-1, motors 5 and 6 turn with several joints): the standard
// model carries those motors' inertia and friction as Iam, Fvm, Fcm on the coupled motor
// (Gautier & Briot eq. 26, reference_dynamics.cpp), the drive model as K^T (JM ddq_M + ...).
TEST(ModelidSimulate, DriveTorquesEqualTheStandardModelOnTheCoupledWrist) {
  const fs::path dir = test_folder();
  write_text(dir / "traj.yaml", trajectory_text());
  const fs::path robot = source_path("robots/kr150.yaml");
  const modelgen::RobotModel description = modelgen::load_robot(robot.string());
  const std::map<std::string, double> links = link_values(description, 12);

  nlohmann::json theta(links);
  std::map<std::string, double> standard = links;
  add_drive_values(theta, standard, true);
  for (int j = 0; j < kDof; ++j) theta["Rz" + std::to_string(j + 1)] = 1.0;
  write_json(dir / "theta.json", theta);
  write_json(dir / "standard.json", standard_file(standard));

  const CliRun drive =
      simulate(robot, "--drive", dir / "theta.json", dir / "traj.yaml", "0", dir / "drive.csv");
  ASSERT_EQ(drive.exit_code, 0) << drive.err;
  const CliRun params = simulate(robot, "--params", dir / "standard.json", dir / "traj.yaml", "0",
                                 dir / "params.csv");
  ASSERT_EQ(params.exit_code, 0) << params.err;
  expect_same_torques(read_csv(dir / "drive.csv"), read_csv(dir / "params.csv"));
  // Nothing defaulted but the load: the note says only that.
  EXPECT_EQ(drive.err.find("Rz"), std::string::npos) << drive.err;
}

// Eq. 8 with efficiencies below 1, per sample: on a diagonal chain tau = k tau_M and
// tau'_G dq_M has the sign of tau_G dq, so the written torque is
//   g tau_G(rigid) + (Ia ddq + Fv dq + Fc sign dq),  g = 1/Rz motoring (tau_G dq > 0),
//   Rz braking (< 0), (1/Rz + Rz)/2 with the motor standing still (drive_model.hpp),
// with tau_G(rigid) and the drive terms from two --params runs.
TEST(ModelidSimulate, EfficiencyFollowsEquation8) {
  const fs::path dir = test_folder();
  write_text(dir / "robot.yaml", kr150_with_drives(ratio_drives()));
  write_text(dir / "traj.yaml", trajectory_text());
  const modelgen::RobotModel description = modelgen::load_robot((dir / "robot.yaml").string());
  const std::map<std::string, double> links = link_values(description, 13);
  constexpr double kRz[kDof] = {0.8, 0.9, 0.85, 0.7, 0.9, 0.6};

  nlohmann::json theta(links);
  std::map<std::string, double> drive_only;
  add_drive_values(theta, drive_only, false);
  for (int j = 0; j < kDof; ++j) theta["Rz" + std::to_string(j + 1)] = kRz[j];
  write_json(dir / "theta.json", theta);
  write_json(dir / "rigid.json", standard_file(links));
  write_json(dir / "drive_only.json", standard_file(drive_only));

  ASSERT_EQ(simulate(dir / "robot.yaml", "--drive", dir / "theta.json", dir / "traj.yaml", "0",
                     dir / "drive.csv")
                .exit_code,
            0);
  ASSERT_EQ(simulate(dir / "robot.yaml", "--params", dir / "rigid.json", dir / "traj.yaml", "0",
                     dir / "rigid.csv")
                .exit_code,
            0);
  ASSERT_EQ(simulate(dir / "robot.yaml", "--params", dir / "drive_only.json", dir / "traj.yaml",
                     "0", dir / "drive_only.csv")
                .exit_code,
            0);
  const CsvTable drive = read_csv(dir / "drive.csv"), rigid = read_csv(dir / "rigid.csv"),
                 terms = read_csv(dir / "drive_only.csv");
  int motoring = 0, braking = 0, still = 0;
  for (int j = 1; j <= kDof; ++j) {
    const std::vector<double> tau = column(drive, "tau", j), tau_G = column(rigid, "tau", j),
                              extra = column(terms, "tau", j), dq = column(rigid, "dq", j);
    const double Rz = kRz[j - 1], scale = std::max(1.0, max_abs(tau_G));
    for (std::size_t s = 0; s < tau.size(); ++s) {
      double g = (1 / Rz + Rz) / 2;
      if (dq[s] != 0 && tau_G[s] * dq[s] > 0) {
        g = 1 / Rz;
        ++motoring;
      } else if (dq[s] != 0 && tau_G[s] * dq[s] < 0) {
        g = Rz;
        ++braking;
      } else {
        ++still;
      }
      ASSERT_NEAR(tau[s], g * tau_G[s] + extra[s], 1e-9 * scale) << "tau" << j << " sample " << s;
    }
  }
  // Every branch was exercised: joint 1 stands still throughout.
  EXPECT_GT(motoring, 100);
  EXPECT_GT(braking, 100);
  EXPECT_GE(still, 200);
}

// A load (Table 2 of the paper) on the payload link adds exactly the joint torques of the load
// alone, computed here by KDL on the description's tree with the load's standard parameters on
// link 7 (efficiencies 1, so the drive model is linear in the inertial parameters).
TEST(ModelidSimulate, LoadAddsItsTorqueOnThePayloadLink) {
  const fs::path dir = test_folder();
  write_text(dir / "traj.yaml", trajectory_text());
  const fs::path robot = source_path("robots/kr150.yaml");
  const modelgen::RobotModel description = modelgen::load_robot(robot.string());
  ASSERT_EQ(description.payload_body, 6);
  nlohmann::json theta(link_values(description, 14));
  for (int j = 0; j < kDof; ++j) theta["Rv" + std::to_string(j + 1)] = kRv[j];
  write_json(dir / "bare.json", theta);
  LoadParameters load;
  load.mass = 125.46;
  load.com = {0.088, -0.032, 0.140};
  load.inertia = {38.21, 6.55, 37.13, 7.28, 1.49, -1.23};
  const std::array<double, kLoadParams> values = load.to_vector();
  for (int m = 0; m < kLoadParams; ++m) theta[load_param_names()[m]] = values[m];
  write_json(dir / "loaded.json", theta);

  ASSERT_EQ(simulate(robot, "--drive", dir / "bare.json", dir / "traj.yaml", "0", dir / "bare.csv")
                .exit_code,
            0);
  const CliRun loaded =
      simulate(robot, "--drive", dir / "loaded.json", dir / "traj.yaml", "0", dir / "loaded.csv");
  ASSERT_EQ(loaded.exit_code, 0) << loaded.err;
  EXPECT_EQ(loaded.err.find("no load"), std::string::npos) << loaded.err;

  // The load's standard parameters about the flange frame origin, by the parallel-axis theorem
  // written out here (Ixy etc. are tensor entries: XY = Ixy - m cx cy).
  const double m = load.mass, cx = load.com[0], cy = load.com[1], cz = load.com[2];
  const std::map<std::string, double> load_standard = {
      {"XX7", load.inertia[0] + m * (cy * cy + cz * cz)},
      {"YY7", load.inertia[1] + m * (cx * cx + cz * cz)},
      {"ZZ7", load.inertia[2] + m * (cx * cx + cy * cy)},
      {"XY7", load.inertia[3] - m * cx * cy},
      {"XZ7", load.inertia[4] - m * cx * cz},
      {"YZ7", load.inertia[5] - m * cy * cz},
      {"MX7", m * cx},
      {"MY7", m * cy},
      {"MZ7", m * cz},
      {"M7", m}};
  Eigen::VectorXd p =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(description.tree.params.size()));
  for (std::size_t k = 0; k < description.tree.params.size(); ++k) {
    const auto found = load_standard.find(description.tree.params[k].name);
    if (found != load_standard.end()) p[static_cast<Eigen::Index>(k)] = found->second;
  }
  const CsvTable bare = read_csv(dir / "bare.csv"), with_load = read_csv(dir / "loaded.csv");
  ASSERT_EQ(bare.rows.size(), with_load.rows.size());
  double largest = 0;
  for (std::size_t s = 0; s < bare.rows.size(); ++s) {
    Eigen::VectorXd q(kDof), dq(kDof), ddq(kDof);
    for (int j = 0; j < kDof; ++j) {
      q[j] = with_load.at(s, "q" + std::to_string(j + 1));
      dq[j] = with_load.at(s, "dq" + std::to_string(j + 1));
      ddq[j] = with_load.at(s, "ddq" + std::to_string(j + 1));
    }
    const Eigen::VectorXd expected = kdl_inverse_dynamics(description.tree, q, dq, ddq, p);
    for (int j = 0; j < kDof; ++j) {
      const std::string tau = "tau" + std::to_string(j + 1);
      ASSERT_NEAR(with_load.at(s, tau) - bare.at(s, tau), expected[j],
                  1e-9 * std::max(1.0, expected.cwiseAbs().maxCoeff()))
          << tau << " sample " << s;
      largest = std::max(largest, std::abs(expected[j]));
    }
  }
  EXPECT_GT(largest, 1000.0);  // 125 kg at 1.3 m and more: the check is not vacuous
}

// Noise is added to the motor torques, then mapped to the joints by tau = K^T tau_M: noise on
// motor 6 alone reaches joints 4 and 5 through the coupling (K_64, K_65) and not joints 1-3.
// Per-axis sigmas in --params mode apply to the joint torques, and a list of equal sigmas is the
// single sigma.
TEST(ModelidSimulate, NoiseIsPerMotorOnTheMotorSide) {
  const fs::path dir = test_folder();
  write_text(dir / "traj.yaml", trajectory_text());
  const fs::path robot = source_path("robots/kr150.yaml");
  const modelgen::RobotModel description = modelgen::load_robot(robot.string());
  write_json(dir / "theta.json", nlohmann::json(link_values(description, 15)));
  ASSERT_EQ(
      simulate(robot, "--drive", dir / "theta.json", dir / "traj.yaml", "0", dir / "clean.csv")
          .exit_code,
      0);
  const CliRun noisy = simulate(robot, "--drive", dir / "theta.json", dir / "traj.yaml",
                                "0,0,0,0,0,3", dir / "noisy.csv");
  ASSERT_EQ(noisy.exit_code, 0) << noisy.err;
  const CsvTable clean = read_csv(dir / "clean.csv"), table = read_csv(dir / "noisy.csv");
  const Eigen::MatrixXd& K = description.drives.motor_from_joint;
  double sum2 = 0;
  for (std::size_t s = 0; s < clean.rows.size(); ++s) {
    const auto d = [&](int j) {
      const std::string tau = "tau" + std::to_string(j);
      return table.at(s, tau) - clean.at(s, tau);
    };
    for (int j = 1; j <= 3; ++j) EXPECT_EQ(d(j), 0.0) << "tau" << j;
    const double n6 = d(6);
    EXPECT_NEAR(d(4), K(5, 3) * n6, 1e-9);
    EXPECT_NEAR(d(5), K(5, 4) * n6, 1e-9);
    sum2 += n6 * n6;
  }
  EXPECT_NEAR(std::sqrt(sum2 / clean.rows.size()), 3.0, 0.45);  // 200 samples: 5% sd

  // --params: one sigma per joint on the joint torques; equal ones give the single-sigma file.
  write_text(dir / "zero.json", "{\"base\": {}}");
  const auto params_run = [&](const std::string& noise, const std::string& name) {
    const CliRun run =
        simulate(robot, "--params", dir / "zero.json", dir / "traj.yaml", noise, dir / name);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return read_text(dir / name);
  };
  EXPECT_EQ(params_run("2", "one.csv"), params_run("2,2,2,2,2,2", "six.csv"));
  params_run("0,0,0,0,2,0", "fifth.csv");
  const CsvTable fifth = read_csv(dir / "fifth.csv");
  for (std::size_t s = 0; s < fifth.rows.size(); ++s) {
    EXPECT_EQ(fifth.at(s, "tau6"), 0.0);
    EXPECT_EQ(fifth.at(s, "tau4"), 0.0);
  }
  EXPECT_GT(max_abs(column(fifth, "tau", 5)), 1.0);
}

TEST(ModelidSimulate, UsageAndInputErrors) {
  const fs::path dir = test_folder();
  write_text(dir / "traj.yaml", trajectory_text());
  write_text(dir / "theta.json", "{\"JM3\": 8}");
  write_text(dir / "zero.json", "{\"base\": {}}");
  const std::string robot = quoted_source("robots/kr150.yaml");
  const std::string rest =
      " --trajectory " + quoted(dir / "traj.yaml") + " -o " + quoted(dir / "out.csv");
  const std::string drive = " --drive " + quoted(dir / "theta.json");
  const std::string params = " --params " + quoted(dir / "zero.json");
  struct Case {
    std::string arguments, message;
    int exit_code;
  };
  write_text(dir / "unknown.json", "{\"JM3\": 8, \"Ia3\": 8}");
  write_text(dir / "no_payload.yaml", kr150_without_payload());
  write_text(dir / "load.json",
             "{\"load_m\": 10, \"load_Ixx\": 1, \"load_Iyy\": 1, "
             "\"load_Izz\": 1}");
  write_text(dir / "flat_load.json",
             "{\"load_m\": 10, \"load_Ixx\": 1, \"load_Iyy\": 1, \"load_Izz\": 3}");
  write_text(dir / "bad_rz.json", "{\"Rz4\": 0}");
  const std::vector<Case> cases = {
      {"simulate --robot " + robot + drive + params + " --noise 1" + rest,
       "--drive and --params exclude each other", 2},
      {"simulate --robot " + robot + " --noise 1" + rest,
       "simulate needs --params TRUE.json (base or standard parameters) or --drive THETA.json", 2},
      {"simulate --robot kr150" + drive + " --noise 1" + rest,
       "--drive needs --robot to be a description file (.yaml/.urdf), not 'kr150'", 2},
      {"simulate --robot " + robot + drive + " --noise 1,2,3" + rest,
       "--noise needs one standard deviation or 6 (one per motor), not 3: '1,2,3'", 2},
      {"simulate --robot " + robot + params + " --noise 1,2" + rest,
       "--noise needs one standard deviation or 6 (one per joint), not 2: '1,2'", 2},
      {"simulate --robot " + robot + params + " --noise 1,-2,1,1,1,1" + rest,
       "--noise: a standard deviation cannot be negative, not '-2'", 2},
      {"simulate --robot " + robot + " --drive " + quoted(dir / "unknown.json") + " --noise 1" +
           rest,
       "unknown.json:1:12: error: 'Ia3' is not a parameter of the drive model", 1},
      {"simulate --robot " + quoted(dir / "no_payload.yaml") + " --drive " +
           quoted(dir / "load.json") + " --noise 1" + rest,
       "load.json: error: a load is given but " + (dir / "no_payload.yaml").string() +
           " names no payload link (add 'payload: {link: N}')",
       1},
      {"simulate --robot " + robot + " --drive " + quoted(dir / "flat_load.json") + " --noise 1" +
           rest,
       "flat_load.json: error: the load is not physically consistent: ", 1},
      {"simulate --robot " + robot + " --drive " + quoted(dir / "bad_rz.json") + " --noise 1" +
           rest,
       "bad_rz.json: error: these values cannot be those of a physical robot: Rz4 = 0 is no efficiency (0 < Rz <= 1)", 1},
  };
  for (const Case& c : cases) {
    const CliRun run = modelid(c.arguments);
    EXPECT_EQ(run.exit_code, c.exit_code) << c.arguments << "\n" << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos) << c.arguments << "\n" << run.err;
    EXPECT_FALSE(fs::exists(dir / "out.csv")) << c.arguments;
  }
  // The help names the drive mode.
  const CliRun help = modelid("simulate --help");
  EXPECT_NE(help.out.find("--drive THETA.json"), std::string::npos) << help.out;
}

// The bundled scenario of robots/data/kr150/load, the README's first command: the documented
// command makes ten periods of the Table 1 excitation (1540 samples each, axes 1-2 held), and
// `fit --method ml --approach all` with the a-priori values of known.json compares the three
// approaches. Approach 3 finds the load of drive_truth.json within 4 of its reported standard
// deviations and within Table 2's approach-3 errors, with rms torque errors per axis at the
// noise of the average; approach 1 (R_z taken as 1 while it is 0.85-0.9) misses the mass by many
// of its own standard deviations.
TEST(ModelidSimulate, BundledLoadScenario) {
  const fs::path dir = test_folder();
  const std::string folder = "robots/data/kr150/load/";
  const std::string options = "--trajectory " + folder +
                              "table1.yaml --noise 345,345,345,133,126,123 --seed 2002 "
                              "--sample-time 0.024 --periods 10 --ignore-limits";
  const std::string readme = read_text(source_path(folder + "README.md"));
  const std::string documented = "modelid simulate --robot robots/kr150.yaml --drive " + folder +
                                 "drive_truth.json " + options;
  ASSERT_NE(readme.find(documented), std::string::npos)
      << folder << "README.md no longer documents: " << documented;
  const fs::path csv = dir / "run.csv";
  const CliRun run = modelid("simulate --robot " + quoted_source("robots/kr150.yaml") +
                             " --drive " + quoted_source(folder + "drive_truth.json") +
                             " --trajectory " + quoted_source(folder + "table1.yaml") +
                             " --noise 345,345,345,133,126,123 --seed 2002 --sample-time 0.024"
                             " --periods 10 --ignore-limits -o " +
                             quoted(csv));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err.find("note"), std::string::npos) << "every value is given: " << run.err;

  const CsvTable table = read_csv(csv);
  ASSERT_EQ(table.rows.size(), 15400u);
  std::vector<std::string> header = {"t"};
  for (const char* prefix : {"q", "dq", "ddq", "tau"}) {
    for (int j = 1; j <= kDof; ++j) header.push_back(prefix + std::to_string(j));
  }
  EXPECT_EQ(table.header, header);
  EXPECT_NEAR(table.rows.back()[0], 15399 * 0.024, 1e-9);
  for (std::size_t s = 0; s < table.rows.size(); ++s) {
    ASSERT_EQ(table.at(s, "q1"), 0.0) << s;
    ASSERT_NEAR(table.at(s, "q2"), -M_PI / 2, 1e-15) << s;
    for (const char* name : {"dq1", "dq2", "ddq1", "ddq2"}) ASSERT_EQ(table.at(s, name), 0.0);
  }
  // Table 1: q3 = 1.57 + a25 sin(25 wf t) + b25 cos(25 wf t), at t = 3 s.
  const double wf = 2 * M_PI / 36.96;
  const std::size_t s1 = 125;
  const double t1 = table.at(s1, "t");
  EXPECT_NEAR(table.at(s1, "q3"),
              1.57 + 8.72e-2 * std::sin(25 * wf * t1) - 4.62e-3 * std::cos(25 * wf * t1), 1e-12);

  const std::string top_readme = read_text(source_path("README.md"));
  for (const std::string& command :
       {documented, "modelid fit --method ml --approach all --robot robots/kr150.yaml --known " +
                        folder + "known.json --data build/kr150_load.csv --periodic --period " +
                        "36.96 --truth " + folder + "drive_truth.json"}) {
    EXPECT_NE(
        top_readme.substr(0, top_readme.find("```", top_readme.find("```") + 3)).find(command),
        std::string::npos)
        << "README.md's first command no longer runs: " << command;
  }
  const fs::path estimate = dir / "est.json";
  const CliRun fit =
      modelid("fit --method ml --approach all --robot " + quoted_source("robots/kr150.yaml") +
              " --known " + quoted_source(folder + "known.json") + " --data " + quoted(csv) +
              " --periodic --period 36.96 --truth " + quoted_source(folder + "drive_truth.json") +
              " -o " + quoted(estimate));
  ASSERT_EQ(fit.exit_code, 0) << fit.out << fit.err;
  std::printf("%s%s", fit.out.c_str(), fit.err.c_str());
  // Every value is known a priori: the only warnings are those about impossible estimates
  // (modelid_ml_test.cpp checks them) and the residual check's on approaches 1 and 2, whose
  // efficiencies fixed to 1 the simulation does not follow (modelid_ml_residual_check_test).
  std::istringstream err_lines(fit.err);
  for (std::string line; std::getline(err_lines, line);) {
    if (line.find("warning") == std::string::npos) continue;
    const bool fixed_efficiency = line.find("the residual (of approach 1)") != std::string::npos ||
                                  line.find("the residual (of approach 2)") != std::string::npos;
    EXPECT_TRUE(line.find("cannot be") != std::string::npos || fixed_efficiency) << line;
  }
  EXPECT_NE(fit.out.find("drive model: generated kr150"), std::string::npos) << fit.out;
  const nlohmann::json all = nlohmann::json::parse(read_text(estimate));
  ASSERT_EQ(all["approaches"].size(), 3u);
  const nlohmann::json& est = all["approaches"][2];
  ASSERT_EQ(est["method"], "ML approach 3");
  EXPECT_EQ(est["identifiability"]["rank"], 22);
  const nlohmann::json truth =
      nlohmann::json::parse(read_text(source_path(folder + "drive_truth.json")));
  const nlohmann::json& load = est["load"];
  const nlohmann::json& sd = load["std"];
  struct Entry {
    const char* name;
    nlohmann::json value, std;
    double scale;
    const char* unit;
    double paper;  // Swevers Table 2, approach 3: average error
  };
  const std::vector<Entry> entries = {
      {"load_m", load["m"], sd["m"], 1, "kg", 0.85},
      {"load_cx", load["c"][0], sd["c"][0], 1e3, "mm", 1},
      {"load_cy", load["c"][1], sd["c"][1], 1e3, "mm", 2},
      {"load_cz", load["c"][2], sd["c"][2], 1e3, "mm", 4},
      {"load_Ixx", load["I"]["xx"], sd["I"]["xx"], 1, "kg m^2", 0.70},
      {"load_Iyy", load["I"]["yy"], sd["I"]["yy"], 1, "kg m^2", 1.72},
      {"load_Izz", load["I"]["zz"], sd["I"]["zz"], 1, "kg m^2", 0.39},
      {"load_Ixy", load["I"]["xy"], sd["I"]["xy"], 1, "kg m^2", 0.26},
      {"load_Ixz", load["I"]["xz"], sd["I"]["xz"], 1, "kg m^2", 0.34},
      {"load_Iyz", load["I"]["yz"], sd["I"]["yz"], 1, "kg m^2", 0.18}};
  std::printf("%-9s %10s %10s %10s %8s %12s\n", "load", "truth", "estimate", "error", "sd",
              "paper error");
  for (const Entry& e : entries) {
    ASSERT_TRUE(e.value.is_number() && e.std.is_number()) << e.name;
    const double exact = truth[e.name].get<double>(), value = e.value.get<double>(),
                 std = e.std.get<double>();
    std::printf("%-9s %10.4f %10.4f %10.4f %8.4f %12.2f %s\n", e.name, exact * e.scale,
                value * e.scale, (value - exact) * e.scale, std * e.scale, e.paper, e.unit);
    EXPECT_LT(std::abs(value - exact), 4 * std) << e.name;
    EXPECT_LT(std::abs(value - exact) * e.scale, e.paper) << e.name << " beyond Table 2";
  }
  // Approach 1: the linear route with R_z = 1 is biased (Swevers Table 2).
  const nlohmann::json& est1 = all["approaches"][0];
  ASSERT_EQ(est1["method"], "ML approach 1");
  const double m1 = est1["load"]["m"].get<double>(), sd1 = est1["load"]["std"]["m"].get<double>();
  const double m_exact = truth["load_m"].get<double>();
  std::printf("approach 1 mass %.3f +- %.3f kg, approach 3 %.3f kg, exact %.2f kg\n", m1, sd1,
              load["m"].get<double>(), m_exact);
  EXPECT_GT(std::abs(m1 - m_exact), 5 * sd1);
  EXPECT_GT(std::abs(m1 - m_exact), 10 * std::abs(load["m"].get<double>() - m_exact));
  // rms per motor of the fitted axes at the noise of the ten-period average, sigma / sqrt(10)
  // (Table 3, approach 3: 109, 42, 40, 39 N m).
  const double sigma[kDof] = {345, 345, 345, 133, 126, 123};
  for (int i = 2; i < kDof; ++i) {
    EXPECT_NEAR(est["rms_per_axis"][i].get<double>(), sigma[i] / std::sqrt(10.0),
                0.1 * sigma[i] / std::sqrt(10.0))
        << "axis " << i + 1;
  }
}

// Swevers section 4.2: moving only the wrist leaves the load mass unidentifiable (19 unknowns,
// rank 18). The fit names it and, since the centre of gravity and the inertia about it depend on
// the mass, reports no number for any load parameter; the drive parameters stay identified. With
// the mass given a priori (weighed) the other 18 unknowns are identified.
TEST(ModelidSimulate, WristOnlyNeedsAKnownLoadMass) {
  const fs::path dir = test_folder();
  const std::string folder = "robots/data/kr150/load/";
  std::string trajectory = read_text(source_path(folder + "table1.yaml"));
  const std::string axis3 = "terms: [{l: 25, a: 8.72e-2, b: -4.62e-3}]";
  ASSERT_NE(trajectory.find(axis3), std::string::npos);
  trajectory.replace(trajectory.find(axis3), axis3.size(), "terms: []");
  write_text(dir / "wrist.yaml", trajectory);
  ASSERT_EQ(modelid("simulate --robot " + quoted_source("robots/kr150.yaml") + " --drive " +
                    quoted_source(folder + "drive_truth.json") + " --trajectory " +
                    quoted(dir / "wrist.yaml") +
                    " --noise 345,345,345,133,126,123 --seed 7 --sample-time 0.024 --periods 10 "
                    "--ignore-limits "
                    "-o " +
                    quoted(dir / "wrist.csv"))
                .exit_code,
            0);
  const nlohmann::json truth =
      nlohmann::json::parse(read_text(source_path(folder + "drive_truth.json")));
  const auto fit = [&](const fs::path& known, const std::string& out) {
    return modelid("fit --method ml --approach 3 --robot " + quoted_source("robots/kr150.yaml") +
                   " --known " + quoted(known) + " --data " + quoted(dir / "wrist.csv") +
                   " --periodic --period 36.96 -o " + quoted(dir / out));
  };

  const CliRun no_mass = fit(fs::path(source_path(folder + "known.json")), "no_mass.json");
  ASSERT_EQ(no_mass.exit_code, 0) << no_mass.out << no_mass.err;
  std::printf("%s", no_mass.out.c_str());
  const nlohmann::json est = nlohmann::json::parse(read_text(dir / "no_mass.json"));
  EXPECT_EQ(est["identifiability"]["rank"], 18);
  EXPECT_EQ(est["identifiability"]["unknowns"], 19);
  ASSERT_EQ(est["identifiability"]["directions"].size(), 1u);
  EXPECT_EQ(est["identifiability"]["directions"][0].get<std::string>().rfind("load_m (", 0), 0u);
  EXPECT_TRUE(est["load"]["m"].is_null());
  EXPECT_TRUE(est["load"]["c"][2].is_null());
  EXPECT_TRUE(est["load"]["I"]["xx"].is_null());
  EXPECT_TRUE(est["load"]["warnings"].empty());
  for (const nlohmann::json& p : est["parameters"]) EXPECT_TRUE(p["value"].is_number()) << p;

  nlohmann::json known = nlohmann::json::parse(read_text(source_path(folder + "known.json")));
  known["load_m"] = truth["load_m"];
  write_text(dir / "known_mass.json", known.dump());
  const CliRun mass = fit(dir / "known_mass.json", "mass.json");
  ASSERT_EQ(mass.exit_code, 0) << mass.out << mass.err;
  std::printf("%s", mass.out.c_str());
  EXPECT_NE(mass.out.find("125.46 (known)"), std::string::npos);
  const nlohmann::json est_mass = nlohmann::json::parse(read_text(dir / "mass.json"));
  EXPECT_EQ(est_mass["identifiability"]["rank"], 18);
  EXPECT_EQ(est_mass["identifiability"]["unknowns"], 18);
  const nlohmann::json& load = est_mass["load"];
  for (int k = 0; k < 3; ++k) {
    const char* name[3] = {"load_cx", "load_cy", "load_cz"};
    EXPECT_LT(std::abs(load["c"][k].get<double>() - truth[name[k]].get<double>()),
              4 * load["std"]["c"][k].get<double>())
        << name[k];
  }
  for (const char* axis : {"xx", "yy", "zz", "xy", "xz", "yz"}) {
    const double exact = truth[std::string("load_I") + axis].get<double>();
    EXPECT_LT(std::abs(load["I"][axis].get<double>() - exact),
              4 * load["std"]["I"][axis].get<double>())
        << axis;
  }

  known["load_m"] = -1;
  write_text(dir / "bad_mass.json", known.dump());
  const CliRun bad = fit(dir / "bad_mass.json", "bad.json");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("bad_mass.json: error: 'load_m' must be positive, not -1"),
            std::string::npos)
      << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad.json"));
}

}  // namespace
}  // namespace modelgen::test
