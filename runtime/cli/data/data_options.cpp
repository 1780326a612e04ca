// The data options of fit and predict, declared once (in the order EST.json records them): their
// table, the words fit records in EST.json so that predict prepares data the same way, and the
// preparation they ask for.

#include <algorithm>
#include <stdexcept>

#include "modelgen/signal/decimation.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

namespace {

constexpr const char* kGroup = "Data preparation";

CommandSpec make_data_options_spec() {
  CommandSpec spec;
  spec.name = "";
  spec.options = {
      {.name = "--motor-side",
       .type = ValueType::kFlag,
       .help = "positions and torques were measured on the motor side: brought to the joint "
               "side through the description's drive chain (Gautier eq. 25, Swevers eq. 9-10)",
       .group = kGroup},
      {.name = "--periodic",
       .type = ValueType::kFlag,
       .help = "periodic excitation: whole periods averaged, the noise variance estimated per "
               "axis and q, dq, ddq from the re-estimated Fourier series (Swevers 2002, eq. 15-17)",
       .group = kGroup},
      {.name = "--period",
       .type = ValueType::kPositive,
       .value = "S",
       .help = "the excitation period",
       .unit = "s",
       .default_value = "detected from the data",
       .needs = "--periodic",
       .group = kGroup},
      {.name = "--harmonics",
       .type = ValueType::kCount,
       .value = "H",
       .help = "harmonics kept in the Fourier re-estimation",
       .default_value = "those that stand out of the noise",
       .needs = "--periodic",
       .group = kGroup},
      {.name = "--raw",
       .type = ValueType::kFlag,
       .help = "plain central differences, no filter, no decimation (clean simulated data)",
       .group = kGroup},
      {.name = "--bandwidth",
       .type = ValueType::kPositive,
       .value = "HZ",
       .help = "the excitation bandwidth the filter and decimation are planned for",
       .unit = "Hz",
       .default_value = "estimated from the spectra",
       .group = kGroup},
      {.name = "--cutoff",
       .type = ValueType::kPositive,
       .value = "HZ",
       .help = "the cut-off of the zero-phase position filter",
       .unit = "Hz",
       .default_value = "10 x the bandwidth",
       .group = kGroup},
      {.name = "--decimate",
       .type = ValueType::kCount,
       .value = "N",
       .help = "the parallel decimation factor (Gautier & Briot eq. 13-14); it must split into "
               "stages of at most 10",
       .default_value = "the largest that keeps 2 x the bandwidth and 20 rows per parameter",
       .group = kGroup},
      {.name = "--torque-hold",
       .type = ValueType::kChoice,
       .help = "zoh: the torques are a digital controller's commands held over each sample "
               "(replaced by the mean of each and the one before); sampled: measured at the time "
               "stamps",
       .default_value = "sampled",
       .choices = {"zoh", "sampled"},
       .group = kGroup},
      {.name = "--skip-periods",
       .type = ValueType::kCount,
       .value = "K",
       .help = "periods left out at the start (a closed-loop record's transient)",
       .needs = "--periodic",
       .group = kGroup},
  };
  const std::string filter = "it sets the position filter of non-periodic data";
  spec.exclusive = {
      {"--periodic", "--raw",
       "the periodic route computes the derivatives from the Fourier series"},
      {"--bandwidth", "--periodic", filter},
      {"--bandwidth", "--raw", filter},
      {"--cutoff", "--periodic", filter},
      {"--cutoff", "--raw", filter},
      {"--decimate", "--periodic",
       "the averaged period is already noise-reduced and its Fourier series smooth"},
  };
  return spec;
}

// The table of the data options alone: EST.json's words are parsed by it.
const CommandSpec& data_options_spec() {
  static const CommandSpec spec = make_data_options_spec();
  return spec;
}

}  // namespace

void add_data_options(CommandSpec& spec) {
  const CommandSpec& data = data_options_spec();
  // Before the options every command takes, which close the table.
  auto at = std::find_if(spec.options.begin(), spec.options.end(), [](const OptionSpec& option) {
    return option.name == "--angle-tolerance";
  });
  spec.options.insert(at, data.options.begin(), data.options.end());
  spec.exclusive.insert(spec.exclusive.end(), data.exclusive.begin(), data.exclusive.end());
}

std::vector<std::string> data_option_words(const CommandLine& args) {
  std::vector<std::string> words;
  for (const OptionSpec& option : data_options_spec().options) {
    if (!args.has(option.name)) continue;
    words.push_back(option.name);
    if (option.type != ValueType::kFlag) words.push_back(args.one(option.name));
  }
  return words;
}

CommandLine data_options_from_words(const std::vector<std::string>& words,
                                    const std::string& origin) {
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  try {
    return parse_command(data_options_spec(), static_cast<int>(argv.size()), argv.data(), 0);
  } catch (const UsageError& e) {
    throw UsageError{origin + ": the data options of the estimate: " + e.what()};
  }
}

PreparationOptions preparation_options(const CommandLine& args) {
  // Types, ranges, --periodic's refinements and exclusions were checked by the table.
  PreparationOptions options;
  if (args.has("--motor-side")) options.side = Side::kMotor;
  options.periodic = args.has("--periodic");
  options.raw = args.has("--raw");
  const auto number = [&args](const char* option) {
    return parse_number(args.one(option), option);
  };
  if (args.has("--period")) options.period = number("--period");
  if (args.has("--harmonics")) options.harmonics = static_cast<int>(number("--harmonics"));
  if (args.has("--skip-periods")) options.skip_periods = static_cast<int>(number("--skip-periods"));
  if (args.has("--bandwidth")) options.bandwidth_hz = number("--bandwidth");
  if (args.has("--cutoff")) options.cutoff_hz = number("--cutoff");
  if (args.has("--torque-hold")) options.torque_hold = args.one("--torque-hold") == "zoh";
  if (args.has("--decimate")) {
    options.decimation = static_cast<int>(number("--decimate"));
    try {
      decimation_stages(*options.decimation);
    } catch (const std::invalid_argument& e) {
      throw UsageError{std::string("--decimate: ") + e.what()};
    }
  }
  return options;
}

}  // namespace modelgen::internal
