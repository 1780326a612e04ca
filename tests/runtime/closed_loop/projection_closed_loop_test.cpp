// The projection method on a TX-40 simulated under a 1 kHz PID (as closed_loop_identification_
// test): moving one joint at a time, as Bona & Curatella did, with the Coulomb friction
// compensated as in their section 3.4, the projection keeps the moving joint's torque and the
// inertia and viscous friction it sees come out at the truth; moving all joints along the
// bundled design, it discards far more than the warning threshold (the torque at sums and
// products of the reference's frequencies), and the test prints how far PM and IDIM-WLS land
// from the truth.

#include "modelgen/closed_loop/projection_method.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

#include <Eigen/LU>
#include <Eigen/QR>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "modelgen/closed_loop/closed_loop_simulation.hpp"
#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/test_support.hpp"
#include "tests/support/tx40_truth.hpp"

namespace modelgen {
namespace {

constexpr double kTs = 1e-3;

// The bundled design's Fourier series (Swevers 2002 eq. 15) sampled at the controller's rate;
// only the joints in `moving` follow it, the others are held at its q0.
Eigen::MatrixXd design_reference(const std::vector<int>& moving) {
  const YAML::Node root = YAML::LoadFile(test::source_path("robots/data/tx40/design.yaml"));
  const double w = 2 * M_PI / root["period"].as<double>();
  const Eigen::Index samples = 10000;
  Eigen::MatrixXd qr(samples, 6);
  for (int j = 0; j < 6; ++j) {
    const YAML::Node joint = root["joints"][j];
    const bool moves = std::find(moving.begin(), moving.end(), j) != moving.end();
    for (Eigen::Index k = 0; k < samples; ++k) {
      const double t = static_cast<double>(k) * kTs;
      double q = joint["q0"].as<double>();
      for (std::size_t l = 0; moves && l < joint["a"].size(); ++l) {
        const double lwt = static_cast<double>(l + 1) * w * t;
        q +=
            joint["a"][l].as<double>() * std::sin(lwt) + joint["b"][l].as<double>() * std::cos(lwt);
      }
      qr(k, j) = q;
    }
  }
  return qr;
}

PidGains tx40_gains() {
  PidGains gains;
  gains.sample_time = kTs;
  gains.kp = (Eigen::VectorXd(6) << 18000, 18000, 3000, 400, 400, 200).finished();
  gains.ki = (Eigen::VectorXd(6) << 1.8e5, 1.8e5, 3e4, 4000, 4000, 2000).finished();
  gains.kd = (Eigen::VectorXd(6) << 260, 260, 40, 5, 5, 2.5).finished();
  return gains;
}

class ProjectionClosedLoopTest : public testing::Test {
 protected:
  void SetUp() override {
    model_ = internal::make_shipped_model("tx40");
    truth_ = test::tx40_true_base(model_->base_param_names());
    ASSERT_TRUE(truth_.allFinite());
  }

  // The robot `beta` under the PID along `qr`, with encoder quantisation and torque noise,
  // prepared as closed_loop_identification_test does (100 Hz position filter, decimation 10,
  // held torques paired).
  ProjectionRecord record(const Eigen::VectorXd& beta, const Eigen::MatrixXd& qr) const {
    PidController controller(tx40_gains());
    ClosedLoopOptions options;
    options.encoder_resolution = Eigen::VectorXd::Constant(6, 2 * M_PI / (1 << 17) / 32);
    options.tau_noise = Eigen::VectorXd::Constant(6, 0.2);
    options.seed = 11;
    const std::vector<double> values(beta.data(), beta.data() + beta.size());
    const ClosedLoopRun run = simulate_closed_loop(
        *model_, values, controller, qr, qr.row(0).transpose(), Eigen::VectorXd::Zero(6), options);
    Trajectory raw;
    raw.source = "simulated TX-40 under PID";
    raw.t = run.t;
    raw.q = run.q_measured;
    raw.tau = run.tau_recorded;
    raw.dq = raw.ddq = Eigen::MatrixXd::Zero(run.t.size(), 6);
    PreparationOptions preparation;
    preparation.cutoff_hz = 100;
    preparation.decimation = 10;
    preparation.torque_hold = true;
    const PreparedExperiment prepared = prepare_experiment(raw, model_->drive_chain(), preparation);
    ProjectionRecord out;
    out.prepared = prepared.data;
    out.decimation = prepared.decimation;
    out.torque_hold = true;
    out.qr = qr;
    out.first_row = std::lround((prepared.data.t[0] - run.t[0]) / kTs);
    return out;
  }

  double& parameter(Eigen::VectorXd& beta, const std::string& name) const {
    const auto& names = model_->base_param_names();
    const auto it = std::find(names.begin(), names.end(), name);
    EXPECT_NE(it, names.end()) << name;
    return beta[it - names.begin()];
  }

  std::unique_ptr<IdentificationModel> model_;
  Eigen::VectorXd truth_;
};

TEST_F(ProjectionClosedLoopTest, OneJointAtATimeKeepsItsTorque) {
  // Bona & Curatella compensate the Coulomb friction with separately identified values before
  // the projection (section 3.4): sign(dq) is no linear filter of the reference. Here the
  // simulated robot has none.
  Eigen::VectorXd beta = truth_;
  for (const char* name : {"Fc1", "Fc2", "Fc3", "Fc4", "Fc5", "Fc6", "Fcm6"})
    parameter(beta, name) = 0;
  const Eigen::MatrixXd qr = design_reference({0});
  const ProjectionRecord r = record(beta, qr);
  const ProjectedRecords stage1 = project_records(6, {r}, std::nullopt);
  std::cout << "[ one joint ] M " << stage1.lags << ", discarded per joint";
  for (int j = 0; j < 6; ++j) std::cout << " " << stage1.discarded[j];
  std::cout << ", all " << stage1.discarded_total << "\n";
  EXPECT_TRUE(stage1.decorrelated);
  // Joint 1's torque is linear in its reference but for the noise (measured 0.5 %); the held
  // joints' small torques carry dq1^2 (centrifugal), which no FIR makes: over all joints
  // (measured 2.0 %) still below the CLI's 3 % warning.
  EXPECT_LT(stage1.discarded[0], 0.02);
  EXPECT_LT(stage1.discarded_total, 0.03);
  // u^ at the raw rate, decimated as identify() decimates it, is the FIR's fit on those rows
  // (decimation is linear): the discarded fraction recomputed from it is the same, to the
  // rounding the 65 nearly dependent lags of M = 32 amplify (measured 5e-8 relative).
  const Eigen::MatrixXd u = decimate_interior(r.prepared.tau, r.decimation);
  const Eigen::MatrixXd u_hat = decimate_interior(stage1.projected[0], r.decimation);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR((u - u_hat).col(j).norm() / u.col(j).norm(), stage1.discarded[j],
                1e-6 * stage1.discarded[j])
        << j;
  }

  // What joint 1's motion identifies, the others held: the inertia about axis 1 at the held
  // posture, its viscous friction and its offset. Fitted here to u^_1 on the decimated rows,
  // against the truth: the inertia from the regressor at the held posture.
  const Trajectory& x = r.prepared;
  const Eigen::Index samples = x.t.size();
  Eigen::MatrixXd columns(samples, 3);
  columns.col(0) = x.ddq.col(0);
  columns.col(1) = x.dq.col(0);
  columns.col(2).setOnes();
  const Eigen::MatrixXd Phi = decimate_interior(columns, r.decimation);
  const Eigen::VectorXd y = decimate_interior(stage1.projected[0].col(0), r.decimation).col(0);
  const Eigen::VectorXd measured = decimate_interior(x.tau.col(0), r.decimation).col(0);
  const Eigen::VectorXd estimate = Phi.colPivHouseholderQr().solve(y);
  const Eigen::VectorXd plain = Phi.colPivHouseholderQr().solve(measured);
  const Eigen::VectorXd residual = measured - Phi * plain;
  const double sigma = std::sqrt(residual.squaredNorm() / double(Phi.rows() - 3));
  const Eigen::VectorXd sd = sigma * (Phi.transpose() * Phi).inverse().diagonal().cwiseSqrt();
  Eigen::VectorXd q = qr.row(0).transpose(), zero = Eigen::VectorXd::Zero(6), e1 = zero;
  e1[0] = 1;
  Eigen::MatrixXd W(6, beta.size()), W0(6, beta.size());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Wr(6, beta.size());
  model_->regressor(q.data(), zero.data(), e1.data(), Wr.data());
  W = Wr;
  model_->regressor(q.data(), zero.data(), zero.data(), Wr.data());
  W0 = Wr;
  const double inertia = (W.row(0) - W0.row(0)).dot(beta);
  const Eigen::Vector3d expected(inertia, parameter(beta, "Fv1"), parameter(beta, "OFF1"));
  std::cout << "[ one joint ] joint 1 from u^: inertia " << estimate[0] << " (truth " << inertia
            << "), Fv1 " << estimate[1] << " (" << expected[1] << "), offset " << estimate[2]
            << " (" << expected[2] << "); sd of the plain fit " << sd.transpose() << "; plain fit "
            << plain.transpose() << "\n";
  // Within 4 sd of the plain least-squares fit on the measured torque, as in
  // closed_loop_identification_test: these three columns lie in the span of the reference's
  // lags, so the fit to u^ equals the plain one (to rounding), and what separates both from
  // the truth (the inertia sits 3.0 sd off) is the preparation's (filter, decimation, held
  // torque pairing), not the projection's.
  EXPECT_LT((estimate - plain).norm(), 1e-3 * sd.minCoeff());
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(estimate[k] - expected[k]), 4 * sd[k]) << k;
  }
}

TEST_F(ProjectionClosedLoopTest, MultiJointRunDiscardsMoreThanTheWarning) {
  const ProjectionRecord r = record(truth_, design_reference({0, 1, 2, 3, 4, 5}));
  const auto start = std::chrono::steady_clock::now();
  const ProjectionIdentification pm = projection_method(*model_, {r});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  IdentifyOptions wls_options;
  wls_options.decimation = {r.decimation};
  const Identification wls = identify(*model_, {r.prepared}, Method::kWls, wls_options);
  auto distance = [&](const LeastSquaresResult& fit) {
    double worst = 0, sum = 0;
    for (Eigen::Index k = 0; k < truth_.size(); ++k) {
      const double d = std::abs(fit.value[k] - truth_[k]) / fit.std_dev[k];
      worst = std::max(worst, d);
      sum += d * d;
    }
    return std::make_pair(worst, std::sqrt(sum / double(truth_.size())));
  };
  const auto [pm_worst, pm_rms] = distance(pm.id.fit);
  const auto [wls_worst, wls_rms] = distance(wls.fit);
  std::cout << "[ all joints ] PM " << seconds << " s, M " << pm.stage1.lags << ", discarded "
            << pm.stage1.discarded_total << "; distance to the truth in sd (largest, rms): PM "
            << pm_worst << ", " << pm_rms << "; IDIM-WLS " << wls_worst << ", " << wls_rms
            << "; |beta - truth| PM " << (pm.id.fit.value - truth_).norm() << ", WLS "
            << (wls.fit.value - truth_).norm() << "\n";
  EXPECT_GT(pm.stage1.discarded_total, 0.03);
  EXPECT_TRUE(pm.id.fit.value.allFinite());
}

}  // namespace
}  // namespace modelgen
