// Durable writes, output-folder locks and leftovers of killed runs (file_system.hpp).

#include "generator/output/file_system.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "generator/output/file_set.hpp"

namespace modelgen::gen {

namespace test_hooks {
void (*after_step)(std::size_t step) = nullptr;
}

namespace detail {

namespace {
std::size_t steps = 0;
}

void step_done() {
  ++steps;
  if (test_hooks::after_step != nullptr) test_hooks::after_step(steps);
}

void reset_steps() { steps = 0; }

bool same_content(const fs::path& path, const std::string& content) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream existing;
  existing << in.rdbuf();
  return existing.str() == content;
}

std::string first_line(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::getline(in, line);
  return line;
}

std::string write_new_file(const fs::path& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return std::strerror(errno);
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? std::strerror(errno) : "nothing written";
      ::close(fd);
      return reason;
    }
    written += static_cast<std::size_t>(n);
  }
  // A rename or a swap commits the file: it must be on the disk before that.
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    return reason;
  }
  if (::close(fd) != 0) return std::strerror(errno);
  return "";
}

void sync_directory(const fs::path& directory) {
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

bool process_alive(long pid) {
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

DirectoryLock::DirectoryLock(const fs::path& directory) {
  for (;;) {
    fd_ = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) return;
    while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
    }
    struct stat locked {
    }, named{};
    if (::fstat(fd_, &locked) != 0 || ::stat(directory.c_str(), &named) != 0 ||
        (locked.st_ino == named.st_ino && locked.st_dev == named.st_dev)) {
      return;
    }
    ::close(fd_);  // swapped out while this run waited: lock the folder now there
  }
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);
}

bool DirectoryLock::free(const fs::path& directory) {
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool locked = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);
  return locked;
}

fs::path staging_folder(const fs::path& directory) {
  return directory.parent_path() /
         ("." + directory.filename().string() + ".modelgen-" + std::to_string(::getpid()));
}

void remove_leftovers(const fs::path& directory) {
  std::error_code ignored;
  // ".<name>.tmp-<pid>", ".<name>.old-<pid>" and ".modelgen-commit.tmp-<pid>" of dead runs.
  static const std::regex leftover(R"(^\..+\.(tmp|old)-([0-9]+)$)");
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(directory, ignored)) {
    const std::string name = entry.path().filename().string();
    std::smatch match;
    if (std::regex_match(name, match, leftover) && !process_alive(std::stol(match[2].str()))) {
      stale.push_back(entry.path());
    }
  }
  for (const fs::path& path : stale) fs::remove(path, ignored);
  // Staging folders of this output folder whose run is gone: a new set never swapped in, or
  // the old set a killed run had not removed yet; never the output folder itself.
  const std::string prefix = "." + directory.filename().string() + ".modelgen-";
  stale.clear();
  for (const auto& entry : fs::directory_iterator(directory.parent_path(), ignored)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size()) continue;
    const std::string pid = name.substr(prefix.size());
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    if (!fs::is_directory(fs::symlink_status(entry.path(), ignored))) continue;
    if (process_alive(std::stol(pid)) || !DirectoryLock::free(entry.path())) continue;
    stale.push_back(entry.path());
  }
  for (const fs::path& path : stale) {
    fs::remove_all(path, ignored);
    step_done();
  }
}

}  // namespace detail
}  // namespace modelgen::gen
