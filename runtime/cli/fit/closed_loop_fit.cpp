// The records of fit --method iv|didim: prepared rows located in the raw samples, the
// reference and start state from the raw file.

#include "runtime/cli/fit/closed_loop_fit.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "modelgen/io/experiment/controller_file.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

Identification fit_closed_loop(const CommandLine& args, const IdentificationModel& model,
                               const Experiments& experiments,
                               const std::vector<double>& min_speed, ClosedLoopMethod method,
                               std::ostream& report, std::ostream& log) {
  const char* name = method == ClosedLoopMethod::kIv ? "IDIM-IV" : "DIDIM";
  // --controller given, no --motor-side or --periodic: checked before the data were read.
  std::vector<std::string> warnings;
  const PidGains gains = read_controller(args.one("--controller"), model.dof(), &warnings);
  for (const std::string& warning : warnings) std::cerr << warning << "\n";
  const std::vector<std::string>& paths = args.all("--data");
  std::vector<ClosedLoopRecord> records;
  for (std::size_t e = 0; e < paths.size(); ++e) {
    const Trajectory& raw = experiments.raw[e];  // read with the preparation, not again
    if (raw.qr.size() == 0) {
      throw DataError(paths[e] + ": error: " + name + " needs the reference positions of the "
                      "record, columns qr1..qr" + std::to_string(model.dof()) +
                      " (modelid simulate --controller writes them)");
    }
    ClosedLoopRecord record;
    record.prepared = experiments.data[e];
    record.decimation = experiments.decimation[e];
    record.reversal_guard = experiments.reversal_guard[e];
    record.torque_hold = args.has("--torque-hold") && args.one("--torque-hold") == "zoh";
    record.qr = raw.qr;
    record.t0 = raw.t[0];
    record.first_row = std::lround((record.prepared.t[0] - raw.t[0]) / gains.sample_time);
    record.q0 = raw.q.row(0).transpose();
    // The start velocity from the reference: the measured positions' differences are noisy.
    record.dq0 = (raw.qr.row(1) - raw.qr.row(0)).transpose() / gains.sample_time;
    records.push_back(std::move(record));
  }
  ClosedLoopFitOptions options;
  if (!min_speed.empty()) {
    options.min_speed = Eigen::Map<const Eigen::VectorXd>(min_speed.data(),
                                                           static_cast<Eigen::Index>(min_speed.size()));
  }
  options.on_iteration = [&log, name](int iteration, double move) {
    log << "modelid fit: " << name << " iteration " << iteration << ": largest change "
        << fixed(move, 0, 3) << " standard deviations\n";
  };
  const auto start = std::chrono::steady_clock::now();
  ClosedLoopIdentification result = identify_closed_loop(model, method, gains, records, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report << "  " << name << " from IDIM-WLS: " << result.iterations << " iteration(s), "
         << (result.converged ? "converged" : "NOT converged") << ", " << fixed(seconds, 0, 3)
         << " s; each simulates the records under the controller of "
         << args.one("--controller") << "\n";
  if (!result.converged) {
    log << "modelid: warning: " << name << " did not converge ("
        << (result.stop_reason.empty() ? std::to_string(options.max_iterations) + " iterations"
                                       : result.stop_reason)
        << "; last change "
        << (result.moves.empty() ? std::string("none") : fixed(result.moves.back(), 0, 3))
        << " standard deviations): the estimate is the last iterate\n";
  }
  return std::move(result.id);
}

}  // namespace modelgen::internal
