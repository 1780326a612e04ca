// modelid fit --method ml: load identification by maximum likelihood with the nonlinear drive
// model of Swevers et al. 2002 (eq. 12, cost eq. 18), the paper's approaches 1-3 (section 4):
// 1 the linear route of section 3.2 (base parameters of the moving links with the load, rotor
// inertias and friction by weighted least squares with R_z = 1, the load solved from them),
// 2 the nonlinear search with R_z fixed to 1, 3 the nonlinear search with R_z unknown; `all`
// runs the three and compares them as Tables 2-3 do. --truth adds exact values and errors.
// The a-priori values theta2 come from the description's `known:` values and --known.
// --physical replaces each approach's estimate by the nearest physically consistent one
// (modelgen/ml/physical_fit.hpp) and keeps the unconstrained one beside it.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/io/drive_parameter_file.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/linear_route.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/load_plausibility.hpp"
#include "modelgen/ml/physical_fit.hpp"
#include "modelgen/ml/problem.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/data/data_files.hpp"
#include "runtime/cli/data/drive_parameter_checks.hpp"
#include "runtime/cli/fit/ml_plan.hpp"
#include "runtime/cli/reports/ml_decided_report.hpp"
#include "runtime/cli/reports/ml_report.hpp"
#include "runtime/cli/reports/ml_residual_check.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

const std::vector<std::string> kUnknownGroups = {"load", "Rv", "Rc", "Rz"};

// The approaches to run: 1, 2 or 3, or all three for the comparison of Tables 2-3.
std::vector<int> parse_approaches(const CommandLine& args) {
  if (!args.has("--approach")) {
    throw UsageError{
        "--method ml needs --approach 1, 2, 3 or all (Swevers section 4: 1 linear, "
        "2 nonlinear with R_z = 1, 3 nonlinear with R_z unknown)"};
  }
  const std::string& text = args.one("--approach");
  if (text == "all") return {1, 2, 3};
  if (text != "1" && text != "2" && text != "3") {
    throw UsageError{"--approach must be 1, 2, 3 or all, not '" + text + "'"};
  }
  return {text[0] - '0'};
}

std::set<std::string> parse_unknown_groups(const CommandLine& args) {
  std::set<std::string> groups;
  const std::string text = args.has("--unknown") ? args.one("--unknown") : "load,Rv,Rc,Rz";
  for (const std::string& item : comma_items(text, "--unknown")) {
    if (std::find(kUnknownGroups.begin(), kUnknownGroups.end(), item) == kUnknownGroups.end()) {
      throw UsageError{"--unknown takes a comma-separated list of load, Rv, Rc, Rz, not '" + item +
                       "'"};
    }
    if (!groups.insert(item).second) {
      throw UsageError{"--unknown lists '" + item + "' twice"};
    }
  }
  if (groups.empty()) throw UsageError{"--unknown lists nothing"};
  return groups;
}

// The ML request: approaches and unknown groups, checked before anything is read.
struct MlRequest {
  std::vector<int> approaches;
  std::set<std::string> groups;
};

MlRequest read_ml_request(const CommandLine& args) {
  MlRequest request{parse_approaches(args), parse_unknown_groups(args)};
  if (args.has("--unknown") && request.groups.count("Rz") &&
      std::find(request.approaches.begin(), request.approaches.end(), 3) ==
          request.approaches.end()) {
    std::cerr << "modelid: note: approaches 1 and 2 fix R_z to 1; Rz in --unknown is ignored\n";
  }
  if (!args.has("--periodic")) {
    throw UsageError{
        "--method ml needs --periodic: the noise variance per axis (eq. 18's "
        "weights) comes from averaging the periods"};
  }
  return request;
}

// The description behind --robot, which the a-priori link values come from.
const RobotModel& ml_description(const ModelSource& source, const CommandLine& args,
                                 const MlRequest& request) {
  if (!source.description) {
    throw UsageError{
        "--method ml needs --robot to be a description file (.yaml/.urdf): the "
        "a-priori link values come from its 'known:' section, not '" +
        args.one("--robot") + "'"};
  }
  const RobotModel& description = *source.description;
  if (request.groups.count("load") && description.payload_body < 0) {
    throw UsageError{"the load is unknown but " + description.source_file +
                     " names no payload link (add 'payload: {link: N}')"};
  }
  return description;
}

// The values of --known, checked: a-priori values no robot has would bias every estimate made
// with them, and --physical couples the load's ten parameters.
std::map<std::string, double> read_known(const CommandLine& args,
                                         const std::vector<std::string>& names,
                                         const RobotModel& description, const MlRequest& request) {
  if (!args.has("--known")) return {};
  const std::string& path = args.one("--known");
  const std::map<std::string, double> known = read_drive_parameter_values(path, names);
  const std::vector<std::string> violations = drive_parameter_violations(known, description.tree);
  if (!violations.empty()) {
    std::string list;
    for (const std::string& v : violations) list += (list.empty() ? "" : "; ") + v;
    throw std::runtime_error(path +
                             ": error: these a-priori values cannot be those of a "
                             "physical robot: " +
                             list);
  }
  if (known.count("load_m") && !(known.at("load_m") > 0)) {
    throw std::runtime_error(path + ": error: 'load_m' must be positive, not " +
                             shortest(known.at("load_m")));
  }
  if (args.has("--physical") && request.groups.count("load")) {
    const auto& load = load_param_names();
    const auto given = std::count_if(load.begin(), load.end(),
                                     [&](const std::string& n) { return known.count(n) > 0; });
    if (given > 0 && given < static_cast<long>(load.size())) {
      throw UsageError{
          "--physical needs the load's ten parameters all unknown or all known (its "
          "log-Cholesky parameters couple them); " +
          path + " gives " + std::to_string(given) + " of them"};
    }
  }
  return known;
}

// The averaged periods as eq. 18 weighs them: motor-side, with their noise variances.
std::vector<MlExperiment> ml_data(const Experiments& experiments, const DriveChain& drive) {
  std::vector<MlExperiment> data;
  for (std::size_t e = 0; e < experiments.data.size(); ++e) {
    PreparedExperiment prepared;
    prepared.data = experiments.data[e];
    prepared.tau_noise_variance = experiments.tau_noise_variance[e];
    data.push_back(ml_experiment(prepared, drive));
  }
  return data;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// --physical: the consistent estimate takes the approach's place; the unconstrained one stays
// beside it. Approach 1's route estimates the rotor inertias too: its consistent version
// searches eq. 18 (R_z = 1, linear in these unknowns) over exactly the route's unknowns.
MlPhysicalRun physical_run(DriveModel& drive_model, const std::vector<MlExperiment>& data,
                           const MlPlan& plan, MlProblem& problem, const MlRun& run,
                           const Eigen::VectorXd& route_values, double prior_weight) {
  const auto start = std::chrono::steady_clock::now();
  MlPhysicalRun physical;
  physical.prior_weight = prior_weight;
  physical.unconstrained = run.fit;
  MlPhysicalOptions options;
  options.prior_weight = prior_weight;
  if (run.approach == 1) {
    MlSetup route_setup = plan.setup(1);
    route_setup.unknown = run.fit.names;
    MlProblem route_problem(drive_model, data, route_setup, route_values);
    physical.violations = ml_physical_violations(route_problem, run.fit);
    physical.result = fit_ml_physical(route_problem, run.fit, options);
  } else {
    physical.violations = ml_physical_violations(problem, run.fit);
    physical.result = fit_ml_physical(problem, run.fit, options);
  }
  physical.seconds = seconds_since(start);
  return physical;
}

// One approach of Swevers section 4: 1 the linear route (section 3.2), 2 and 3 the nonlinear
// drive model (eq. 12) with R_z fixed or unknown, started from the route.
MlRun run_approach(int approach, DriveModel& drive_model, const std::vector<MlExperiment>& data,
                   const MlPlan& plan, bool physical, double prior_weight, Eigen::Index& samples) {
  MlProblem problem(drive_model, data, plan.setup(approach), plan.values(approach));
  samples = problem.num_samples();
  MlRun run;
  run.approach = approach;
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd route_values;  // approach 1: every value, the route's estimates included
  if (approach == 1) {
    const LinearRoute route = linear_route(problem);
    run.fit = route.fit;
    route_values = route.values;
    run.summary =
        "linear model (R_z = 1, section 3.2): " + std::to_string(route.excited_parameters) +
        " parameters, " + std::to_string(route.base_parameters) +
        " identifiable combinations estimated by weighted least squares, the "
        "unknowns solved from them and the a-priori link values";
  } else {
    run.fit = fit_ml(problem);
    run.summary = "nonlinear drive model (eq. 12), R_z " +
                  std::string(approach == 3 ? "unknown" : "fixed to 1") +
                  ", started from the linear route";
  }
  run.seconds = seconds_since(start);
  if (physical) {
    run.physical = physical_run(drive_model, data, plan, problem, run, route_values, prior_weight);
    run.fit = run.physical->result.fit;
  }
  run.torque_errors = problem.torque_errors(run.fit.all_values);
  return run;
}

// Who decided the run's load and drive unknowns, and whether the load is plausible: within the
// arm's reach of the payload link and inside its region when the description gives one.
void summarise_run(const RobotModel& description, MlRun& run) {
  const std::vector<bool> none;
  const MlPhysicalResult* physical = run.physical ? &run.physical->result : nullptr;
  run.drives = summarise_ml_drives(run.fit, physical ? physical->at_bound : none);
  if (!run.fit.has_load || description.payload_body < 0) return;
  const auto body = static_cast<std::size_t>(description.payload_body);
  const std::optional<BodyRegion> region =
      body < description.body_regions.size() ? description.body_regions[body] : std::nullopt;
  run.load_summary = summarise_ml_load(run.fit, physical && physical->load_on_boundary,
                                       arm_reach(description.tree, description.payload_body),
                                       region, description.payload_body + 1);
}

void print_ml(const IdentificationModel& model, const std::vector<MlRun>& runs, const MlPlan& plan,
              std::size_t experiments, Eigen::Index samples, const std::string& data_report,
              const std::string& generated_name, const MlTruth& truth) {
  std::cout << "modelid fit: " << model.name() << ", ML approach"
            << (runs.size() > 1 ? "es 1-3" : " " + std::to_string(runs[0].approach)) << " on "
            << experiments << " experiment(s), " << samples << " averaged samples, axes";
  for (const int j : plan.axes) std::cout << " " << j + 1;
  std::cout << "\n"
            << data_report << "  drive model: "
            << (generated_name.empty()
                    ? std::string("numeric reference (the description is not compiled in)")
                    : "generated " + generated_name + " (analytic Jacobians)")
            << "\n";
  if (runs.size() == 1) {
    print_ml_run(std::cout, runs[0], plan.payload_link, truth);
  } else {
    print_ml_comparison(std::cout, runs, plan.payload_link, truth);
  }
  print_ml_physical(std::cout, runs);
  print_ml_decided(std::cout, runs, plan.payload_link);
  for (const MlRun& run : runs) warn_implausible_ml_estimates(std::cerr, run, runs.size() > 1);
  warn_implausible_ml_load(std::cerr, runs);
}

std::string ml_estimate_json(const CommandLine& args, const IdentificationModel& model,
                             const std::vector<MlRun>& runs) {
  nlohmann::json out;
  out["model"] = model.name();
  out["description_sha256"] = model.description_sha256();
  if (runs.size() == 1) {
    out.update(ml_run_json(runs[0]));
  } else {
    out["method"] = "ML approaches 1-3";
    out["approaches"] = nlohmann::json::array();
    for (const MlRun& run : runs) out["approaches"].push_back(ml_run_json(run));
  }
  out["data"] = args.all("--data");
  return out.dump(2) + "\n";
}

}  // namespace

int run_fit_ml(const CommandLine& args, double prior_weight) {
  const MlRequest request = read_ml_request(args);
  const ModelSource source = load_model_source(args.one("--robot"), args);
  const RobotModel& description = ml_description(source, args, request);
  const IdentificationModel& model = *source.model;

  // The generated drive model (flattened analytic Jacobians) when this description is one
  // modelid carries compiled in or has compiled, else the numeric reference's.
  std::string generated_name;
  std::unique_ptr<DriveModel> drive_model =
      make_shipped_drive_model(model.description_sha256(), &generated_name);
  if (drive_model == nullptr && (drive_model = compiled_drive_model(source)) != nullptr) {
    generated_name = model.name() + ", compiled from its description";
  }
  if (drive_model == nullptr) {
    drive_model = std::make_unique<ReferenceDriveModel>(description.tree, model.drive_chain());
  }
  const std::vector<std::string> names = ml_param_names(*drive_model);
  std::map<std::string, double> known = read_known(args, names, description, request);
  MlTruth truth;
  if (args.has("--truth")) truth = read_drive_parameter_values(args.one("--truth"), names);

  std::ostringstream data_report;
  const Experiments experiments = read_experiments(
      args.all("--data"), model, preparation_options(args), EffortColumns::kRequired, data_report);
  const std::vector<MlExperiment> data = ml_data(experiments, model.drive_chain());
  const MlPlan plan =
      make_ml_plan(description, model.drive_chain(), names, request.groups, std::move(known), data);
  warn_defaulted_priors(plan, request.approaches);

  std::vector<MlRun> runs;
  Eigen::Index samples = 0;
  for (const int approach : request.approaches) {
    runs.push_back(run_approach(approach, *drive_model, data, plan, args.has("--physical"),
                                prior_weight, samples));
    summarise_run(description, runs.back());
  }
  print_ml(model, runs, plan, data.size(), samples, data_report.str(), generated_name, truth);
  // Each approach's residual against the periods' noise, on the joints its motors reach.
  for (const MlRun& run : runs) {
    warn_ml_residual_against_noise(std::cerr, model, experiments, run.torque_errors, plan.axes,
                                   static_cast<Eigen::Index>(run.fit.names.size()),
                                   " (of approach " + std::to_string(run.approach) + ")");
  }
  if (args.has("-o")) write_file(args.one("-o"), ml_estimate_json(args, model, runs));
  return 0;
}

}  // namespace modelgen::internal
