// --q-limit JOINT=LO,HI (design, check-trajectory, simulate): a position range given on the
// command line for a joint whose description has none (a URDF continuous joint) or a narrower
// one than the description's.
#pragma once

#include "modelgen/model/command_line.hpp"
#include "modelgen/model/option_table.hpp"
#include "runtime/cli/common/model_source.hpp"

namespace modelgen::internal {

/// The option's table entry, the same in the three commands.
OptionSpec q_limit_option_spec();

/// Applies every --q-limit JOINT=LO,HI to `source.limits`: JOINT is a moving joint's name in
/// the description or its 1-based number; LO < HI in rad (m for a prismatic joint). The joint's
/// q range becomes [LO, HI] and it is no longer taken as continuous; its dq, ddq and effort
/// limits stay. A model without a description gets a limit entry per joint first. UsageError
/// naming --q-limit for a value without '=', an unknown joint (with did-you-mean), bounds that
/// are not two numbers with LO < HI, or a joint given twice. No-op without the option.
void apply_q_limit_option(const CommandLine& args, ModelSource& source);

}  // namespace modelgen::internal
