// The atomic file write of modelid.

#include "runtime/cli/common/arguments.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace modelgen::internal {

void write_file(const std::string& path, const std::string& text) {
  // The temporary lives in the destination's folder so that the rename cannot cross file
  // systems; the process id keeps two concurrent runs apart. POSIX calls rather than a stream,
  // so a failure carries the system's reason ("No space left on device").
  const std::string temporary = path + ".tmp-modelid-" + std::to_string(::getpid());
  std::string reason;
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    reason = std::strerror(errno);
  } else {
    std::size_t written = 0;
    while (written < text.size()) {
      const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        reason = n < 0 ? std::strerror(errno) : "nothing written";
        break;
      }
      written += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0 && reason.empty()) reason = std::strerror(errno);
    if (reason.empty() && std::rename(temporary.c_str(), path.c_str()) != 0) {
      reason = std::strerror(errno);
    }
  }
  if (!reason.empty()) {
    std::remove(temporary.c_str());
    throw std::runtime_error(path + ": error: cannot write the file: " + reason +
                             " (no file was changed)");
  }
}

}  // namespace modelgen::internal
