// The decided-by table, plausibility warnings and EST.json block of ml_decided_report.hpp.

#include "runtime/cli/reports/ml_decided_report.hpp"

#include <cmath>
#include <string>

#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

std::string triple(const std::array<double, 3>& v, double scale) {
  if (!std::isfinite(v[0])) return "not identifiable";
  return fixed(v[0] * scale, 0, 4) + ", " + fixed(v[1] * scale, 0, 4) + ", " +
         fixed(v[2] * scale, 0, 4);
}

void row(std::ostream& out, const std::string& label, const std::string& value, MlDecidedBy by) {
  out << "    " << pad(label, 24) << pad(value, 30) << ml_decided_by_name(by) << "\n";
}

void print_run(std::ostream& out, const MlRun& run, int payload_link, const std::string& name) {
  out << "  " << name << "who decided the estimate (data; bound: held by a constraint of "
      << "--physical; undetermined: the data leave it free, no number):\n";
  if (run.load_summary) {
    const MlLoadSummary& load = *run.load_summary;
    row(out, "load mass (kg)",
        std::isfinite(load.mass) ? fixed(load.mass, 0, 6) : std::string("not identifiable"),
        load.mass_by);
    row(out, "load c (mm)", triple(load.com, 1e3), load.com_by);
    row(out, "load moments (kg m^2)", triple(load.principal_moments, 1), load.moments_by);
    if (std::isfinite(load.com_distance)) {
      out << "    the centre of gravity is " << fixed(load.com_distance, 0, 3) << " m from link "
          << payload_link << "'s frame (the arm's reach: " << fixed(load.reach, 0, 3) << " m)";
      if (load.region_extent) {
        out << "; extent in its region" << (load.region_guessed ? " (a guess)" : "") << " "
            << fixed(*load.region_extent, 0, 3) << " (<= 1 inside)";
      }
      out << "\n";
    }
  }
  for (const MlDriveSummary& drive : run.drives) {
    row(out, drive.name,
        std::isfinite(drive.value) ? fixed(drive.value, 0, 6) + " +- " + fixed(drive.std_dev, 0, 2)
                                   : std::string("not identifiable"),
        drive.by);
  }
}

}  // namespace

void print_ml_decided(std::ostream& out, const std::vector<MlRun>& runs, int payload_link) {
  for (const MlRun& run : runs) {
    if (!run.physical) continue;
    print_run(out, run, payload_link,
              runs.size() > 1 ? "approach " + std::to_string(run.approach) + ": " : "");
  }
}

void warn_implausible_ml_load(std::ostream& err, const std::vector<MlRun>& runs) {
  for (const MlRun& run : runs) {
    if (!run.load_summary) continue;
    for (const std::string& warning : run.load_summary->warnings) {
      err << "modelid: warning: "
          << (runs.size() > 1 ? "approach " + std::to_string(run.approach) + ": " : "") << warning
          << "\n";
    }
  }
}

nlohmann::json ml_decided_json(const MlRun& run) {
  nlohmann::json out;
  if (run.load_summary) {
    const MlLoadSummary& load = *run.load_summary;
    nlohmann::json json = {{"mass", number(load.mass)},
                           {"com", {number(load.com[0]), number(load.com[1]), number(load.com[2])}},
                           {"principal_moments",
                            {number(load.principal_moments[0]), number(load.principal_moments[1]),
                             number(load.principal_moments[2])}},
                           {"decided_by",
                            {{"mass", ml_decided_by_name(load.mass_by)},
                             {"com", ml_decided_by_name(load.com_by)},
                             {"principal_moments", ml_decided_by_name(load.moments_by)}}},
                           {"com_distance", number(load.com_distance)},
                           {"reach", load.reach},
                           {"warnings", load.warnings}};
    if (load.region_extent) {
      json["region_extent"] = number(*load.region_extent);
      json["region_guessed"] = load.region_guessed;
    }
    out["load"] = json;
  }
  out["drives"] = nlohmann::json::array();
  for (const MlDriveSummary& drive : run.drives) {
    out["drives"].push_back({{"name", drive.name},
                             {"value", number(drive.value)},
                             {"std", number(drive.std_dev)},
                             {"decided_by", ml_decided_by_name(drive.by)}});
  }
  return out;
}

}  // namespace modelgen::internal
