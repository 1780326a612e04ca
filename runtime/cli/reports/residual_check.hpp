// After a fit: is each joint's residual in the excitation band what the record's noise leaves
// there? Far above: the model misses something on that joint; far below: the fit explains
// noise (issue 31).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// The torques predicted with `beta` on every experiment as prepared (at its rate, before the
/// parallel decimation, whose filter keeps the band), each record's band from its positions
/// (band_of_positions; a record without one skips the check), and per joint the residual's energy
/// in the band against the noise floor there (residual_against_noise, its bounds at 0.05 % per
/// side). Averaged periods (--periodic: IDIM-WLS, ML-EIV and the other linear methods on them)
/// are judged on their harmonics in the band against the noise the periods' spread left there
/// (period_residual_against_noise). Writes one "modelid fit: warning:" line per joint outside the
/// bounds (above them only when the excess over the noise is also more than 1 % of the joint's
/// torque in the band, rms), naming the joint, the ratio, the likely causes and the options, and
/// returns their number. `whose` follows "the residual" in the message (e.g. " (of the IDIM-WLS
/// estimate)").
int warn_residual_against_noise(std::ostream& err, const IdentificationModel& model,
                                const Experiments& experiments, const Eigen::VectorXd& beta,
                                const std::string& whose = "");

/// What a residual warning judges and says beyond the numbers.
struct ResidualWording {
  std::string whose;  ///< follows "the residual", e.g. " (of the IDIM-WLS estimate)"
  /// Per joint, whether it is judged (empty: every joint): an ML fit leaves out the motors that
  /// do not move, and with them the joints they drive.
  std::vector<bool> judged;
  /// The ML route (--method ml): its own causes and options, and "values per unknown" counted
  /// with `unknowns` instead of the model's base parameters.
  bool drive_model = false;
  Eigen::Index unknowns = 0;
};

/// The same for averaged periods (--periodic) whose errors (measured minus modelled torque,
/// joint side, one N x dof matrix per experiment of `experiments`) a fit computed itself: the
/// ML route's torque errors, mapped to the joints by K^T (ml_residual_check.hpp). Nothing when
/// an experiment is not an averaged period.
int warn_period_residual_against_noise(std::ostream& err, const IdentificationModel& model,
                                       const Experiments& experiments,
                                       const std::vector<Eigen::MatrixXd>& errors,
                                       const ResidualWording& wording);

}  // namespace modelgen::internal
