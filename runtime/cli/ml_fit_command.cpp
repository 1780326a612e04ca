// modelid fit --method ml: load identification by maximum likelihood with the nonlinear drive
// model of Swevers et al. 2002 (eq. 12, cost eq. 18), the paper's approaches 1-3 (section 4):
// 1 the linear route of section 3.2 (efficiencies R_z fixed to 1, no nonlinear search),
// 2 the nonlinear search with R_z fixed to 1, 3 the nonlinear search with R_z unknown.
// The a-priori values theta2 come from the description's `known:` values and --known.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "modelgen/drive_model.hpp"
#include "modelgen/estimate.hpp"
#include "modelgen/load_parameters.hpp"
#include "modelgen/ml_fit.hpp"
#include "modelgen/ml_problem.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/data_files.hpp"
#include "runtime/cli/drive_parameter_file.hpp"
#include "runtime/cli/model_source.hpp"
#include "runtime/cli/text_format.hpp"

namespace modelgen::internal {

namespace {

const std::vector<std::string> kUnknownGroups = {"load", "Rv", "Rc", "Rz"};

int parse_approach(const Arguments& args) {
  if (!args.has("--approach")) {
    throw UsageError{
        "--method ml needs --approach 1, 2 or 3 (Swevers section 4: 1 linear, "
        "2 nonlinear with R_z = 1, 3 nonlinear with R_z unknown)"};
  }
  const std::string& text = args.one("--approach");
  if (text != "1" && text != "2" && text != "3") {
    throw UsageError{"--approach must be 1, 2 or 3, not '" + text + "'"};
  }
  return text[0] - '0';
}

std::set<std::string> parse_unknown_groups(const Arguments& args) {
  std::set<std::string> groups;
  const std::string text = args.has("--unknown") ? args.one("--unknown") : "load,Rv,Rc,Rz";
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
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
Eigen::VectorXd prior_values(const gen::RobotModel& description, const Transmission& drive,
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
std::vector<int> moving_axes(const std::vector<MlExperiment>& data, const Transmission& drive) {
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

std::string with_std(double value, double sd, double scale, int precision) {
  if (!std::isfinite(value)) return "not identifiable";
  return fixed(value * scale, 10, precision) + " +- " + fixed(sd * scale, 0, 2);
}

}  // namespace

int run_fit_ml(const Arguments& args) {
  const int approach = parse_approach(args);
  const std::set<std::string> groups = parse_unknown_groups(args);
  if (approach != 3 && args.has("--unknown") && groups.count("Rz")) {
    std::cerr << "modelid: note: approach " << approach
              << " fixes R_z to 1; Rz in --unknown is ignored\n";
  }
  const ModelSource source = load_model_source(args.one("--robot"));
  if (!source.description) {
    throw UsageError{
        "--method ml needs --robot to be a description file (.yaml/.urdf): the "
        "a-priori link values come from its 'known:' section, not '" +
        args.one("--robot") + "'"};
  }
  const gen::RobotModel& description = *source.description;
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

  ReferenceDriveModel drive_model(description.tree, model.transmission());
  const std::vector<std::string> names = ml_param_names(drive_model);
  std::map<std::string, double> overrides;
  if (args.has("--known")) overrides = read_drive_parameter_values(args.one("--known"), names);

  std::ostringstream data_report;
  const Experiments experiments = read_experiments(
      args.all("--data"), model, preparation_options(args), EffortColumns::kRequired, data_report);
  std::vector<MlExperiment> data;
  for (std::size_t e = 0; e < experiments.data.size(); ++e) {
    PreparedExperiment prepared;
    prepared.data = experiments.data[e];
    prepared.tau_noise_variance = experiments.tau_noise_variance[e];
    data.push_back(ml_experiment(prepared, model.transmission()));
  }

  std::vector<std::string> missing;
  Eigen::VectorXd values =
      prior_values(description, model.transmission(), names, overrides, missing);

  MlSetup setup;
  setup.payload_link = description.payload_body >= 0 ? description.payload_body + 1 : 0;
  const std::vector<int> axes = moving_axes(data, model.transmission());
  if (axes.empty()) throw EstimationError("maximum likelihood: no motor moves in the data");
  setup.axes = axes;
  if (groups.count("load")) setup.unknown = load_param_names();
  for (const char* stem : {"Rv", "Rc", "Rz"}) {
    if (!groups.count(stem)) continue;
    for (const int j : axes) {
      const std::string name = stem + std::to_string(j + 1);
      if (std::string(stem) == "Rz" && approach != 3) continue;
      setup.unknown.push_back(name);
    }
  }
  if (setup.unknown.empty()) throw UsageError{"--unknown leaves nothing to identify"};
  // Approaches 1 and 2: every efficiency at 1 (Swevers section 4).
  if (approach != 3) {
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (names[k].compare(0, 2, "Rz") == 0) values[static_cast<Eigen::Index>(k)] = 1.0;
    }
  }
  // A-priori values the fit uses without having been given; the unknowns only start there.
  std::vector<std::string> defaulted;
  for (const std::string& name : missing) {
    if (std::find(setup.unknown.begin(), setup.unknown.end(), name) != setup.unknown.end()) {
      continue;
    }
    if (approach != 3 && name.compare(0, 2, "Rz") == 0) continue;
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

  MlProblem problem(drive_model, data, setup, values);
  MlFitOptions options;
  // Approach 1: the linear route only. fit_ml then evaluates the statistics at the linear
  // estimate, which with every R_z = 1 is the weighted least-squares solution itself.
  if (approach == 1) options.max_iterations = 0;
  const auto start = std::chrono::steady_clock::now();
  const MlFitResult fit = fit_ml(problem, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::cout << "modelid fit: " << model.name() << ", ML approach " << approach << " on "
            << data.size() << " experiment(s), " << problem.num_samples()
            << " averaged samples, axes";
  for (const int j : problem.axes()) std::cout << " " << j + 1;
  std::cout << "\n" << data_report.str();
  const Identifiability& id = fit.identifiability;
  std::cout << "  identifiability: rank " << id.rank << " of " << fit.names.size()
            << " unknowns, condition number " << fixed(id.condition_number, 0, 4) << "\n";
  for (const std::string& direction : id.directions) std::cout << "    " << direction << "\n";
  for (const std::string& note : fit.notes) std::cout << "  note: " << note << "\n";
  if (fit.has_load) {
    const LoadParameters& l = fit.load;
    const LoadParameters& s = fit.load_std_dev;
    std::cout << "  load on link " << setup.payload_link
              << " (centre of gravity in mm, inertia about it in kg m^2):\n"
              << "    m   " << with_std(l.mass, s.mass, 1, 6) << " kg\n";
    const char* c_names[3] = {"cx", "cy", "cz"};
    for (int k = 0; k < 3; ++k) {
      std::cout << "    " << pad(c_names[k], 3) << " " << with_std(l.com[k], s.com[k], 1e3, 5)
                << " mm\n";
    }
    const char* i_names[6] = {"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"};
    for (int k = 0; k < 6; ++k) {
      std::cout << "    " << i_names[k] << " " << with_std(l.inertia[k], s.inertia[k], 1, 5)
                << "\n";
    }
    for (const std::string& warning : fit.load_warnings) {
      std::cout << "  warning: " << warning << "\n";
    }
  }
  std::cout << "  drive parameters:\n";
  nlohmann::json parameters = nlohmann::json::array();
  for (std::size_t u = 0; u < fit.names.size(); ++u) {
    if (fit.names[u].compare(0, 5, "load_") == 0) continue;
    std::cout << "    " << pad(fit.names[u], 5) << " "
              << with_std(fit.value[static_cast<Eigen::Index>(u)],
                          fit.std_dev[static_cast<Eigen::Index>(u)], 1, 5)
              << "\n";
    parameters.push_back({{"name", fit.names[u]},
                          {"value", number(fit.value[static_cast<Eigen::Index>(u)])},
                          {"std", number(fit.std_dev[static_cast<Eigen::Index>(u)])}});
  }
  std::cout << "  rms torque error per motor (N m):";
  for (Eigen::Index j = 0; j < fit.rms_error.size(); ++j) {
    std::cout << " " << fixed(fit.rms_error[j], 0, 3);
  }
  std::cout << "\n  " << fit.iterations << " Levenberg-Marquardt iteration(s), "
            << fixed(seconds, 0, 3) << " s" << (approach == 1 ? " (linear route only)" : "")
            << "\n";

  if (args.has("-o")) {
    nlohmann::json out;
    out["model"] = model.name();
    out["description_sha256"] = model.description_sha256();
    out["method"] = "ML approach " + std::to_string(approach);
    if (fit.has_load) {
      nlohmann::json load = load_json(fit.load);
      load["std"] = load_json(fit.load_std_dev);
      load["warnings"] = fit.load_warnings;
      out["load"] = load;
    }
    out["parameters"] = parameters;
    out["rms_per_axis"] =
        std::vector<double>(fit.rms_error.data(), fit.rms_error.data() + fit.rms_error.size());
    out["identifiability"] = {{"rank", id.rank},
                              {"unknowns", fit.names.size()},
                              {"condition_number", number(id.condition_number)},
                              {"directions", id.directions}};
    out["iterations"] = fit.iterations;
    out["data"] = args.all("--data");
    write_file(args.one("-o"), out.dump(2) + "\n");
  }
  return 0;
}

}  // namespace modelgen::internal
