// A generator file reaching into modelid: the layering check must refuse it
// (tests/architecture/layers.cmake, run on this folder, is expected to fail).
#include "runtime/cli/common/commands.hpp"
