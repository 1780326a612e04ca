// JSON input files of modelid (parameters, estimates, a-priori values), read the same way.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace modelgen::internal {

/// The JSON document in `path`. Throws std::runtime_error "PATH: error: ..." when the file
/// cannot be opened or is not valid JSON (the parser's message gives line and column).
nlohmann::json read_json_file(const std::string& path);

}  // namespace modelgen::internal
