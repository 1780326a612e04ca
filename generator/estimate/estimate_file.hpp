// The estimate file of `modelid fit -o` (EST.json) as `modelgen --params` reads it: the base
// parameter values by name, checked against the description being compiled, for the constants
// baked into the generated code. The JSON goes through the file formats' reader
// (modelgen/io/json_file.hpp), so every complaint names the file, line and column.
#pragma once

#include <string>
#include <vector>

#include "modelgen/model/error.hpp"

namespace modelgen::gen {

/// One entry of the estimate's "parameters" list and where it is written.
struct EstimateEntry {
  std::string name;  ///< a base parameter name, e.g. "ZZ1R"
  double value = 0;  ///< finite
  SourceLocation name_at, value_at;
};

struct EstimateFile {
  std::string path;       ///< as given on the command line
  std::string file_name;  ///< without directories: what the banner and the manifest show
  std::string sha256;     ///< of the file's bytes, 64 hex digits
  std::string method;     ///< the fit's "method" ("IDIM-WLS"); empty when the file has none
  std::vector<EstimateEntry> entries;  ///< in file order, each name once
  SourceLocation parameters_at;        ///< of the "parameters" key
  /// What is legal but suspicious, as printed: "PATH: warning: ...".
  std::vector<std::string> warnings;
};

/// Reads the estimate at `path` for the description `description_path` whose bytes hash to
/// `description_sha256`. Throws InputError naming the file, line and column when the file
/// cannot be read or is not JSON, when its "description_sha256" is another description's (an
/// estimate of another robot must not become its constants), when it has no "parameters" list,
/// and for an entry without a name, a name given twice or a value that is not a finite number
/// (modelid writes non-finite values as null). A file without "description_sha256" (written by
/// hand) is read with a warning.
EstimateFile read_estimate_file(const std::string& path, const std::string& description_path,
                                const std::string& description_sha256);

/// The values of `estimate` in the order of `base_names`, the base parameters of the model
/// `robot`. Throws InputError at the entry of a name the model does not have, and at the
/// "parameters" key when base parameters are missing (all of them named).
std::vector<double> base_values(const EstimateFile& estimate,
                                const std::vector<std::string>& base_names,
                                const std::string& robot);

/// Throws InputError at the first value beyond the range of a float: float entry points hold
/// the constants as float literals.
void check_fits_float(const EstimateFile& estimate);

}  // namespace modelgen::gen
