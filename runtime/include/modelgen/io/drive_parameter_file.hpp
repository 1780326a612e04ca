// Drive-model parameter files: {"name": value, ...} over ml_param_names() (link inertial
// parameters XXj..Mj, JMj, Rvj, Rcj, Rzj, load_m, load_cx, ...), read by modelid for
// `fit --method ml --known` (a-priori values) and `simulate --drive` (the simulated truth).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace modelgen::io {

/// The values in `path`; every name must be one of `names`. Throws InputError naming
/// the file, line and column and the problem (not JSON, not an object, an unknown name, a
/// value that is not a finite number).
std::map<std::string, double> read_drive_parameter_values(const std::string& path,
                                                          const std::vector<std::string>& names);

}  // namespace modelgen::io
