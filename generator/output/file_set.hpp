// Generated files held in memory and written all-or-nothing: every file goes to a temporary
// beside its destination first, and only when all are written are they renamed into place,
// so a failed run never leaves a half-written or mixed set of files.
#pragma once

#include <string>
#include <vector>

namespace modelgen::gen {

struct OutputFile {
  std::string name;     ///< file name inside the output directory
  std::string content;
};

class FileSet {
 public:
  void add(std::string name, std::string content);
  const std::vector<OutputFile>& files() const { return files_; }

  /// Writes every file into `directory` (created if missing). Files whose content is already
  /// identical are left untouched, so build systems see no change. Throws InputError naming
  /// the path on failure, after removing any temporary it wrote.
  void write_to(const std::string& directory) const;

 private:
  std::vector<OutputFile> files_;
};

}  // namespace modelgen::gen
