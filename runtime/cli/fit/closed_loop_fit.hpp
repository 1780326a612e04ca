// fit --method iv|didim: the closed-loop records of the --data files and the controller of
// --controller, identified by IDIM-IV or DIDIM (modelgen/closed_loop).
#pragma once

#include <ostream>
#include <string>

#include "modelgen/closed_loop/closed_loop_identification.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// "iv" -> kIv, "didim" -> kDidim; other texts are not closed-loop methods (nullopt).
std::optional<ClosedLoopMethod> closed_loop_method(const std::string& text);

/// "IDIM-IV" or "DIDIM".
const char* closed_loop_method_name(ClosedLoopMethod method);

/// Identifies `model` from the --data files of `args` (each read again for its reference
/// columns qr1..qrn and its first sample; `experiments` are the same files prepared) under the
/// controller of --controller, leaving out the samples slower than `min_speed` (per joint,
/// empty: none; --min-speed). Prints one line per iteration to `log` and a summary to
/// `report`. Throws UsageError without --controller, with --motor-side or --periodic; DataError
/// for a file without qr columns; EstimationError from the method.
Identification fit_closed_loop(const CommandLine& args, const IdentificationModel& model,
                               const Experiments& experiments,
                               const std::vector<double>& min_speed, ClosedLoopMethod method,
                               std::ostream& report, std::ostream& log);

}  // namespace modelgen::internal
