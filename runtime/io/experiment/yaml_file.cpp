// Reading an experiment's YAML file whole, with the checks of a description file.

#include "runtime/io/experiment/yaml_file.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "modelgen/model/error.hpp"

namespace modelgen::io {

namespace {

// A controller is a few hundred bytes, a trajectory of 1000 harmonics on 32 joints about 2 MB.
constexpr std::uintmax_t kMaxExperimentYamlBytes = std::uintmax_t{16} << 20;

std::string read_whole(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError({path}, "is a directory, not " + what);
  }
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec);
      !ec && size > kMaxExperimentYamlBytes) {
    throw InputError({path}, "the file has " + std::to_string(size) +
                                 " bytes, beyond the limit of " +
                                 std::to_string(kMaxExperimentYamlBytes) + " bytes for " + what);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path}, "cannot open the file (does it exist and is it readable?)");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError({path}, "error while reading the file");
  return bytes.str();
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path, const std::string& what) {
  const std::string text = read_whole(path, what);
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError({path, e.mark.line + 1, e.mark.column + 1}, e.msg);
  }
}

}  // namespace modelgen::io
