// modelid export's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"

namespace modelgen::internal {

const CommandSpec& export_spec() {
  static const CommandSpec spec = [] {
    CommandSpec spec = modelid_command(
        "export",
        "the identified inertials of an estimate of fit --physical written into the description "
        "(URDF or YAML)",
        {robot_option("DESCRIPTION", "the description file (.urdf or .yaml)"),
         {.name = "--params",
          .value = "EST.json",
          .help = "an estimate of fit --physical (it has a \"standard\" set)",
          .required = true},
         {.name = "-o",
          .value = "IDENTIFIED",
          .help = "the identified description, of the same kind as DESCRIPTION",
          .required = true},
         {.name = "--force",
          .type = ValueType::kFlag,
          .help =
              "write links far from their a-priori values (mass off by over a factor 2, "
              "centre of mass over 10 cm away) or reaching outside their region (URDF shapes, "
              "YAML region, or guessed from the next joints), which export otherwise refuses"}});
    spec.details =
        "URDF: each moving link's <inertial> gets its identified body less the a-priori inertials\n"
        "of the links fixed to it, which keep theirs (when that is no physical body, the moving\n"
        "link takes it all and the fixed links' inertials are removed, with a warning); drive\n"
        "parameters have no URDF element and go into a comment. YAML: every standard parameter\n"
        "as its known: section.\n";
    return spec;
  }();
  return spec;
}

}  // namespace modelgen::internal
