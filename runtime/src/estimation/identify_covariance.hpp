// identify()'s standard deviations on correlated equation errors (issue 31).
#pragma once

#include <vector>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/model/identification_model.hpp"
#include "runtime/src/estimation/identify_equations.hpp"

namespace modelgen::detail {

/// Rebuilds the weighted rows of every group (IDIM: a joint of an experiment; PIM, `power`: an
/// experiment) and replaces fit's standard deviations by the sandwich covariance of
/// correlated_covariance.hpp, naming it in fit.covariance, if the residuals call for it:
/// periodic experiments with cut torques (`harmonics`, per experiment, -1 or H), or residuals
/// correlated from row to row (decimated or not). `decimated` in experiment order, one per
/// experiment with a factor > 1.
void correct_for_correlation(const IdentificationModel& model, const std::vector<Trajectory>& data,
                             const std::vector<int>& decimation,
                             const std::vector<DecimatedExperiment>& decimated,
                             const std::vector<int>& harmonics, bool power,
                             LeastSquaresResult& fit);

}  // namespace modelgen::detail
