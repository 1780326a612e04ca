// modelid's data options as a user runs them, on TX-40 data made here from known parameters:
// motor-side files and motor currents give the same estimate as joint-side torques (the drive
// chain converted independently in the test), the periodic route recovers the parameters from
// a record that is not a whole number of periods (and says what it dropped), the non-periodic
// route filters and decimates, and contradictory options are usage errors.

#include <cmath>
#include <fstream>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/signal/decimation.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/kdl_oracle.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::modelid;
using test::quoted;

// A TX-40 with random physical parameters, its base parameters, and a 3-harmonic excitation
// of all joints (period 4 s).
struct Tx40Case {
  Tx40Case() : model(internal::make_shipped_model("tx40")) {
    const modelgen::RobotModel description =
        modelgen::load_robot(test::source_path("robots/tx40.yaml"));
    test::Random random(31);
    const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
    beta.resize(model->num_base_params());
    model->base_from_standard(p.data(), beta.data());
    fourier.period = 4.0;
    fourier.q0 = Eigen::VectorXd::LinSpaced(6, -0.3, 0.4);
    fourier.a.resize(6, 3);
    fourier.b.resize(6, 3);
    for (int j = 0; j < 6; ++j) {
      for (int l = 0; l < 3; ++l) {
        fourier.a(j, l) = random.uniform(-0.6, 0.6);
        fourier.b(j, l) = random.uniform(-0.6, 0.6);
      }
    }
  }
  // Noise-free joint-side samples with their torques.
  Trajectory sampled(double sample_time, double duration) const {
    Trajectory x = sample(fourier, sample_time, duration);
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      Eigen::VectorXd tau(6);
      model->inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
      x.tau.row(s) = tau.transpose();
    }
    return x;
  }
  std::unique_ptr<IdentificationModel> model;
  Eigen::VectorXd beta;
  FourierTrajectory fourier;
};

// t, q and an effort column set (prefix "tau" or "i"), no derivatives: what a controller logs.
void write_log(const fs::path& path, const Eigen::VectorXd& t, const Eigen::MatrixXd& q,
               const Eigen::MatrixXd& effort, const std::string& prefix) {
  std::ofstream out(path);
  out.precision(17);
  out << "t";
  for (int j = 1; j <= q.cols(); ++j) out << ",q" << j;
  for (int j = 1; j <= q.cols(); ++j) out << "," << prefix << j;
  out << "\n";
  for (Eigen::Index s = 0; s < t.size(); ++s) {
    out << t[s];
    for (Eigen::Index j = 0; j < q.cols(); ++j) out << "," << q(s, j);
    for (Eigen::Index j = 0; j < q.cols(); ++j) out << "," << effort(s, j);
    out << "\n";
  }
}

Eigen::VectorXd estimate_values(const fs::path& path) {
  const nlohmann::json estimate = nlohmann::json::parse(test::read_text(path));
  Eigen::VectorXd values(estimate["parameters"].size());
  for (std::size_t b = 0; b < estimate["parameters"].size(); ++b) {
    values[b] = estimate["parameters"][b]["value"].get<double>();
  }
  return values;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / b.norm();
}

TEST(ModelidData, MotorSideFilesGiveTheJointSideEstimate) {
  const fs::path dir = test::test_folder();
  const Tx40Case tx40;
  const Trajectory x = tx40.sampled(0.004, 8.0);
  const Eigen::MatrixXd& K = tx40.model->drive_chain().motor_from_joint;
  // Motor side, independently: q_motor = K q (offsets are zero for tx40), tau_motor solves
  // K^T tau_motor = tau.
  const Eigen::MatrixXd q_motor = x.q * K.transpose();
  const Eigen::MatrixXd tau_motor =
      K.transpose().partialPivLu().solve(x.tau.transpose()).transpose();
  write_log(dir / "joint.csv", x.t, x.q, x.tau, "tau");
  write_log(dir / "motor.csv", x.t, q_motor, tau_motor, "tau");

  // OLS: on noise-free data WLS weights would be round-off levels.
  const CliRun joint = modelid("fit --robot tx40 --method ols --raw --data " +
                               quoted(dir / "joint.csv") + " -o " + quoted(dir / "joint.json"));
  ASSERT_EQ(joint.exit_code, 0) << joint.err;
  const CliRun motor = modelid("fit --robot tx40 --method ols --raw --motor-side --data " +
                               quoted(dir / "motor.csv") + " -o " + quoted(dir / "motor.json"));
  ASSERT_EQ(motor.exit_code, 0) << motor.err;
  const Eigen::VectorXd from_joint = estimate_values(dir / "joint.json");
  EXPECT_LT(relative_difference(estimate_values(dir / "motor.json"), from_joint), 1e-8);
  // Central differences of exact samples: close to the truth, not equal.
  EXPECT_LT(relative_difference(from_joint, tx40.beta), 1e-3);
  // Without --motor-side the same file is nonsense for the joint-side model.
  const CliRun wrong = modelid("fit --robot tx40 --method ols --raw --data " +
                               quoted(dir / "motor.csv") + " -o " + quoted(dir / "wrong.json"));
  if (wrong.exit_code == 0) {
    EXPECT_GT(relative_difference(estimate_values(dir / "wrong.json"), from_joint), 0.1);
  }
}

TEST(ModelidData, MotorCurrentsGoThroughTheTorqueConstants) {
  const fs::path dir = test::test_folder();
  const Tx40Case tx40;
  const Trajectory x = tx40.sampled(0.004, 8.0);
  // The TX-40 description with torque constants added to its drives.
  std::string yaml = test::read_text(test::source_path("robots/tx40.yaml"));
  const std::string anchor = "  ratio: [32, 32, 45, -48, 45, 32]\n";
  ASSERT_NE(yaml.find(anchor), std::string::npos);
  yaml.replace(yaml.find(anchor), anchor.size(),
               anchor + "  torque_constant: [0.9, 0.9, 0.6, 0.35, 0.3, 0.25]\n");
  test::write_text(dir / "tx40.yaml", yaml);
  const Eigen::VectorXd kt = (Eigen::VectorXd(6) << 0.9, 0.9, 0.6, 0.35, 0.3, 0.25).finished();
  const Eigen::MatrixXd& K = tx40.model->drive_chain().motor_from_joint;
  const Eigen::MatrixXd tau_motor =
      K.transpose().partialPivLu().solve(x.tau.transpose()).transpose();
  const Eigen::MatrixXd currents = tau_motor * kt.cwiseInverse().asDiagonal();
  write_log(dir / "torques.csv", x.t, x.q, x.tau, "tau");
  write_log(dir / "currents.csv", x.t, x.q, currents, "i");

  const CliRun torques =
      modelid("fit --robot " + quoted(dir / "tx40.yaml") + " --method ols --raw --data " +
              quoted(dir / "torques.csv") + " -o " + quoted(dir / "torques.json"));
  ASSERT_EQ(torques.exit_code, 0) << torques.err;
  const CliRun from_currents =
      modelid("fit --robot " + quoted(dir / "tx40.yaml") + " --method ols --raw --data " +
              quoted(dir / "currents.csv") + " -o " + quoted(dir / "currents.json"));
  ASSERT_EQ(from_currents.exit_code, 0) << from_currents.err;
  EXPECT_LT(relative_difference(estimate_values(dir / "currents.json"),
                                estimate_values(dir / "torques.json")),
            1e-8);
  // The shipped description gives no torque constants: currents are refused, naming them.
  const CliRun refused =
      modelid("fit --robot tx40 --method ols --raw --data " + quoted(dir / "currents.csv"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("currents.csv"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("torque_constant"), std::string::npos) << refused.err;
}

TEST(ModelidData, PeriodicRouteAveragesAndSaysWhatItDropped) {
  const fs::path dir = test::test_folder();
  const Tx40Case tx40;
  // 6.5 periods of 500 samples, noise-free: the Fourier re-estimation is exact, so is the fit.
  const Trajectory x = tx40.sampled(0.008, 6.5 * tx40.fourier.period);
  write_log(dir / "periodic.csv", x.t, x.q, x.tau, "tau");
  const CliRun run = modelid("fit --robot tx40 --method wls --periodic --data " +
                             quoted(dir / "periodic.csv") + " -o " + quoted(dir / "est.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("periodic: 6 periods of 500 samples"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("3 harmonics"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("warning: the record is not a whole number of periods; the 250 samples"),
            std::string::npos)
      << run.err;
  EXPECT_LT(relative_difference(estimate_values(dir / "est.json"), tx40.beta), 1e-8);
}

TEST(ModelidData, NonPeriodicRouteFiltersAndDecimates) {
  const fs::path dir = test::test_folder();
  const Tx40Case tx40;
  const Trajectory x = tx40.sampled(0.001, 12.0);  // 1 kHz, excitation up to 0.75 Hz
  write_log(dir / "log.csv", x.t, x.q, x.tau, "tau");
  const CliRun run = modelid("fit --robot tx40 --method ols --bandwidth 1 --data " +
                             quoted(dir / "log.csv") + " -o " + quoted(dir / "est.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // plan_filtering: cut-off 10 x 1 Hz; the largest n_d with 0.8 (500 Hz) / n_d >= 2 Hz is 200,
  // but 20 rows per parameter over the 11400 samples the filter's edges leave, 6 axes and the
  // TX-40's 61 base parameters allow at most 11400 x 6 / 1220 = 56.07: 56 = 8 x 7.
  EXPECT_NE(run.out.find("positions low-passed at 10 Hz"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("0.3 s dropped at each end"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("parallel decimation by 56"), std::string::npos) << run.out;
  const nlohmann::json estimate = nlohmann::json::parse(test::read_text(dir / "est.json"));
  // Central differences drop 2 samples, the filter edges 3 cut-off periods (300 samples) at
  // each end; decimation keeps rows 0, 56, 112, ... but those the end samples dominate.
  const Eigen::Index filtered = x.t.size() - 2 - 600;
  EXPECT_EQ(estimate["samples"].get<long long>(), decimated_interior(filtered, 56).count);
  EXPECT_LT(decimated_interior(filtered, 56).count, (filtered + 55) / 56);
  // Noise-free torques stay explained after filtering and decimation: what is left is the
  // filter's smoothing of the sampled positions and of the Coulomb terms' sign steps.
  EXPECT_LT(estimate["rel_error_norm"].get<double>(), 1e-4);
  EXPECT_LT(relative_difference(estimate_values(dir / "est.json"), tx40.beta), 1e-3);
}

TEST(ModelidData, AResidualAboveTheBandSaysThePreparationWasWrong) {
  // Encoder-like position noise (1 mrad) and torque noise: with the bandwidth given 50 times too
  // high, the position filter passes the noise, differentiation amplifies it, and W carries
  // high-frequency content the torques do not: the fit must say so. With the estimated
  // bandwidth (the excitation ends at 0.75 Hz) it must not.
  const fs::path dir = test::test_folder();
  const Tx40Case tx40;
  Trajectory x = tx40.sampled(0.001, 12.0);
  std::mt19937_64 engine(5);
  std::normal_distribution<double> position_noise(0.0, 1e-3), torque_noise(0.0, 0.5);
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    for (int j = 0; j < 6; ++j) {
      x.q(s, j) += position_noise(engine);
      x.tau(s, j) += torque_noise(engine);
    }
  }
  write_log(dir / "noisy.csv", x.t, x.q, x.tau, "tau");
  const std::string fit = "fit --robot tx40 --method ols --data " + quoted(dir / "noisy.csv");
  const CliRun wide = modelid(fit + " --bandwidth 50");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.err.find("noisy.csv: above the 50 Hz excitation bandwidth the residual has"),
            std::string::npos)
      << wide.err;
  EXPECT_NE(wide.err.find("filtered too little"), std::string::npos) << wide.err;
  const CliRun estimated = modelid(fit);
  ASSERT_EQ(estimated.exit_code, 0) << estimated.err;
  EXPECT_EQ(estimated.err.find("excitation bandwidth the residual"), std::string::npos)
      << estimated.err;
}

TEST(ModelidData, AFileAboveTheRowLimitIsRefusedWithTheLimit) {
  const fs::path dir = test::test_folder();
  {
    std::ofstream out(dir / "long.csv");
    out << "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n";
    for (long s = 0; s <= 1000000; ++s) out << s << ",0,0,0,0,0,0,1,1,1,1,1,1\n";
  }
  const CliRun run = modelid("fit --robot tx40 --method ols --data " + quoted(dir / "long.csv"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err.rfind((dir / "long.csv").string() +
                              ":1000002: error: more than 1000000 samples, modelid's limit per "
                              "data file",
                          0),
            0u)
      << run.err;
}

TEST(ModelidData, PositionsBeyondTheLimitsAreWarnedAboutInFitAndPredict) {
  // Motor angles (gear ratio 32 on joint 2) given as joint angles: joint 2 of robots/tx40.yaml
  // is limited to [-2.18, 2.18] rad.
  const fs::path dir = test::test_folder();
  const Tx40Case tx40;
  const Trajectory x = tx40.sampled(0.01, 8.0);
  Eigen::MatrixXd q = x.q;
  q.col(1) *= 32.0;
  const double reach = q.col(1).cwiseAbs().maxCoeff();
  ASSERT_GT(reach, 2.18 * 1.01);
  write_log(dir / "motor.csv", x.t, q, x.tau, "tau");
  const std::string data = " --data " + quoted(dir / "motor.csv");
  const CliRun fit = modelid("fit --robot tx40 --method ols --raw" + data + " -o " +
                             quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const std::string expected = ": warning: " + (dir / "motor.csv").string() +
                               ": joint 2 ('J2') reaches q = ";
  EXPECT_NE(fit.err.find("modelid fit" + expected), std::string::npos) << fit.err;
  EXPECT_NE(fit.err.find("outside its limits [-2.18, 2.18] in the description: motor-side data "
                         "read as joint data (--motor-side)?"),
            std::string::npos)
      << fit.err;
  // The joints inside their limits are not named.
  EXPECT_EQ(fit.err.find("joint 1 ('J1') reaches q"), std::string::npos) << fit.err;
  const CliRun predict =
      modelid("predict --robot " + test::quoted_source("robots/tx40.yaml") + " --params " +
              quoted(dir / "est.json") + data);
  ASSERT_EQ(predict.exit_code, 0) << predict.err;
  EXPECT_NE(predict.err.find("modelid predict" + expected), std::string::npos) << predict.err;
}

TEST(ModelidData, ContradictoryOptionsAreUsageErrors) {
  const std::string data = " --data " + test::quoted_source("robots/data/kr150/excitation.csv");
  for (const std::string& options :
       {std::string("--periodic --raw"), std::string("--period 3"), std::string("--harmonics 4"),
        std::string("--periodic --cutoff 5"), std::string("--decimate 0"),
        std::string("--bandwidth -1")}) {
    const CliRun run = modelid("fit --robot kr150 --method ols " + options + data);
    EXPECT_EQ(run.exit_code, 2) << options << "\n" << run.err;
  }
}

}  // namespace
}  // namespace modelgen
