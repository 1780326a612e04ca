// All-or-nothing writing of generated files through temporaries and rename(2).

#include "generator/output/file_set.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "generator/description/diagnostics.hpp"

namespace modelgen::gen {

namespace fs = std::filesystem;

void FileSet::add(std::string name, std::string content) {
  files_.push_back({std::move(name), std::move(content)});
}

namespace {

bool same_content(const fs::path& path, const std::string& content) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream existing;
  existing << in.rdbuf();
  return existing.str() == content;
}

}  // namespace

void FileSet::write_to(const std::string& directory) const {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec || !fs::is_directory(directory)) {
    throw InputError({directory}, "cannot create the output directory: " + ec.message());
  }
  std::vector<std::pair<fs::path, fs::path>> renames;  // temporary -> destination
  auto remove_temporaries = [&renames] {
    std::error_code ignored;
    for (const auto& [temporary, destination] : renames) fs::remove(temporary, ignored);
  };
  for (const OutputFile& file : files_) {
    const fs::path destination = fs::path(directory) / file.name;
    if (same_content(destination, file.content)) continue;
    const fs::path temporary =
        fs::path(directory) / ("." + file.name + ".tmp-" + std::to_string(::getpid()));
    renames.emplace_back(temporary, destination);
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << file.content;
    out.close();
    if (!out) {
      remove_temporaries();
      throw InputError({temporary.string()}, "cannot write the file (disk full or no permission?)");
    }
  }
  for (const auto& [temporary, destination] : renames) {
    fs::rename(temporary, destination, ec);
    if (ec) {
      remove_temporaries();
      throw InputError({destination.string()}, "cannot replace the file: " + ec.message());
    }
  }
}

}  // namespace modelgen::gen
