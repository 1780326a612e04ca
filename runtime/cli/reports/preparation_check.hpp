// After a fit: does the residual say the data were prepared wrongly? (a position filter far
// too wide for the excitation, so that W carries noise the torques do not).
#pragma once

#include <ostream>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// Above this ratio of the residual's power to the measured torques' power, both above the
/// excitation bandwidth, the preparation is called wrong (see warn_residual_outside_band).
inline constexpr double kOutOfBandExcess = 2.0;

/// For each experiment of the non-periodic route with a position filter (bandwidth_hz > 0):
/// the torques predicted with `beta`, compared after the parallel decimation as the fit
/// compares them, and the ratio of the residual's power above the experiment's bandwidth to
/// the measured torques' power there. Above the excitation band the measured torques hold
/// only noise (and what the model leaves out), and a regressor made from well-filtered
/// positions has almost nothing there, so the residual's power above the band is about the
/// torques'. Well above it (kOutOfBandExcess), the regressor brings content of its own:
/// differentiated position noise, a filter far above the excitation, whose errors in the
/// variables bias the estimate. Writes one "modelid fit: warning:" line per such experiment
/// to `err` and returns their number.
int warn_residual_outside_band(std::ostream& err, const IdentificationModel& model,
                               const Experiments& experiments, const Eigen::VectorXd& beta);

}  // namespace modelgen::internal
