// What fit --method ml prints and writes of who decided the load and the drive unknowns
// (modelgen/ml/load_plausibility.hpp): a table per approach with --physical, the load's
// plausibility warnings always, and EST.json's "decided" block.
#pragma once

#include <nlohmann/json.hpp>

#include <ostream>
#include <vector>

#include "runtime/cli/reports/ml_report.hpp"

namespace modelgen::internal {

/// With --physical: per run, the load (mass, centre of gravity in mm, principal moments, its
/// distance from the payload link's frame against the arm's reach, its extent in the link's
/// region) and the drive unknowns, each with who decided it.
void print_ml_decided(std::ostream& out, const std::vector<MlRun>& runs, int payload_link);

/// The load's plausibility warnings of every run on `err`.
void warn_implausible_ml_load(std::ostream& err, const std::vector<MlRun>& runs);

/// EST.json's "decided" block of one run: {"load": {...}, "drives": [...]}.
nlohmann::json ml_decided_json(const MlRun& run);

}  // namespace modelgen::internal
