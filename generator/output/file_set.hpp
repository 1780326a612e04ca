// Generated files held in memory and written all-or-nothing. When the output folder holds only
// this set's files, the new set is built beside it and swapped in with one rename, so the
// folder shows the old set or the new one whatever happens (directory_swap.hpp). Beside other
// files (the user's own, which stay), every file goes to a temporary beside its destination
// first, a journal then commits the set and the temporaries are renamed into place: a failed
// run never leaves a half-written or mixed set, and a run killed during the renames is
// completed by the next run in the same folder (recover_output_directory).
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
  /// --functions): removed from the directory when the new set is in place, not before, and
  /// only if it is this generator's own (set_owner).
  void retire(std::string name);
  /// Files whose first line contains `generated_mark` were written by this generator; of those,
  /// only the ones whose first line also contains `owner_mark` belong to this set's input. An
  /// existing file of the generator that belongs to another input is neither replaced (write_to
  /// throws InputError naming it, before anything is written) nor retired. Without a call, every
  /// file may be replaced and retired files are removed whatever they hold.
  void set_owner(std::string generated_mark, std::string owner_mark);
  const std::vector<OutputFile>& files() const { return files_; }
  const std::vector<std::string>& retired() const { return retired_; }

  /// Writes every file into `directory` (created if missing). Files whose content is already
  /// identical are left untouched (same inode and modification time), so build systems see no
  /// change; files of the folder that are not this set's (not generated from its input) stay.
  /// When the folder holds nothing but this set's files (its files, retired ones, files
  /// generated from its input) or does not exist, the set is built in a hidden sibling folder
  /// ".<name>.modelgen-<pid>" and swapped in at once (the folder keeps its permissions, owner
  /// and group; through a symbolic link, the folder it points to is replaced); otherwise, or
  /// where the file system cannot swap folders, file by file under a journal. First does what
  /// recover_output_directory does. Throws InputError naming the path and the system's reason
  /// (strerror) on failure, after restoring the old files and removing every temporary it wrote.
  void write_to(const std::string& directory) const;

 private:
  std::vector<OutputFile> files_;
  std::vector<std::string> retired_;
  std::string generated_mark_, owner_mark_;
};

/// Brings an output folder that a killed write_to left mixed back to one complete set: completes
/// the set its journal committed, removes the temporaries and sibling folders of runs that no
/// longer exist. modelgen calls it before it reads its input, so that a run that fails
/// afterwards repairs the folder too. Does nothing when `directory` is not a folder; never
/// throws.
void recover_output_directory(const std::string& directory);

namespace test_hooks {
/// Called after each rename of the journal's way of write_to with the number done so far;
/// tests set it to stop the process between renames, as a kill would. Null in the programs.
extern void (*after_rename)(std::size_t renamed);
/// Called after every change write_to or recover_output_directory makes to the file system (a
/// file written or linked, a rename, a removal) with the number made since the call began.
extern void (*after_step)(std::size_t step);
}  // namespace test_hooks

}  // namespace modelgen::gen
