// Reading and preparing the --data files of fit and predict, one experiment per file.

#include "runtime/cli/data/data_files.hpp"

#include <iostream>
#include <stdexcept>

#include "runtime/cli/common/progress.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

Experiments read_experiments(const std::vector<std::string>& paths,
                             const IdentificationModel& model, const PreparationOptions& options,
                             EffortColumns effort, std::ostream& report, bool keep_raw) {
  Experiments out;
  // The plan leaves enough rows per base parameter (plan_filtering's RowBudget).
  PreparationOptions with_unknowns = options;
  if (with_unknowns.unknowns == 0) with_unknowns.unknowns = model.num_base_params();
  Progress progress("reading data", static_cast<long long>(paths.size()));
  for (const std::string& path : paths) {
    progress.update(static_cast<long long>(out.data.size()), path);
    Trajectory raw = read_trajectory_csv(path, model.dof(), effort);
    if (keep_raw) out.raw.push_back(raw);
    PreparedExperiment prepared =
        prepare_experiment(std::move(raw), model.drive_chain(), with_unknowns);
    report << "  " << path << ": " << prepared.summary << "\n";
    if (!prepared.warning.empty()) std::cerr << prepared.warning << "\n";
    out.data.push_back(std::move(prepared.data));
    out.decimation.push_back(prepared.decimation);
    out.reversal_guard.push_back(prepared.reversal_guard);
    out.reversal_speed.push_back(std::move(prepared.reversal_speed));
    out.bandwidth_hz.push_back(prepared.bandwidth_hz);
    out.tau_noise_variance.push_back(std::move(prepared.tau_noise_variance));
    out.noise.push_back(std::move(prepared.noise));
  }
  progress.update(static_cast<long long>(out.data.size()));
  return out;
}

}  // namespace modelgen::internal
