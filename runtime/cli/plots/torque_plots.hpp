// --plot DIR of fit and predict: the measured and predicted torques as CSV, and one SVG per
// axis drawn by gnuplot when it is installed.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/data/trajectory.hpp"
#include "runtime/cli/reports/prediction_output.hpp"

namespace modelgen::internal {

/// Checks, without creating anything, that `dir` is a writable folder or could be created (its
/// nearest existing ancestor is a writable folder). Throws std::runtime_error "DIR: error: ..."
/// otherwise; called before any work so a bad DIR fails early, and a run that fails later
/// leaves no new folder behind (write_torque_plots creates it).
void check_plot_folder(const std::string& dir);

/// The full path of an executable `name` found on $PATH, or nothing; never throws.
std::optional<std::string> find_program(const std::string& name);

/// Writes DIR/torques.csv (prediction_csv without positions: experiment, t, tau, tau_pred,
/// error) and, when gnuplot is on PATH, DIR/plot.gp and DIR/axis<j>.svg (j = 1..dof): measured
/// and predicted torque against time above, their difference below, experiments end to end.
/// DIR/plot.gp is written in every case, so the plots can be drawn elsewhere
/// (`cd DIR && gnuplot plot.gp`). `title` heads every plot. Says on `out` what was written or
/// why the SVGs were skipped; a gnuplot failure is a warning on `warnings` with gnuplot's
/// message (the CSV stays), not an exception. Throws std::runtime_error when the CSV or the
/// script cannot be written.
void write_torque_plots(const std::string& dir, const std::string& title,
                        const std::vector<Trajectory>& data, const TorquePrediction& prediction,
                        std::ostream& out, std::ostream& warnings);

}  // namespace modelgen::internal
