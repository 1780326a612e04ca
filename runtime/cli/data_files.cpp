// Reading the --data files of fit and predict, one experiment per file.

#include "runtime/cli/data_files.hpp"

#include "runtime/cli/progress.hpp"

namespace modelgen::internal {

std::vector<Trajectory> read_experiments(const std::vector<std::string>& paths, int dof) {
  std::vector<Trajectory> data;
  Progress progress("reading data", static_cast<long long>(paths.size()));
  for (const std::string& path : paths) {
    progress.update(static_cast<long long>(data.size()), path);
    Trajectory x = read_trajectory_csv(path, dof);
    if (!x.has_velocity) differentiate(x);
    data.push_back(std::move(x));
  }
  progress.update(static_cast<long long>(data.size()));
  return data;
}

}  // namespace modelgen::internal
