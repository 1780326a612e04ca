// All-or-nothing writing of generated files through temporaries and rename(2).

#include "generator/output/file_set.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "modelgen/model/error.hpp"

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
    throw InputError({directory}, "cannot create the output directory" +
                                      (ec ? ": " + ec.message() : std::string()));
  }
  // Refuse before touching anything if a destination is something other than a file.
  for (const OutputFile& file : files_) {
    const fs::path destination = fs::path(directory) / file.name;
    if (fs::exists(fs::symlink_status(destination)) && !fs::is_regular_file(destination)) {
      throw InputError({destination.string()}, "exists and is not a regular file; not replaced");
    }
  }
  struct Replacement {
    fs::path temporary, destination, backup;
    bool backed_up = false, replaced = false;
  };
  std::vector<Replacement> replacements;
  const std::string suffix = std::to_string(::getpid());
  // Undo everything done so far: new files out, old files back, temporaries gone.
  auto roll_back = [&replacements] {
    std::error_code ignored;
    for (auto it = replacements.rbegin(); it != replacements.rend(); ++it) {
      if (it->replaced) fs::remove(it->destination, ignored);
      if (it->backed_up) fs::rename(it->backup, it->destination, ignored);
      fs::remove(it->temporary, ignored);
    }
  };
  for (const OutputFile& file : files_) {
    const fs::path destination = fs::path(directory) / file.name;
    if (same_content(destination, file.content)) continue;
    Replacement r;
    r.destination = destination;
    r.temporary = fs::path(directory) / ("." + file.name + ".tmp-" + suffix);
    r.backup = fs::path(directory) / ("." + file.name + ".old-" + suffix);
    replacements.push_back(r);
    std::ofstream out(r.temporary, std::ios::binary | std::ios::trunc);
    out << file.content;
    out.close();
    if (!out) {
      roll_back();
      throw InputError({r.temporary.string()}, "cannot write the file (disk full or no permission?)");
    }
  }
  // Every new file is complete on disk; now swap them in, keeping the old ones until all
  // swaps succeeded so that a failure can restore the previous set exactly.
  for (Replacement& r : replacements) {
    if (fs::exists(r.destination)) {
      fs::rename(r.destination, r.backup, ec);
      if (ec) {
        roll_back();
        throw InputError({r.destination.string()}, "cannot replace the file: " + ec.message());
      }
      r.backed_up = true;
    }
    fs::rename(r.temporary, r.destination, ec);
    if (ec) {
      roll_back();
      throw InputError({r.destination.string()}, "cannot replace the file: " + ec.message());
    }
    r.replaced = true;
  }
  std::error_code ignored;
  for (const Replacement& r : replacements) {
    if (r.backed_up) fs::remove(r.backup, ignored);
  }
}

}  // namespace modelgen::gen
