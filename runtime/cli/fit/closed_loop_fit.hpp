// fit --method iv|didim: the closed-loop records of the --data files and the controller of
// --controller, identified by IDIM-IV or DIDIM (modelgen/closed_loop).
#pragma once

#include <ostream>
#include <string>

#include "modelgen/closed_loop/closed_loop_identification.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// Identifies `model` from the --data files of `args` (`experiments` holds them prepared and as
/// read, for the reference columns qr1..qrn and the first sample) under the
/// controller of --controller, leaving out the samples slower than `min_speed` (per joint,
/// empty: none; --min-speed). Prints one line per iteration to `log` and a summary to
/// `report`. Throws DataError for a file without qr columns; EstimationError from the method.
Identification fit_closed_loop(const CommandLine& args, const IdentificationModel& model,
                               const Experiments& experiments,
                               const std::vector<double>& min_speed, ClosedLoopMethod method,
                               std::ostream& report, std::ostream& log);

}  // namespace modelgen::internal
