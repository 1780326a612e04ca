// predict's and validate's torque comparison judged in the excitation band and against the
// record's noise floor (modelgen/signal/noise_floor.hpp): the band found, the figures, and
// which of them is the headline.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/noise_floor.hpp"

namespace modelgen::internal {

/// The comparison of every record in its band, or why there is none.
struct BandComparison {
  std::vector<BandEnergies> records;  ///< one per record; empty when `missing` says why
  NoiseFloor floor;                   ///< the records pooled
  std::string missing;                ///< why no band was found; empty when one was
};

/// For each record e: its band from the Fourier series in `trajectory_path` (when given; read
/// for `dof` joints, an error there throws InputError naming the file) or else from
/// motion[e]'s positions (q, t: uniform sampling), then the energies of tau[e] (measured) and
/// error[e] (measured minus predicted, samples x dof). A record whose band cannot be found (too
/// short, not uniformly sampled, positions that do not move) leaves `records` empty and says
/// why in `missing`.
BandComparison compare_in_band(const std::vector<Trajectory>& motion,
                               const std::vector<Eigen::MatrixXd>& tau,
                               const std::vector<Eigen::MatrixXd>& error,
                               const std::optional<std::string>& trajectory_path, int dof);

/// The relative error norm lines: full band ("relative error norm ||tau - tau_pred|| / ||tau||:
/// X"), in the band ("relative error norm in the band: X (rms E N m)"), the noise floor in the
/// band ("noise floor in the band: X, rms E N m (how it was estimated)") and the
/// band itself; the headline figure is marked "<- headline" and says why. Without a band, the
/// full-band line and the reason.
void print_relative_errors(std::ostream& out, double full_band, const BandComparison& comparison,
                           const std::vector<std::string>& sources);

}  // namespace modelgen::internal
