// modelid validate: the identified model under the robot's controller along a validation
// record's reference (Bona & Curatella section 3.5), compared with what the robot did: the
// position error in degrees and the torque error in N m per joint, and the relative error in
// the excitation band against the record's own noise floor there.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/closed_loop/closed_loop_simulation.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/experiment/controller_file.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/io/json_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "modelgen/model/number_text.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/plots/torque_plots.hpp"
#include "runtime/cli/reports/noise_floor_report.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / static_cast<double>(v.size())); }

}  // namespace

int run_validate(const CommandLine& args) {
  const ModelSource source = load_model_source(args.one("--robot"), args);
  const IdentificationModel& model = *source.model;
  const int n = model.dof();
  const JsonDocument estimate = read_json_document(args.one("--params"));  // read once
  check_estimate_model(estimate, model);
  const Eigen::VectorXd beta = read_base_parameters(estimate, model);
  std::vector<std::string> warnings;
  PidController controller(read_controller(args.one("--controller"), n, &warnings));
  for (const std::string& warning : warnings) std::cerr << warning << "\n";
  const double ts = controller.gains().sample_time;
  if (args.has("--plot")) check_plot_folder(args.one("--plot"));
  const std::string& path = args.one("--data");
  const Trajectory record = read_trajectory_csv(path, n);
  if (record.measured != Measured::kTorque) {
    throw DataError(path + ": error: validate compares joint torques: the record needs columns "
                    "tau1..tau" + std::to_string(n) + " (motor currents are not converted here)");
  }
  if (record.qr.size() == 0) {
    throw DataError(path + ": error: validate simulates the controller along the record's "
                    "reference: it needs columns qr1..qr" + std::to_string(n));
  }
  for (Eigen::Index k = 1; k < record.t.size(); ++k) {
    if (std::abs(record.t[k] - record.t[0] - ts * static_cast<double>(k)) > 0.01 * ts) {
      throw DataError(path + ": error: sample " + std::to_string(k + 1) + " (t = " +
                      shortest_text(record.t[k]) + " s) is not on the controller's clock of " +
                      shortest_text(ts) + " s: validate replays the controller sample by sample");
    }
  }
  const std::vector<double> values(beta.data(), beta.data() + beta.size());
  ClosedLoopRun run;
  try {
    run = simulate_closed_loop(model, values, controller, record.qr, record.q.row(0).transpose(),
                               (record.qr.row(1) - record.qr.row(0)).transpose() / ts,
                               ClosedLoopOptions{}, record.t[0]);
  } catch (const std::domain_error& e) {
    throw std::runtime_error(args.one("--params") + ": error: the estimate cannot be simulated "
                             "under this controller: " + e.what());
  }
  // The record's own floor (issue 31): its torque above the reference's band, and the noise in
  // the band. The reference is the excitation without the encoder's noise.
  Trajectory reference = record;
  reference.q = record.qr;
  const std::optional<std::string> trajectory =
      args.has("--trajectory") ? std::optional<std::string>(args.one("--trajectory"))
                               : std::nullopt;
  const BandComparison band =
      compare_in_band({reference}, {record.tau}, {record.tau - run.tau_command}, trajectory, n);
  const Eigen::MatrixXd position_error =
      (record.q - run.q) * (180.0 / std::numbers::pi);  // degrees
  const Eigen::MatrixXd torque_error = record.tau - run.tau_command;
  std::cout << "modelid validate: " << model.name() << " with " << args.one("--params")
            << " under " << args.one("--controller") << " along " << path << " ("
            << record.t.size() << " samples, " << shortest_text(record.t[record.t.size() - 1] - record.t[0])
            << " s)\n"
            << "  joint   position error (deg)   torque error (N m)   torque (N m)\n"
            << "              rms        max        rms        max        rms\n";
  for (int j = 0; j < n; ++j) {
    std::cout << "  " << pad(std::to_string(j + 1), 5) << " " << fixed(rms(position_error.col(j)), 10, 4)
              << " " << fixed(position_error.col(j).cwiseAbs().maxCoeff(), 10, 4) << " "
              << fixed(rms(torque_error.col(j)), 10, 4) << " "
              << fixed(torque_error.col(j).cwiseAbs().maxCoeff(), 10, 4) << " "
              << fixed(rms(record.tau.col(j)), 10, 4) << "\n";
  }
  const double relative = torque_error.norm() / record.tau.norm();
  print_relative_errors(std::cout, relative, band, {path});
  if (args.has("--plot")) {
    const std::string dir = args.one("--plot");
    TorquePrediction prediction;
    prediction.tau_pred = {run.tau_command};
    prediction.error = {torque_error};
    prediction.rms_torque = (record.tau.colwise().squaredNorm() / static_cast<double>(record.t.size()))
                                .cwiseSqrt()
                                .transpose();
    prediction.rms_error = (torque_error.colwise().squaredNorm() / static_cast<double>(record.t.size()))
                               .cwiseSqrt()
                               .transpose();
    prediction.rel_error_norm = relative;
    prediction.rel_error_norm_per_experiment = {relative};
    prediction.samples = record.t.size();
    write_torque_plots(dir, model.name() + " simulated under the controller", {record},
                       prediction, std::cout, std::cerr);
    // Written beside its destination and renamed: never a half-written file.
    const std::filesystem::path destination = std::filesystem::path(dir) / "positions.csv";
    const std::filesystem::path temporary = destination.string() + ".tmp-modelid";
    std::ofstream out(temporary);
    out << "t";
    for (const char* prefix : {"q", "q_sim", "error_deg"}) {
      for (int j = 1; j <= n; ++j) out << "," << prefix << j;
    }
    out << "\n";
    for (Eigen::Index k = 0; k < record.t.size(); ++k) {
      out << shortest_text(record.t[k]);
      for (const Eigen::MatrixXd* m : {&record.q, static_cast<const Eigen::MatrixXd*>(&run.q), &position_error}) {
        for (int j = 0; j < n; ++j) out << "," << shortest_text((*m)(k, j));
      }
      out << "\n";
    }
    out.close();
    std::error_code renamed;
    if (out) std::filesystem::rename(temporary, destination, renamed);
    if (!out || renamed) {
      std::filesystem::remove(temporary, renamed);
      throw std::runtime_error(destination.string() + ": error: cannot write the file");
    }
    std::cout << "  positions written to " << (std::filesystem::path(dir) / "positions.csv").string()
              << "\n";
  }
  return 0;
}

}  // namespace modelgen::internal
