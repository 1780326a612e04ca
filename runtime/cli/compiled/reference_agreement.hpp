// The last check before modelid uses a loaded model in place of the numeric reference: the two
// agree on names and sizes and on the regressor and inverse dynamics at fixed states.
#pragma once

#include <string>

#include "modelgen/model/identification_model.hpp"

namespace modelgen::internal {

/// Empty when `loaded` and `reference` agree (values to 1e-9 relative, at three states spread
/// over +-pi); else what differs first.
std::string disagreement(const IdentificationModel& loaded, const IdentificationModel& reference);

}  // namespace modelgen::internal
