// The file-system steps FileSet::write_to is made of, shared by its two ways of replacing a set
// (directory_swap.hpp, and the journal of file_set.cpp): durable writes, the lock of an output
// folder, the names of leftovers and the test hook that stops a run between two steps.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace modelgen::gen::detail {

namespace fs = std::filesystem;

/// Calls test_hooks::after_step with the count of the steps done since reset_steps(); every
/// change write_to makes to the file system (a file written or linked, a rename, a removal) is
/// one step.
void step_done();
void reset_steps();

/// Whether `path` holds exactly `content`.
bool same_content(const fs::path& path, const std::string& content);

/// The first line of `path` ("" if unreadable).
std::string first_line(const fs::path& path);

/// Writes `content` to a new file at `path` and flushes it to the disk; on failure, returns the
/// system's reason (strerror), so a full disk says "No space left on device".
std::string write_new_file(const fs::path& path, const std::string& content);

/// Flushes a directory's entries (the renames and links in it) to the disk.
void sync_directory(const fs::path& directory);

/// Whether a process of that id exists.
bool process_alive(long pid);

/// An exclusive lock on an output folder for a whole write: two runs into one folder take
/// turns. The folder a path names can change while a run waits (another run swapped a new set
/// in, directory_swap.hpp), so the lock is taken again until the folder locked is the one the
/// path names. Released when the object goes.
class DirectoryLock {
 public:
  explicit DirectoryLock(const fs::path& directory);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  /// Whether the lock is held: false when the folder cannot be opened.
  bool held() const { return fd_ >= 0; }
  /// Tries the lock without waiting: false when another process holds it.
  static bool free(const fs::path& directory);

 private:
  int fd_ = -1;
};

/// The sibling folder a run builds a new set in: ".<name>.modelgen-<pid>" beside the output
/// folder `directory` (a path without a trailing separator).
fs::path staging_folder(const fs::path& directory);

/// Removes what killed runs left: in `directory`, the journal's temporaries and backups of
/// processes that no longer exist; beside it, staging folders whose run is gone (no lock on
/// them, no process of their id).
void remove_leftovers(const fs::path& directory);

}  // namespace modelgen::gen::detail
