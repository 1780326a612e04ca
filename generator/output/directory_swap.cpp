// The whole-folder replacement of directory_swap.hpp: build beside, exchange, remove the old.

#include "generator/output/directory_swap.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "generator/output/file_system.hpp"
#include "modelgen/model/error.hpp"

namespace modelgen::gen::detail {

namespace {

// The sibling folder while it is being built: removed on every way out but success, and locked
// for its whole life, so that a run waiting for the output folder (DirectoryLock) waits for this
// one to finish with the folder it swaps in, and leftovers of live runs are told apart.
class Staging {
 public:
  explicit Staging(fs::path path) : path_(std::move(path)) {}
  ~Staging() {
    if (created_ && !kept_) {
      std::error_code ignored;
      fs::remove_all(path_, ignored);
    }
    if (fd_ >= 0) ::close(fd_);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;

  bool create() {
    // A folder of this name is a leftover of a killed process that had this process's id.
    std::error_code ignored;
    if (::mkdir(path_.c_str(), 0777) != 0 &&
        (errno != EEXIST || fs::remove_all(path_, ignored) == 0 ||
         ::mkdir(path_.c_str(), 0777) != 0)) {
      return false;
    }
    created_ = true;
    step_done();
    fd_ = ::open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    return fd_ >= 0 && ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
  }
  int fd() const { return fd_; }
  const fs::path& path() const { return path_; }
  void keep() { kept_ = true; }

 private:
  fs::path path_;
  int fd_ = -1;
  bool created_ = false, kept_ = false;
};

// Extended attributes other than the security module's label (access control lists, user
// attributes): a new folder would not have them, so such a folder is not swapped.
bool has_copyable_attributes(const fs::path& directory) {
  const ssize_t size = ::listxattr(directory.c_str(), nullptr, 0);
  if (size <= 0) return size < 0 && errno != ENOTSUP;
  std::vector<char> names(static_cast<std::size_t>(size));
  const ssize_t got = ::listxattr(directory.c_str(), names.data(), names.size());
  if (got < 0) return true;
  for (std::size_t at = 0; at < static_cast<std::size_t>(got);) {
    const std::string name(names.data() + at);
    if (name.rfind("security.", 0) != 0) return true;
    at += name.size() + 1;
  }
  return false;
}

// The new folder takes the old one's permissions, owner and group, before any file goes in
// (files created in a set-group-ID folder take its group). False when that is not possible.
bool copy_folder_metadata(const fs::path& old_folder, const Staging& staging) {
  struct stat old {
  }, made{};
  if (::stat(old_folder.c_str(), &old) != 0 || ::fstat(staging.fd(), &made) != 0) return false;
  if (has_copyable_attributes(old_folder)) return false;
  if ((old.st_uid != made.st_uid || old.st_gid != made.st_gid) &&
      ::fchown(staging.fd(), old.st_uid, old.st_gid) != 0) {
    return false;
  }
  return ::fchmod(staging.fd(), old.st_mode & 07777) == 0;
}

// The old set, now in the sibling folder, goes; a name that appeared in the output folder while
// the new set was built is moved back beside it (unless the new set has that name, as a rename
// over it would have replaced it).
void remove_old_set(const fs::path& old_set, const fs::path& directory,
                    const std::vector<std::string>& old_names) {
  std::error_code ignored;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(old_set, ignored)) {
    names.push_back(entry.path().filename().string());
  }
  for (const std::string& name : names) {
    if (std::find(old_names.begin(), old_names.end(), name) != old_names.end()) {
      fs::remove(old_set / name, ignored);
      step_done();
    } else {
      ::renameat2(AT_FDCWD, (old_set / name).c_str(), AT_FDCWD, (directory / name).c_str(),
                  RENAME_NOREPLACE);
    }
  }
  fs::remove_all(old_set, ignored);
  step_done();
}

// Errors of renameat2 that say the exchange cannot be done here rather than that it failed.
bool unsupported(int error) {
  return error == EINVAL || error == ENOSYS || error == EXDEV || error == EBUSY || error == EPERM ||
         error == ENOTSUP || error == EACCES || error == EROFS;
}

}  // namespace

SwapResult swap_in_directory(const SwapPlan& plan) {
  const fs::path& directory = plan.directory;
  std::error_code ec;
  const bool existed = fs::exists(fs::symlink_status(directory, ec));
  // A read-only output folder stays as it is (the journal's way then reports the error).
  if (existed && ::access(directory.c_str(), W_OK) != 0) return SwapResult::kUnsupported;
  Staging staging(staging_folder(directory));
  if (!staging.create()) return SwapResult::kUnsupported;
  if (existed && !copy_folder_metadata(directory, staging)) return SwapResult::kUnsupported;
  for (const std::string& name : plan.linked) {
    if (::link((directory / name).c_str(), (staging.path() / name).c_str()) != 0) {
      return SwapResult::kUnsupported;  // a file system without hard links
    }
    step_done();
  }
  for (const OutputFile* file : plan.written) {
    const std::string reason = write_new_file(staging.path() / file->name, file->content);
    if (!reason.empty()) {
      throw InputError({(directory / file->name).string()},
                       "cannot write the file: " + reason + " (no file was changed)");
    }
    step_done();
  }
  sync_directory(staging.path());
  // The commit: one rename, so the folder's name gives the old set or the new one.
  const int done = existed ? ::renameat2(AT_FDCWD, staging.path().c_str(), AT_FDCWD,
                                         directory.c_str(), RENAME_EXCHANGE)
                           : ::rename(staging.path().c_str(), directory.c_str());
  if (done != 0) {
    const int error = errno;
    // Another run made the folder in the meantime, or it cannot be done here.
    if (!existed || unsupported(error)) return SwapResult::kUnsupported;
    throw InputError({directory.string()},
                     "cannot replace the folder: " + std::string(std::strerror(error)) +
                         " (no file was changed)");
  }
  staging.keep();
  step_done();
  sync_directory(directory.parent_path());
  if (existed) remove_old_set(staging.path(), directory, plan.old_names);
  return SwapResult::kDone;
}

}  // namespace modelgen::gen::detail
