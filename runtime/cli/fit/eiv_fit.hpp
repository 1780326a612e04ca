// fit --method ml-eiv: errors-in-variables maximum likelihood (Bona & Curatella eq. 13-16) on
// the averaged periods of --periodic data (modelgen/estimation/errors_in_variables.hpp).
#pragma once

#include <ostream>
#include <string>

#include "modelgen/estimation/identify.hpp"
#include "modelgen/signal/noise_coupling.hpp"
#include "runtime/cli/common/arguments.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// Before the data are read: UsageError without --periodic (the noise of q, dq, ddq comes from
/// the period average). fit's table refuses the options the method does not use.
void check_eiv_arguments(const CommandLine& args);

/// Fits `model` to the prepared periods of `experiments` (each with its PeriodicNoise) and
/// prints to `report` the noise standard deviations used per axis, the IDIM-WLS start, the
/// Ceres summary, iterations and cost. Returns the estimate in the form fit prints.
/// Prints the q-tau error coupling of each record (noise_coupling) and refuses a closed-loop
/// record: one that carries the reference columns qr1..qrn (experiments.raw,
/// closed_loop_refusal), or one whose errors of q and tau are coupled on a joint
/// (noise_coupled, coupling_refusal): its averaged period is not the errors-in-variables
/// setting of eq. 13-16. Warns on `log` when the residual standard deviation is
/// above kEivResidualStdLimit: the averaged period then carries errors its noise model does
/// not describe (a closed loop without reference columns does this) and the standard
/// deviations are too small by about that factor.
Identification fit_eiv(const IdentificationModel& model, const Experiments& experiments,
                       std::ostream& report, std::ostream& log);

/// s = 1 when eq. 16's noise model is right; an open-loop averaged period stays within
/// 1 +- a few percent (errors_in_variables_test), the COMAU closed loop gives 2.9.
constexpr double kEivResidualStdLimit = 1.5;

/// The reason ML-EIV refuses the closed-loop record `source` (what fit_eiv throws).
std::string closed_loop_refusal(const std::string& source);

/// The coupling test's bounds (modelgen/signal/noise_coupling.hpp): a joint whose errors of q
/// and tau are dependent beyond z = kCouplingZ (one-sided p of 3e-7 per joint) with a
/// correlation of at least kCouplingCorrelation makes fit_eiv refuse the record.
constexpr double kCouplingZ = 5.0;
constexpr double kCouplingCorrelation = 0.1;

/// Whether `joint`'s errors of q and tau are coupled beyond both bounds (inline: the tests
/// check the rule on library-prepared records without the command's objects).
inline bool noise_coupled(const NoiseCoupling& coupling, Eigen::Index joint) {
  return coupling.z[joint] > kCouplingZ && coupling.correlation[joint] >= kCouplingCorrelation;
}

/// The reason ML-EIV refuses the record `source` whose errors of q and tau are coupled (what
/// fit_eiv throws): the joints, their correlations and z, eq. 16's assumption, what to use.
std::string coupling_refusal(const std::string& source, const NoiseCoupling& coupling);

}  // namespace modelgen::internal
