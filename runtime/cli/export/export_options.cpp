// modelid export's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"

namespace modelgen::internal {

namespace {

CommandSpec make_export_spec() {
  CommandSpec spec{.program = "modelid",
                   .name = "export",
                   .summary =
                       "the identified inertials of an estimate of fit --physical written "
                       "into the description (URDF or YAML)"};
  spec.options = {
      {.name = "--robot",
       .value = "DESCRIPTION",
       .help = "the description file (.urdf or .yaml)",
       .required = true},
      {.name = "--params",
       .value = "EST.json",
       .help = "an estimate of fit --physical (it has a \"standard\" set)",
       .required = true},
      {.name = "-o",
       .value = "IDENTIFIED",
       .help = "the identified description, of the same "
               "kind as DESCRIPTION",
       .required = true},
  };
  const std::vector<OptionSpec> common = common_options();
  spec.options.insert(spec.options.end(), common.begin(), common.end());
  spec.details =
      "URDF: each moving link's <inertial> gets its identified body less the a-priori inertials\n"
      "of the links fixed to it, which keep theirs (when that is no physical body, the moving\n"
      "link takes it all and the fixed links' inertials are removed, with a warning); drive\n"
      "parameters have no URDF element and go into a comment. YAML: every standard parameter\n"
      "as its known: section.\n";
  return spec;
}

}  // namespace

const CommandSpec& export_spec() {
  static const CommandSpec spec = make_export_spec();
  return spec;
}

}  // namespace modelgen::internal
