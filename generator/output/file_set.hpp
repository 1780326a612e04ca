// Generated files held in memory and written all-or-nothing: every file goes to a temporary
// beside its destination first, a journal then commits the set and the temporaries are
// renamed into place, so a failed run never leaves a half-written or mixed set of files, and a
// run killed during the renames is completed by the next run in the same folder.
#pragma once

#include <cstddef>
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
  /// A file of an earlier run that this set no longer has (a function left out by
  /// --functions): removed from the directory when the new set is in place, not before.
  void retire(std::string name);
  const std::vector<OutputFile>& files() const { return files_; }
  const std::vector<std::string>& retired() const { return retired_; }

  /// Writes every file into `directory` (created if missing). Files whose content is already
  /// identical are left untouched, so build systems see no change. First completes a run that
  /// was killed after committing its set in `directory` (its journal `.modelgen-commit`) and
  /// removes hidden temporaries of runs that no longer exist. Throws InputError naming the
  /// path and the system's reason (strerror) on failure, after restoring the old files and
  /// removing every temporary it wrote.
  void write_to(const std::string& directory) const;

 private:
  std::vector<OutputFile> files_;
  std::vector<std::string> retired_;
};

namespace test_hooks {
/// Called after each rename of write_to with the number done so far; tests set it to stop the
/// process between renames, as a kill would. Null in the programs.
extern void (*after_rename)(std::size_t renamed);
}  // namespace test_hooks

}  // namespace modelgen::gen
