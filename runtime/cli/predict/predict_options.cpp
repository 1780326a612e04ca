// modelid predict's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

namespace {

CommandSpec make_predict_spec() {
  CommandSpec spec{.program = "modelid",
                   .name = "predict",
                   .summary =
                       "torques of an estimate along recorded trajectories, and their "
                       "errors per axis"};
  spec.options = {
      {.name = "--robot",
       .value = "ROBOT",
       .help = "the description file or shipped model",
       .required = true},
      {.name = "--params",
       .value = "EST.json",
       .help = "an estimate of fit -o, or a {\"base\": ...} or {\"standard\": ...} file",
       .required = true},
      {.name = "--data",
       .value = "FILE",
       .help = "a CSV record (one experiment per file)",
       .repeatable = true,
       .required = true},
      {.name = "-o", .value = "PRED.csv", .help = "write measured and predicted torques"},
      {.name = "--plot", .value = "DIR", .help = "write the torques as CSV and SVG into DIR"},
      {.name = "--decimated",
       .type = ValueType::kFlag,
       .help = "compare where the fit compared: after the parallel decimation's filter"},
  };
  add_data_options(spec);
  const std::vector<OptionSpec> common = common_options();
  spec.options.insert(spec.options.end(), common.begin(), common.end());
  spec.details =
      "The data options default to those the fit recorded in EST.json (\"data_options\"), so\n"
      "that predict prepares the data as the fit did.\n";
  return spec;
}

}  // namespace

const CommandSpec& predict_spec() {
  static const CommandSpec spec = make_predict_spec();
  return spec;
}

}  // namespace modelgen::internal
