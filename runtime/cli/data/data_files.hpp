// The experiments of a modelid run: every --data file read, brought to the joint side and
// prepared (modelgen/signal/prepare.hpp) as the data options say.
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/option_table.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/arguments.hpp"

namespace modelgen::internal {

/// Appends the data options of fit and predict (--motor-side, --periodic, --period,
/// --harmonics, --skip-periods, --raw, --bandwidth, --cutoff, --decimate, --torque-hold) and
/// their exclusions to a command's table (data_options.cpp).
void add_data_options(CommandSpec& spec);

/// The data options given in `args`, as command-line words in a fixed order (--motor-side,
/// --periodic, --period S, --harmonics H, --raw, --bandwidth HZ, --cutoff HZ, --decimate N,
/// --torque-hold H, --skip-periods K):
/// what fit writes into EST.json so that predict prepares data the same way.
std::vector<std::string> data_option_words(const CommandLine& args);

/// The command line of data options `words` (as data_option_words gives them); UsageError
/// naming `origin` (e.g. "EST.json") for a word that is not a data option.
CommandLine data_options_from_words(const std::vector<std::string>& words,
                                    const std::string& origin);

/// The preparation the data options ask for; UsageError for values out of range or options
/// that contradict each other (--periodic with --raw, --period without --periodic, ...).
PreparationOptions preparation_options(const CommandLine& args);

struct Experiments {
  std::vector<Trajectory> data;  ///< joint side, with dq and ddq
  std::vector<int> decimation;   ///< parallel decimation factor per experiment
  std::vector<Eigen::Index> reversal_guard;  ///< PreparedExperiment::reversal_guard
  std::vector<Eigen::VectorXd> reversal_speed;  ///< PreparedExperiment::reversal_speed
  /// Per experiment: the excitation bandwidth its position filter was planned for (Hz), 0
  /// when it had none (dq and ddq given, --raw, --periodic, --cutoff with --decimate).
  std::vector<double> bandwidth_hz;
  /// Per experiment: the joint-side torque noise variance per axis from the period average
  /// (N^2 m^2, dof values) with --periodic, empty otherwise (PreparedExperiment).
  std::vector<Eigen::VectorXd> tau_noise_variance;
  /// Per experiment: the noise of its prepared q, dq, ddq, tau with --periodic, else empty.
  std::vector<PeriodicNoise> noise;
  /// Per experiment: the file as read, before the preparation, when read_experiments was asked
  /// to keep it (the closed-loop fits need the reference qr and the first samples); else empty.
  std::vector<Trajectory> raw;
};

/// Reads each CSV file (read_trajectory_csv: t, q1..qn, tau1..taun or currents i1..in,
/// optionally dq, ddq) for `model` and prepares it (prepare_experiment with the model's drive
/// chain); prints one summary line per file to `report` and warnings to stderr. Shows
/// progress on stderr for many or large files. Throws DataError naming the file, line and
/// column of the first problem. With `keep_raw`, Experiments::raw holds each file as read (each
/// file is read once either way).
Experiments read_experiments(const std::vector<std::string>& paths,
                             const IdentificationModel& model, const PreparationOptions& options,
                             io::EffortColumns effort, std::ostream& report, bool keep_raw = false);

}  // namespace modelgen::internal
