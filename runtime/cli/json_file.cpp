// JSON input files through nlohmann::json.

#include "runtime/cli/json_file.hpp"

#include <fstream>
#include <stdexcept>

namespace modelgen::internal {

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": error: cannot open the file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(path + ": error: not valid JSON: " + e.what());
  }
}

}  // namespace modelgen::internal
