// The experiments of a modelid run: every --data file read, checked and completed with
// velocities and accelerations.
#pragma once

#include <string>
#include <vector>

#include "modelgen/data.hpp"

namespace modelgen::internal {

/// Reads each CSV file (read_trajectory_csv: t, q1..qn, tau1..taun, optionally dq, ddq) for a
/// robot with `dof` joints; files without dq/ddq get them from central differences (their
/// first and last samples are dropped). Shows progress on stderr for many or large files.
/// Throws DataError naming the file, line and column of the first problem.
std::vector<Trajectory> read_experiments(const std::vector<std::string>& paths, int dof);

}  // namespace modelgen::internal
