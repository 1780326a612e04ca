// fit --method pm: the projection method of Bona & Curatella (eq. 10-12) on the closed-loop
// records of the --data files (modelgen/closed_loop/projection_method.hpp).
#pragma once

#include <ostream>
#include <vector>

#include "modelgen/estimation/identify.hpp"
#include "modelgen/model/identification_model.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// Above this fraction of the torque norm discarded by the projection, fit --method pm warns.
inline constexpr double kDiscardedWarning = 0.03;

/// Identifies `model` by the projection method from the --data files of `args` (`experiments`
/// holds them prepared and as read, for the reference columns qr1..qrn), with
/// the FIR's lags from --fir-lags or the decorrelation test, leaving out the samples slower than
/// `min_speed` in stage 2. Prints the FIR's order, the test and the discarded fraction per joint
/// to `report`, and to `log` a warning when more than kDiscardedWarning of the torque is
/// discarded or the test fails. Throws UsageError for a bad --fir-lags; DataError for a file
/// without qr columns or whose prepared samples are not its own (resampled); EstimationError from
/// the method.
Identification fit_projection(const CommandLine& args, const IdentificationModel& model,
                              const Experiments& experiments, const std::vector<double>& min_speed,
                              std::ostream& report, std::ostream& log);

}  // namespace modelgen::internal
