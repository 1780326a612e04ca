// fit --method ml-eiv: errors-in-variables maximum likelihood (Bona & Curatella eq. 13-16) on
// the averaged periods of --periodic data (modelgen/estimation/errors_in_variables.hpp).
#pragma once

#include <ostream>
#include <string>

#include "modelgen/estimation/identify.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// Before the data are read: UsageError without --periodic (the noise of q, dq, ddq comes from
/// the period average). fit's table refuses the options the method does not use.
void check_eiv_arguments(const CommandLine& args);

/// Fits `model` to the prepared periods of `experiments` (each with its PeriodicNoise) and
/// prints to `report` the noise standard deviations used per axis, the IDIM-WLS start, the
/// Ceres summary, iterations and cost. Returns the estimate in the form fit prints.
Identification fit_eiv(const IdentificationModel& model, const Experiments& experiments,
                       std::ostream& report);

}  // namespace modelgen::internal
