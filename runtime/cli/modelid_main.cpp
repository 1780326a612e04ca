// modelid command line: identification of base parameters from trajectories (fit), synthetic
// data from a model and a Fourier excitation (simulate), model checks (check). Exit codes:
// 0 success, 1 bad input or data, 2 bad usage, 3 internal error.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "generator/description/diagnostics.hpp"
#include "modelgen/data.hpp"
#include "modelgen/excitation.hpp"
#include "modelgen/identify.hpp"
#include "runtime/cli/model_source.hpp"
#include "runtime/cli/parameter_file.hpp"

namespace {

using namespace modelgen;

constexpr const char* kUsage =
    "usage: modelid fit --robot ROBOT --data A.csv [--data B.csv ...] --method ols|wls|pim-wls\n"
    "                   [-o EST.json] [--truth TRUE.json]\n"
    "       modelid simulate --robot ROBOT --params TRUE.json --trajectory TRAJ.yaml\n"
    "                   --noise SIGMA [--seed N] [--sample-time S] [--periods K] -o A.csv\n"
    "       modelid check ROBOT\n"
    "       modelid --help\n"
    "\n"
    "ROBOT is a description (.yaml/.urdf, through the numeric reference) or the name of a\n"
    "compiled-in generated model (tx40, kr150, ur5, iiwa14, panda, kuka_kr150_2,\n"
    "panda_arm).\n"
    "Data files: CSV with a header t, q1..qn, tau1..taun and optionally dq1.., ddq1.. (without\n"
    "them, velocities and accelerations come from central differences). README.md has details.\n";

struct UsageError {
  std::string message;
};

struct Arguments {
  std::string command;
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> options;

  bool has(const std::string& name) const { return options.count(name) > 0; }
  const std::string& one(const std::string& name) const {
    auto found = options.find(name);
    if (found == options.end()) throw UsageError{command + " needs " + name};
    if (found->second.size() != 1) throw UsageError{name + " given more than once"};
    return found->second.front();
  }
};

Arguments parse(int argc, char** argv, const std::map<std::string, bool>& allowed) {
  Arguments args;
  args.command = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 1 && arg[0] == '-') {
      auto found = allowed.find(arg);
      if (found == allowed.end()) throw UsageError{"unknown option '" + arg + "' for " + args.command};
      if (i + 1 >= argc) throw UsageError{arg + " needs a value"};
      args.options[arg].push_back(argv[++i]);
      if (!found->second && args.options[arg].size() > 1) throw UsageError{arg + " given twice"};
    } else {
      args.positional.push_back(arg);
    }
  }
  return args;
}

double parse_number(const std::string& text, const std::string& option) {
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw UsageError{option + " must be a number, not '" + text + "'"};
  }
  return value;
}

// Writes `text` to `path` through a temporary and a rename: never a half-written file.
void write_file(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp-modelid";
  std::ofstream out(temporary);
  out << text;
  out.close();
  if (!out || std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw std::runtime_error(path + ": error: cannot write the file");
  }
}

std::string fixed(double value, int width, int precision) {
  char text[64];
  std::snprintf(text, sizeof text, "%*.*g", width, precision, value);
  return text;
}

int run_fit(const Arguments& args) {
  const internal::ModelSource source = internal::load_model_source(args.one("--robot"));
  const IdentificationModel& model = *source.model;
  if (!args.has("--data")) throw UsageError{"fit needs at least one --data file"};
  const Method method = parse_method(args.one("--method"));
  std::vector<Trajectory> data;
  for (const std::string& path : args.options.at("--data")) {
    Trajectory x = read_trajectory_csv(path, model.dof());
    if (!x.has_velocity) differentiate(x);
    data.push_back(std::move(x));
  }
  const Identification id = identify(model, data, method);
  Eigen::VectorXd truth;
  if (args.has("--truth")) truth = internal::read_base_parameters(args.one("--truth"), model);

  const char* method_name = method == Method::kOls ? "IDIM-OLS" : method == Method::kWls ? "IDIM-WLS" : "PIM-WLS";
  std::cout << "modelid fit: " << model.name() << ", " << method_name << " on " << data.size()
            << " experiment(s), " << id.samples << " samples\n";
  std::cout << "  parameter          value          std      %std" << (truth.size() ? "         truth" : "")
            << "\n";
  for (std::size_t b = 0; b < id.names.size(); ++b) {
    std::string name = id.names[b];
    name.resize(std::max<std::size_t>(name.size(), 9), ' ');
    std::cout << "  " << name << " " << fixed(id.fit.value[b], 13, 6) << " "
              << fixed(id.fit.std_dev[b], 12, 3) << " " << fixed(id.fit.rel_std_dev[b], 9, 3)
              << (truth.size() ? " " + fixed(truth[b], 13, 6) : "") << "\n";
  }
  std::cout << "  relative error norm of the torques " << fixed(id.torque_rel_error_norm, 0, 4)
            << ", condition number " << fixed(id.fit.condition_number, 0, 4) << "\n";
  std::cout << "  rms torque error per axis (rms torque):";
  for (Eigen::Index j = 0; j < id.rms_error.size(); ++j) {
    std::cout << " " << fixed(id.rms_error[j], 0, 3) << " (" << fixed(id.rms_torque[j], 0, 3) << ")";
  }
  std::cout << "\n";

  if (args.has("-o")) {
    nlohmann::json out;
    out["model"] = model.name();
    out["description_sha256"] = model.description_sha256();
    out["method"] = method_name;
    out["samples"] = id.samples;
    out["rel_error_norm"] = id.torque_rel_error_norm;
    out["condition_number"] = id.fit.condition_number;
    out["residual_std"] = id.fit.residual_std_dev;
    out["rms_per_axis"] = std::vector<double>(id.rms_error.data(), id.rms_error.data() + id.rms_error.size());
    out["parameters"] = nlohmann::json::array();
    for (std::size_t b = 0; b < id.names.size(); ++b) {
      const double rel = id.fit.rel_std_dev[b];
      nlohmann::json entry = {{"name", id.names[b]},
                              {"value", id.fit.value[b]},
                              {"std", id.fit.std_dev[b]},
                              {"rel_std", std::isfinite(rel) ? nlohmann::json(rel) : nlohmann::json()}};
      if (truth.size()) entry["truth"] = truth[b];
      out["parameters"].push_back(entry);
    }
    write_file(args.one("-o"), out.dump(2) + "\n");
  }
  return 0;
}

FourierTrajectory read_fourier_checked(const std::string& path, int dof);

// Every yaml-cpp error (syntax, bad conversion) as an InputError naming the file and position.
FourierTrajectory read_fourier(const std::string& path, int dof) {
  try {
    return read_fourier_checked(path, dof);
  } catch (const YAML::Exception& e) {
    throw gen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
}

FourierTrajectory read_fourier_checked(const std::string& path, int dof) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw gen::InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
  auto at = [&](const YAML::Node& node) -> gen::SourceLocation {
    return {path, node.Mark().line + 1, node.Mark().column + 1};
  };
  FourierTrajectory f;
  if (!root["period"] || !root["joints"] || !root["joints"].IsSequence()) {
    throw gen::InputError({path}, "a trajectory needs 'period' (s) and 'joints' (one entry per "
                                  "joint with q0, a, b)");
  }
  f.period = root["period"].as<double>();
  if (!(f.period > 0)) throw gen::InputError(at(root["period"]), "'period' must be positive (s)");
  const YAML::Node joints = root["joints"];
  if (static_cast<int>(joints.size()) != dof) {
    throw gen::InputError(at(joints), "'joints' has " + std::to_string(joints.size()) +
                                          " entries, the robot has " + std::to_string(dof) + " joints");
  }
  const std::size_t harmonics = joints[0]["a"] ? joints[0]["a"].size() : 0;
  f.q0 = Eigen::VectorXd::Zero(dof);
  f.a = Eigen::MatrixXd::Zero(dof, harmonics);
  f.b = Eigen::MatrixXd::Zero(dof, harmonics);
  for (int j = 0; j < dof; ++j) {
    const YAML::Node joint = joints[j];
    if (!joint["a"] || !joint["b"] || joint["a"].size() != harmonics || joint["b"].size() != harmonics) {
      throw gen::InputError(at(joint), "joint " + std::to_string(j + 1) + " needs 'a' and 'b' with " +
                                           std::to_string(harmonics) + " coefficients each");
    }
    if (joint["q0"]) f.q0[j] = joint["q0"].as<double>();
    for (std::size_t l = 0; l < harmonics; ++l) {
      f.a(j, l) = joint["a"][l].as<double>();
      f.b(j, l) = joint["b"][l].as<double>();
    }
  }
  return f;
}

int run_simulate(const Arguments& args) {
  const internal::ModelSource source = internal::load_model_source(args.one("--robot"));
  const IdentificationModel& model = *source.model;
  const Eigen::VectorXd beta = internal::read_base_parameters(args.one("--params"), model);
  const FourierTrajectory fourier = read_fourier(args.one("--trajectory"), model.dof());
  const double noise = parse_number(args.one("--noise"), "--noise");
  const double sample_time = args.has("--sample-time") ? parse_number(args.one("--sample-time"), "--sample-time")
                                                       : fourier.period / 1000.0;
  const double periods = args.has("--periods") ? parse_number(args.one("--periods"), "--periods") : 1.0;
  std::uint64_t seed = 1;
  if (args.has("--seed")) {
    const std::string& text = args.one("--seed");
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
    if (ec != std::errc() || end != text.data() + text.size()) {
      throw UsageError{"--seed must be a non-negative integer, not '" + text + "'"};
    }
  }
  Trajectory x = sample(fourier, sample_time, periods * fourier.period);
  // Gaussian torque noise by Box-Muller on a fixed generator: the same seed, the same file.
  std::mt19937_64 engine(seed);
  auto uniform = [&engine] { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; };
  std::vector<double> tau(model.dof());
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    for (int j = 0; j < model.dof(); ++j) {
      const double u1 = uniform(), u2 = uniform();  // named: operand order is unspecified
      const double g = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
      x.tau(s, j) = tau[j] + noise * g;
    }
  }
  write_trajectory_csv(args.one("-o"), x);
  std::cerr << "modelid simulate: " << x.t.size() << " samples of " << model.name() << " written to "
            << args.one("-o") << "\n";
  return 0;
}

int run_check(const Arguments& args) {
  if (args.positional.size() != 1) throw UsageError{"check takes one ROBOT"};
  const internal::ModelSource source = internal::load_model_source(args.positional[0]);
  std::cout << source.model->name() << ": " << source.model->dof() << " dof, "
            << source.model->num_standard_params() << " standard and "
            << source.model->num_base_params() << " base parameters\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    (argc < 2 ? std::cerr : std::cout) << kUsage;
    return argc < 2 ? 2 : 0;
  }
  try {
    const std::string command = argv[1];
    if (command == "fit") {
      return run_fit(parse(argc, argv, {{"--robot", false}, {"--data", true}, {"--method", false},
                                        {"-o", false}, {"--truth", false}}));
    }
    if (command == "simulate") {
      return run_simulate(parse(argc, argv, {{"--robot", false}, {"--params", false},
                                             {"--trajectory", false}, {"--noise", false},
                                             {"--seed", false}, {"--sample-time", false},
                                             {"--periods", false}, {"-o", false}}));
    }
    if (command == "check") return run_check(parse(argc, argv, {}));
    throw UsageError{"unknown command '" + command + "'"};
  } catch (const UsageError& e) {
    std::cerr << "modelid: " << e.message << "\n\n" << kUsage;
    return 2;
  } catch (const gen::InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const DataError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const EstimationError& e) {
    std::cerr << "modelid: cannot identify: " << e.what() << "\n";
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "modelid: " << e.what() << "\n";
    return 1;
  } catch (const std::runtime_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "modelid: internal error: " << e.what() << "\n";
    return 3;
  }
}
