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

#include "modelgen/data/trajectory_csv.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/linear_route.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/physical_fit.hpp"
#include "modelgen/ml/problem.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/data/data_files.hpp"
#include "runtime/cli/data/drive_parameter_file.hpp"
#include "runtime/cli/reports/ml_report.hpp"

namespace modelgen::internal {

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

// The a-priori values of every ml_param_names() entry, and the names that had none.
// Mapping from the description's standard parameters: XXj..Mj keep their names; the joint-side
// rotor inertia Iaj becomes the motor-side JMj = Iaj / K_jj^2 (K = motor_from_joint; for a
// diagonal K the two models then agree on tau_joint = K^T tau_M). Friction Fv/Fc is not mapped:
// the drive model's Rv/Rc are motor-side and usually unknown. Without a value: Rzj 1 (no loss),
// everything else 0; those names are reported.
Eigen::VectorXd prior_values(const modelgen::RobotModel& description, const DriveChain& drive,
                             const std::vector<std::string>& names,
                             const std::map<std::string, double>& overrides,
                             std::vector<std::string>& missing) {
  std::map<std::string, double> known;
  for (std::size_t k = 0; k < description.known_values.size(); ++k) {
    if (!description.known_values[k]) continue;
    const std::string& name = description.tree.params[k].name;
    const double value = *description.known_values[k];
    if (name.compare(0, 2, "Ia") == 0 && name.size() > 2 && std::isdigit(name[2]) &&
        name.find_first_not_of("0123456789", 2) == std::string::npos) {
      const int j = std::stoi(name.substr(2)) - 1;
      if (j >= 0 && j < drive.motor_from_joint.rows()) {
        const double ratio = drive.motor_from_joint(j, j);
        known["JM" + name.substr(2)] = value / (ratio * ratio);
      }
    } else {
      known[name] = value;
    }
  }
  for (const auto& [name, value] : overrides) known[name] = value;
  Eigen::VectorXd values(static_cast<Eigen::Index>(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto found = known.find(names[k]);
    if (found != known.end()) {
      values[static_cast<Eigen::Index>(k)] = found->second;
    } else {
      values[static_cast<Eigen::Index>(k)] = names[k].compare(0, 2, "Rz") == 0 ? 1.0 : 0.0;
      missing.push_back(names[k]);
    }
  }
  return values;
}

// The motors (0-based) that move: max |dq_M,i| (dq_M = K dq, eq. 9) above 1e-6 times the
// largest motor speed. Not an exact zero test: the periodic route's Fourier re-estimation
// leaves rounding-level velocities on axes held still.
std::vector<int> moving_axes(const std::vector<MlExperiment>& data, const DriveChain& drive) {
  const Eigen::Index dof = drive.motor_from_joint.rows();
  Eigen::VectorXd speed = Eigen::VectorXd::Zero(dof);
  for (const MlExperiment& x : data) {
    const Eigen::MatrixXd dq_M = x.dq * drive.motor_from_joint.transpose();
    speed = speed.cwiseMax(dq_M.cwiseAbs().colwise().maxCoeff().transpose());
  }
  std::vector<int> axes;
  for (Eigen::Index i = 0; i < dof; ++i) {
    if (speed[i] > 1e-6 * speed.maxCoeff()) axes.push_back(static_cast<int>(i));
  }
  return axes;
}

// The motor (1-based) a drive parameter name JMj/Rvj/Rcj/Rzj belongs to, or 0.
int drive_motor(const std::string& name) {
  for (const char* stem : {"JM", "Rv", "Rc", "Rz"}) {
    if (name.compare(0, 2, stem) == 0 && name.size() > 2 &&
        name.find_first_not_of("0123456789", 2) == std::string::npos) {
      return std::stoi(name.substr(2));
    }
  }
  return 0;
}

}  // namespace

int run_fit_ml(const CommandLine& args, double prior_weight) {
  const std::vector<int> approaches = parse_approaches(args);
  const std::set<std::string> groups = parse_unknown_groups(args);
  const bool rz_unknown = groups.count("Rz") > 0;
  if (args.has("--unknown") && rz_unknown &&
      std::find(approaches.begin(), approaches.end(), 3) == approaches.end()) {
    std::cerr << "modelid: note: approaches 1 and 2 fix R_z to 1; Rz in --unknown is ignored\n";
  }
  const ModelSource source = load_model_source(args.one("--robot"), angle_tolerance_option(args));
  if (!source.description) {
    throw UsageError{
        "--method ml needs --robot to be a description file (.yaml/.urdf): the "
        "a-priori link values come from its 'known:' section, not '" +
        args.one("--robot") + "'"};
  }
  const modelgen::RobotModel& description = *source.description;
  const IdentificationModel& model = *source.model;
  if (!args.has("--data")) throw UsageError{"fit needs at least one --data file"};
  if (!args.has("--periodic")) {
    throw UsageError{
        "--method ml needs --periodic: the noise variance per axis (eq. 18's "
        "weights) comes from averaging the periods"};
  }
  if (groups.count("load") && description.payload_body < 0) {
    throw UsageError{"the load is unknown but " + description.source_file +
                     " names no payload link (add 'payload: {link: N}')"};
  }

  // The generated drive model (flattened analytic Jacobians) when this description is one
  // modelid carries compiled in, else the numeric reference's.
  std::string generated_name;
  std::unique_ptr<DriveModel> drive_model =
      make_shipped_drive_model(model.description_sha256(), &generated_name);
  if (drive_model == nullptr) {
    drive_model = std::make_unique<ReferenceDriveModel>(description.tree, model.drive_chain());
  }
  const std::vector<std::string> names = ml_param_names(*drive_model);
  std::map<std::string, double> overrides;
  if (args.has("--known")) {
    overrides = read_drive_parameter_values(args.one("--known"), names);
    // A-priori values no robot has would bias every estimate made with them.
    const std::vector<std::string> violations =
        drive_parameter_violations(overrides, description.tree);
    if (!violations.empty()) {
      std::string list;
      for (const std::string& v : violations) list += (list.empty() ? "" : "; ") + v;
      throw std::runtime_error(args.one("--known") +
                               ": error: these a-priori values cannot be those of a physical "
                               "robot: " + list);
    }
  }
  if (overrides.count("load_m") && !(overrides.at("load_m") > 0)) {
    throw std::runtime_error(args.one("--known") + ": error: 'load_m' must be positive, not " +
                             shortest(overrides.at("load_m")));
  }
  if (args.has("--physical") && groups.count("load")) {
    const auto& load = load_param_names();
    const auto known = std::count_if(load.begin(), load.end(),
                                     [&](const std::string& n) { return overrides.count(n) > 0; });
    if (known > 0 && known < static_cast<long>(load.size())) {
      throw UsageError{
          "--physical needs the load's ten parameters all unknown or all known (its "
          "log-Cholesky parameters couple them); " + args.one("--known") + " gives " +
          std::to_string(known) + " of them"};
    }
  }
  MlTruth truth;
  if (args.has("--truth")) truth = read_drive_parameter_values(args.one("--truth"), names);

  std::ostringstream data_report;
  const Experiments experiments = read_experiments(
      args.all("--data"), model, preparation_options(args), EffortColumns::kRequired, data_report);
  std::vector<MlExperiment> data;
  for (std::size_t e = 0; e < experiments.data.size(); ++e) {
    PreparedExperiment prepared;
    prepared.data = experiments.data[e];
    prepared.tau_noise_variance = experiments.tau_noise_variance[e];
    data.push_back(ml_experiment(prepared, model.drive_chain()));
  }

  std::vector<std::string> missing;
  const Eigen::VectorXd priors =
      prior_values(description, model.drive_chain(), names, overrides, missing);
  const std::vector<int> axes = moving_axes(data, model.drive_chain());
  if (axes.empty()) throw EstimationError("maximum likelihood: no motor moves in the data");
  const int payload_link = description.payload_body >= 0 ? description.payload_body + 1 : 0;

  // theta1 of an approach (Swevers section 4): the chosen groups for the moving axes; the
  // efficiencies only in approach 3, every one of them 1 in approaches 1 and 2.
  const auto setup_of = [&](int approach) {
    MlSetup setup;
    setup.payload_link = payload_link;
    setup.axes = axes;
    // Load parameters given in --known are known (a weighed mass, say); the rest are unknown.
    if (groups.count("load")) {
      for (const std::string& name : load_param_names()) {
        if (!overrides.count(name)) setup.unknown.push_back(name);
      }
    }
    for (const char* stem : {"Rv", "Rc", "Rz"}) {
      if (!groups.count(stem) || (std::string(stem) == "Rz" && approach != 3)) continue;
      for (const int j : axes) setup.unknown.push_back(stem + std::to_string(j + 1));
    }
    if (setup.unknown.empty()) throw UsageError{"--unknown leaves nothing to identify"};
    return setup;
  };
  const auto values_of = [&](int approach) {
    Eigen::VectorXd values = priors;
    if (approach != 3) {
      for (std::size_t k = 0; k < names.size(); ++k) {
        if (names[k].compare(0, 2, "Rz") == 0) values[static_cast<Eigen::Index>(k)] = 1.0;
      }
    }
    return values;
  };

  // A-priori values the fits use without having been given; the unknowns only start there.
  std::vector<std::string> defaulted;
  const MlSetup widest = setup_of(approaches.back());
  for (const std::string& name : missing) {
    if (std::find(widest.unknown.begin(), widest.unknown.end(), name) != widest.unknown.end()) {
      continue;
    }
    if (name.compare(0, 2, "Rz") == 0 &&
        std::find(approaches.begin(), approaches.end(), 3) == approaches.end()) {
      continue;
    }
    // Approach 1 estimates the rotor inertias.
    if (name.compare(0, 2, "JM") == 0 && approaches == std::vector<int>{1}) continue;
    // Drive parameters of motors not fitted do not enter eq. 18.
    const int motor = drive_motor(name);
    if (motor > 0 && std::find(axes.begin(), axes.end(), motor - 1) == axes.end()) continue;
    defaulted.push_back(name);
  }
  if (!defaulted.empty()) {
    std::string list;
    for (const std::string& name : defaulted) list += " " + name;
    std::cerr << "modelid: warning: no a-priori value (description 'known:' or --known) for" << list
              << "; taken as 0 (Rz as 1)\n";
  }

  std::vector<MlRun> runs;
  Eigen::Index samples = 0;
  for (const int approach : approaches) {
    MlProblem problem(*drive_model, data, setup_of(approach), values_of(approach));
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
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (args.has("--physical")) {
      // The consistent estimate takes the approach's place; the unconstrained one stays beside.
      const auto physical_start = std::chrono::steady_clock::now();
      MlPhysicalRun physical;
      physical.prior_weight = prior_weight;
      physical.unconstrained = run.fit;
      MlPhysicalOptions options;
      options.prior_weight = prior_weight;
      if (approach == 1) {
        // The route estimates the rotor inertias too: its consistent version searches eq. 18
        // (R_z = 1, linear in these unknowns) over exactly the route's unknowns.
        MlSetup route_setup = setup_of(1);
        route_setup.unknown = run.fit.names;
        MlProblem route_problem(*drive_model, data, route_setup, route_values);
        physical.violations = ml_physical_violations(route_problem, run.fit);
        physical.result = fit_ml_physical(route_problem, run.fit, options);
      } else {
        physical.violations = ml_physical_violations(problem, run.fit);
        physical.result = fit_ml_physical(problem, run.fit, options);
      }
      run.fit = physical.result.fit;
      physical.seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - physical_start).count();
      run.physical = std::move(physical);
    }
    runs.push_back(std::move(run));
  }

  std::cout << "modelid fit: " << model.name() << ", ML approach"
            << (runs.size() > 1 ? "es 1-3" : " " + std::to_string(runs[0].approach)) << " on "
            << data.size() << " experiment(s), " << samples << " averaged samples, axes";
  for (const int j : axes) std::cout << " " << j + 1;
  std::cout << "\n"
            << data_report.str() << "  drive model: "
            << (generated_name.empty()
                    ? std::string("numeric reference (the description is not compiled in)")
                    : "generated " + generated_name + " (analytic Jacobians)")
            << "\n";
  if (runs.size() == 1) {
    print_ml_run(std::cout, runs[0], payload_link, truth);
  } else {
    print_ml_comparison(std::cout, runs, payload_link, truth);
  }
  print_ml_physical(std::cout, runs);
  for (const MlRun& run : runs) warn_implausible_ml_estimates(std::cerr, run, runs.size() > 1);

  if (args.has("-o")) {
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
    write_file(args.one("-o"), out.dump(2) + "\n");
  }
  return 0;
}

}  // namespace modelgen::internal
