// Reading and preparing the --data files of fit and predict, one experiment per file.

#include "runtime/cli/data_files.hpp"

#include <iostream>
#include <stdexcept>

#include "modelgen/signal/decimation.hpp"
#include "runtime/cli/progress.hpp"

namespace modelgen::internal {

namespace {

// The data options in the order data_option_words writes them. A function: the commands'
// option tables, globals of other files, are built from it during static initialisation.
const std::vector<std::pair<std::string, OptionKind>>& data_options() {
  static const std::vector<std::pair<std::string, OptionKind>> options = {
      {"--motor-side", OptionKind::kFlag}, {"--periodic", OptionKind::kFlag},
      {"--period", OptionKind::kOnce},     {"--harmonics", OptionKind::kOnce},
      {"--raw", OptionKind::kFlag},        {"--bandwidth", OptionKind::kOnce},
      {"--cutoff", OptionKind::kOnce},     {"--decimate", OptionKind::kOnce},
      {"--torque-hold", OptionKind::kOnce}, {"--skip-periods", OptionKind::kOnce}};
  return options;
}

}  // namespace

std::map<std::string, OptionKind> with_data_options(std::map<std::string, OptionKind> options) {
  options.insert(data_options().begin(), data_options().end());
  return options;
}

std::vector<std::string> data_option_words(const CommandLine& args) {
  std::vector<std::string> words;
  for (const auto& [name, kind] : data_options()) {
    if (!args.has(name)) continue;
    words.push_back(name);
    if (kind != OptionKind::kFlag) words.push_back(args.one(name));
  }
  return words;
}

CommandLine data_options_from_words(const std::vector<std::string>& words,
                                    const std::string& origin) {
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  const std::map<std::string, OptionKind> allowed(data_options().begin(),
                                                   data_options().end());
  try {
    return parse_command_line(static_cast<int>(argv.size()), argv.data(), 0, "", allowed);
  } catch (const UsageError& e) {
    throw UsageError{origin + ": the data options of the estimate: " + e.what()};
  }
}

namespace {

double positive(const CommandLine& args, const std::string& option) {
  const double value = parse_number(args.one(option), option);
  if (!(value > 0)) throw UsageError{option + " must be positive, not '" + args.one(option) + "'"};
  return value;
}

int count(const CommandLine& args, const std::string& option) {
  const double value = parse_number(args.one(option), option);
  if (!(value >= 1) || value != static_cast<int>(value)) {
    throw UsageError{option + " must be a whole number of at least 1, not '" + args.one(option) +
                     "'"};
  }
  return static_cast<int>(value);
}

}  // namespace

PreparationOptions preparation_options(const CommandLine& args) {
  PreparationOptions options;
  if (args.has("--motor-side")) options.side = Side::kMotor;
  options.periodic = args.has("--periodic");
  options.raw = args.has("--raw");
  if (options.periodic && options.raw) {
    throw UsageError{
        "--periodic and --raw exclude each other (the periodic route computes the "
        "derivatives from the Fourier series)"};
  }
  for (const char* option : {"--period", "--harmonics", "--skip-periods"}) {
    if (args.has(option) && !options.periodic) {
      throw UsageError{std::string(option) + " belongs to --periodic; add --periodic"};
    }
  }
  for (const char* option : {"--bandwidth", "--cutoff"}) {
    if (args.has(option) && (options.periodic || options.raw)) {
      throw UsageError{std::string(option) +
                       " sets the position filter of non-periodic data; it does not go with " +
                       (options.periodic ? "--periodic" : "--raw")};
    }
  }
  if (options.periodic && args.has("--decimate")) {
    throw UsageError{
        "--decimate does not go with --periodic: the averaged period is already "
        "noise-reduced and its Fourier series smooth"};
  }
  if (args.has("--period")) options.period = positive(args, "--period");
  if (args.has("--harmonics")) options.harmonics = count(args, "--harmonics");
  if (args.has("--skip-periods")) options.skip_periods = count(args, "--skip-periods");
  if (args.has("--bandwidth")) options.bandwidth_hz = positive(args, "--bandwidth");
  if (args.has("--cutoff")) options.cutoff_hz = positive(args, "--cutoff");
  if (args.has("--torque-hold")) {
    const std::string& hold = args.one("--torque-hold");
    if (hold != "zoh" && hold != "sampled") {
      throw UsageError{"--torque-hold must be 'zoh' (torque commands held over each sample) or "
                       "'sampled' (torques measured at the time stamps), not '" + hold + "'"};
    }
    options.torque_hold = hold == "zoh";
  }
  if (args.has("--decimate")) {
    options.decimation = count(args, "--decimate");
    try {
      decimation_stages(*options.decimation);
    } catch (const std::invalid_argument& e) {
      throw UsageError{std::string("--decimate: ") + e.what()};
    }
  }
  return options;
}

Experiments read_experiments(const std::vector<std::string>& paths,
                             const IdentificationModel& model, const PreparationOptions& options,
                             EffortColumns effort, std::ostream& report) {
  Experiments out;
  Progress progress("reading data", static_cast<long long>(paths.size()));
  for (const std::string& path : paths) {
    progress.update(static_cast<long long>(out.data.size()), path);
    PreparedExperiment prepared = prepare_experiment(read_trajectory_csv(path, model.dof(), effort),
                                                     model.drive_chain(), options);
    report << "  " << path << ": " << prepared.summary << "\n";
    if (!prepared.warning.empty()) std::cerr << prepared.warning << "\n";
    out.data.push_back(std::move(prepared.data));
    out.decimation.push_back(prepared.decimation);
    out.bandwidth_hz.push_back(prepared.bandwidth_hz);
    out.tau_noise_variance.push_back(std::move(prepared.tau_noise_variance));
    out.noise.push_back(std::move(prepared.noise));
  }
  progress.update(static_cast<long long>(out.data.size()));
  return out;
}

}  // namespace modelgen::internal
