// Text and JSON reports of the maximum-likelihood approaches.

#include "runtime/cli/reports/ml_report.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/identifiability.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/reports/estimate_warnings.hpp"
#include "runtime/cli/reports/ml_decided_report.hpp"

namespace modelgen::internal {

namespace {

constexpr int kCell = 24;  // width of one approach's column in the comparison

nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json load_json(const LoadParameters& load) {
  return {{"m", number(load.mass)},
          {"c", {number(load.com[0]), number(load.com[1]), number(load.com[2])}},
          {"I",
           {{"xx", number(load.inertia[0])},
            {"yy", number(load.inertia[1])},
            {"zz", number(load.inertia[2])},
            {"xy", number(load.inertia[3])},
            {"xz", number(load.inertia[4])},
            {"yz", number(load.inertia[5])}}}};
}

// A printed row: the unknown's name, unit, scale to that unit.
struct Row {
  std::string name, label, unit;
  double scale = 1;
};

// The load rows in Swevers eq. 3 order, the centre of gravity in mm.
std::vector<Row> load_rows() {
  const char* labels[kLoadParams] = {"m",   "cx",  "cy",  "cz",  "Ixx",
                                     "Iyy", "Izz", "Ixy", "Ixz", "Iyz"};
  std::vector<Row> rows;
  for (int k = 0; k < kLoadParams; ++k) {
    const bool com = k >= 1 && k <= 3;
    rows.push_back({load_param_names()[k], labels[k], k == 0 ? "kg" : (com ? "mm" : "kg m^2"),
                    com ? 1e3 : 1.0});
  }
  return rows;
}

// The estimate and standard deviation of `name` in `fit`; false when it is not an unknown.
bool find(const MlFitResult& fit, const std::string& name, double& value, double& sd) {
  const auto at = std::find(fit.names.begin(), fit.names.end(), name);
  if (at == fit.names.end()) return false;
  const auto u = at - fit.names.begin();
  if (name.compare(0, 5, "load_") == 0) {
    const auto k = std::find(load_param_names().begin(), load_param_names().end(), name) -
                   load_param_names().begin();
    value = fit.load.to_vector()[static_cast<size_t>(k)];
    sd = fit.load_std_dev.to_vector()[static_cast<size_t>(k)];
  } else {
    value = fit.value[u];
    sd = fit.std_dev[u];
  }
  return true;
}

// The value of load parameter `name` when the load is in `fit` but `name` is not an unknown:
// known a priori.
bool known_load(const MlFitResult& fit, const std::string& name, double& value) {
  const auto& names = load_param_names();
  const auto at = std::find(names.begin(), names.end(), name);
  if (!fit.has_load || at == names.end()) return false;
  value = fit.load.to_vector()[static_cast<size_t>(at - names.begin())];
  return true;
}

std::string estimate_text(double value, double sd, double scale) {
  if (!std::isfinite(value)) return "not identifiable";
  return fixed(value * scale, 0, 6) + " +- " + fixed(sd * scale, 0, 2);
}

// The unknowns that are not load parameters, in the order they first appear in `runs`.
std::vector<std::string> drive_names(const std::vector<MlRun>& runs) {
  std::vector<std::string> names;
  for (const MlRun& run : runs) {
    for (const std::string& name : run.fit.names) {
      if (name.compare(0, 5, "load_") != 0 &&
          std::find(names.begin(), names.end(), name) == names.end()) {
        names.push_back(name);
      }
    }
  }
  return names;
}

void print_rms(std::ostream& out, const Eigen::VectorXd& rms) {
  out << "  rms torque error per fitted motor (N m):";
  for (Eigen::Index j = 0; j < rms.size(); ++j) {
    if (rms[j] > 0) out << " " << j + 1 << ": " << fixed(rms[j], 0, 4);
  }
  out << "\n";
}

}  // namespace

void print_ml_run(std::ostream& out, const MlRun& run, int payload_link, const MlTruth& truth) {
  const MlFitResult& fit = run.fit;
  if (!run.summary.empty()) out << "  " << run.summary << "\n";
  const Identifiability& id = fit.identifiability;
  out << "  identifiability: rank " << id.rank << " of " << fit.names.size()
      << " unknowns, condition number " << fixed(id.condition_number, 0, 4) << "\n";
  for (const std::string& direction : id.directions) out << "    " << direction << "\n";
  for (const std::string& note : fit.notes) out << "  note: " << note << "\n";
  const auto print_row = [&](const Row& row) {
    double value = 0, sd = 0;
    std::string text;
    if (find(fit, row.name, value, sd)) {
      text = estimate_text(value, sd, row.scale);
    } else if (known_load(fit, row.name, value)) {
      text = fixed(value * row.scale, 0, 6) + " (known)";
    } else {
      return;
    }
    std::string line = "    " + pad(row.label, 5) + " " + pad(text, kCell) + " " + row.unit;
    const auto exact = truth.find(row.name);
    if (exact != truth.end() && std::isfinite(value)) {
      line += "  (exact " + fixed(exact->second * row.scale, 0, 6) + ", error " +
              fixed((value - exact->second) * row.scale, 0, 3) + ")";
    }
    line.erase(line.find_last_not_of(' ') + 1);
    out << line << "\n";
  };
  if (fit.has_load) {
    out << "  load on link " << payload_link
        << " (centre of gravity in mm, inertia about it in kg m^2):\n";
    for (const Row& row : load_rows()) print_row(row);
    for (const std::string& warning : fit.load_warnings) out << "  warning: " << warning << "\n";
  }
  out << "  drive parameters:\n";
  for (const std::string& name : drive_names({run})) print_row({name, name, "", 1});
  print_rms(out, fit.rms_error);
  out << "  " << fit.iterations << " Levenberg-Marquardt iteration(s), " << fixed(run.seconds, 0, 3)
      << " s\n";
}

void print_ml_comparison(std::ostream& out, const std::vector<MlRun>& runs, int payload_link,
                         const MlTruth& truth) {
  const bool exact = !truth.empty();
  // Rows are built whole so that trailing padding can go.
  const auto emit = [&out](std::string line) {
    line.erase(line.find_last_not_of(' ') + 1);
    out << line << "\n";
  };
  const auto header = [&](bool exact_column) {
    std::string line = "  " + pad("", 16) + (exact ? pad(exact_column ? "exact" : "", 12) : "");
    for (const MlRun& run : runs) line += pad("approach " + std::to_string(run.approach), kCell);
    emit(line);
  };
  std::vector<Row> rows;
  if (std::any_of(runs.begin(), runs.end(), [](const MlRun& r) { return r.fit.has_load; })) {
    rows = load_rows();
  }
  for (const std::string& name : drive_names(runs)) rows.push_back({name, name, "", 1});
  // Table 2: estimates +- standard deviation ("-" where the approach does not estimate it).
  out << "  estimates +- standard deviation (load on link " << payload_link
      << ": centre of gravity in mm, inertia about it in kg m^2):\n";
  header(true);
  for (const Row& row : rows) {
    const std::string label = row.label + (row.unit.empty() ? "" : " (" + row.unit + ")");
    std::string line = "  " + pad(label, 16);
    const auto t = truth.find(row.name);
    if (exact) line += pad(t != truth.end() ? fixed(t->second * row.scale, 0, 6) : "", 12);
    for (const MlRun& run : runs) {
      double value = 0, sd = 0;
      line += pad(find(run.fit, row.name, value, sd)     ? estimate_text(value, sd, row.scale)
                  : known_load(run.fit, row.name, value) ? "known"
                                                         : "-",
                  kCell);
    }
    emit(line);
  }
  if (exact) {
    out << "  errors (estimate - exact):\n";
    header(false);
    for (const Row& row : rows) {
      const auto t = truth.find(row.name);
      if (t == truth.end()) continue;
      std::string line =
          "  " + pad(row.label + (row.unit.empty() ? "" : " (" + row.unit + ")"), 16) + pad("", 12);
      for (const MlRun& run : runs) {
        double value = 0, sd = 0;
        const bool has = find(run.fit, row.name, value, sd) && std::isfinite(value);
        line += pad(has ? fixed((value - t->second) * row.scale, 0, 3) : "-", kCell);
      }
      emit(line);
    }
  }
  // Table 3: rms torque errors per fitted motor.
  out << "  rms torque errors (N m):\n";
  header(false);
  const Eigen::Index dof = runs.empty() ? 0 : runs.front().fit.rms_error.size();
  for (Eigen::Index j = 0; j < dof; ++j) {
    if (!std::any_of(runs.begin(), runs.end(),
                     [j](const MlRun& r) { return r.fit.rms_error[j] > 0; })) {
      continue;
    }
    std::string line =
        "  " + pad("motor " + std::to_string(j + 1), 16) + (exact ? pad("", 12) : "");
    for (const MlRun& run : runs) line += pad(fixed(run.fit.rms_error[j], 0, 4), kCell);
    emit(line);
  }
  const auto summary_row = [&](const std::string& label, auto cell) {
    std::string line = "  " + pad(label, 16) + (exact ? pad("", 12) : "");
    for (const MlRun& run : runs) line += pad(cell(run), kCell);
    emit(line);
  };
  summary_row("rank", [](const MlRun& run) {
    return std::to_string(run.fit.identifiability.rank) + " of " +
           std::to_string(run.fit.names.size());
  });
  summary_row("LM iterations", [](const MlRun& run) { return std::to_string(run.fit.iterations); });
  summary_row("time (s)", [](const MlRun& run) { return fixed(run.seconds, 0, 3); });
  for (const MlRun& run : runs) {
    if (!run.summary.empty()) out << "  approach " << run.approach << ": " << run.summary << "\n";
    for (const std::string& direction : run.fit.identifiability.directions) {
      out << "  approach " << run.approach << ": " << direction << "\n";
    }
    for (const std::string& note : run.fit.notes) {
      out << "  approach " << run.approach << ": note: " << note << "\n";
    }
    for (const std::string& warning : run.fit.load_warnings) {
      out << "  approach " << run.approach << ": warning: " << warning << "\n";
    }
  }
}

void warn_implausible_ml_estimates(std::ostream& err, const MlRun& run, bool name_approach) {
  const MlFitResult& fit = run.fit;
  Eigen::VectorXd value(static_cast<Eigen::Index>(fit.names.size()));
  Eigen::VectorXd sd(value.size());
  for (std::size_t u = 0; u < fit.names.size(); ++u) {
    // Load unknowns are read from the load (find() above), as they are printed.
    find(fit, fit.names[u], value[static_cast<Eigen::Index>(u)], sd[static_cast<Eigen::Index>(u)]);
  }
  warn_implausible_estimates(
      err, fit.names, value, sd,
      name_approach ? "approach " + std::to_string(run.approach) + ": " : std::string());
}

void print_ml_physical(std::ostream& out, const std::vector<MlRun>& runs) {
  for (const MlRun& run : runs) {
    if (!run.physical) continue;
    const MlPhysicalRun& p = *run.physical;
    const std::string name = runs.size() > 1 ? "approach " + std::to_string(run.approach) + ": " : "";
    if (p.result.unconstrained_consistent) {
      out << "  " << name << "physically consistent without constraints (--physical changed nothing)\n";
      continue;
    }
    out << "  " << name << "physically consistent estimate (--physical, prior weight "
        << fixed(p.prior_weight, 0, 3) << "); the unconstrained one had:";
    for (const std::string& v : p.violations) out << " [" << v << "]";
    const double unconstrained = p.result.unconstrained_sum_of_squares;
    out << "\n    cost of consistency: " << fixed(p.result.cost_increase, 0, 4)
        << " (weighted sum of squares " << fixed(unconstrained, 0, 6) << " -> "
        << fixed(unconstrained + p.result.cost_increase, 0, 6) << ", "
        << fixed(unconstrained > 0 ? 100 * p.result.cost_increase / unconstrained : 0.0, 0, 3)
        << " %), " << fixed(p.seconds, 0, 3) << " s\n";
    if (p.result.cost_increase < 0) {
      out << "    (below zero: this approach's estimate does not minimise eq. 18, the consistent "
             "search does)\n";
    }
    out << "    binding constraints:";
    if (p.result.binding.empty()) out << " none";
    for (const std::string& b : p.result.binding) out << " [" << b << "]";
    out << "\n    rms torque error per fitted motor, unconstrained:";
    const Eigen::VectorXd& rms = p.unconstrained.rms_error;
    for (Eigen::Index j = 0; j < rms.size(); ++j) {
      if (rms[j] > 0) out << " " << j + 1 << ": " << fixed(rms[j], 0, 4);
    }
    out << "\n";
  }
}

nlohmann::json ml_run_json(const MlRun& run) {
  const MlFitResult& fit = run.fit;
  nlohmann::json out;
  out["method"] = "ML approach " + std::to_string(run.approach) +
                  (run.physical ? " (physically consistent)" : "");
  if (fit.has_load) {
    nlohmann::json load = load_json(fit.load);
    load["std"] = load_json(fit.load_std_dev);
    load["warnings"] = fit.load_warnings;
    out["load"] = load;
  }
  nlohmann::json parameters = nlohmann::json::array();
  for (size_t u = 0; u < fit.names.size(); ++u) {
    if (fit.names[u].compare(0, 5, "load_") == 0) continue;
    parameters.push_back({{"name", fit.names[u]},
                          {"value", number(fit.value[static_cast<Eigen::Index>(u)])},
                          {"std", number(fit.std_dev[static_cast<Eigen::Index>(u)])}});
  }
  out["parameters"] = parameters;
  out["rms_per_axis"] =
      std::vector<double>(fit.rms_error.data(), fit.rms_error.data() + fit.rms_error.size());
  out["identifiability"] = {{"rank", fit.identifiability.rank},
                            {"unknowns", fit.names.size()},
                            {"condition_number", number(fit.identifiability.condition_number)},
                            {"directions", fit.identifiability.directions}};
  out["iterations"] = fit.iterations;
  out["seconds"] = run.seconds;
  if (!run.summary.empty()) out["summary"] = run.summary;
  if (run.load_summary || !run.drives.empty()) out["decided"] = ml_decided_json(run);
  if (run.physical) {
    const MlPhysicalRun& p = *run.physical;
    MlRun unconstrained = run;
    unconstrained.fit = p.unconstrained;
    unconstrained.physical.reset();
    unconstrained.load_summary.reset();
    unconstrained.drives.clear();
    out["physical"] = {{"prior_weight", p.prior_weight},
                       {"cost_increase", p.result.cost_increase},
                       {"binding_constraints", p.result.binding},
                       {"unconstrained_violations", p.violations},
                       {"unconstrained", ml_run_json(unconstrained)}};
  }
  return out;
}

}  // namespace modelgen::internal
