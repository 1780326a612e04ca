// How long estimation steps report their progress to the caller, who decides what to show.
#pragma once

#include <functional>

namespace modelgen {

/// Progress of a long computation: `fraction` of the work done, increasing from 0 to 1.
using ProgressCallback = std::function<void(double fraction)>;

}  // namespace modelgen
