// The atomic file write of modelid, and its refusal of stray positional arguments.

#include "runtime/cli/arguments.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace modelgen::internal {

void write_file(const std::string& path, const std::string& text) {
  // The temporary lives in the destination's folder so that the rename cannot cross file
  // systems; the process id keeps two concurrent runs apart.
  const std::string temporary = path + ".tmp-modelid-" + std::to_string(::getpid());
  std::ofstream out(temporary, std::ios::binary);
  const int open_errno = out ? 0 : errno;
  out << text;
  out.close();
  std::string reason;
  if (!out) {
    reason = open_errno != 0 ? std::strerror(open_errno) : "write failed";
  } else if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    reason = std::strerror(errno);
  }
  if (!reason.empty()) {
    std::remove(temporary.c_str());
    throw std::runtime_error(path + ": error: cannot write the file: " + reason +
                             " (no file was changed)");
  }
}

void reject_positional(const CommandLine& args) {
  if (args.positional.empty()) return;
  throw UsageError{"unexpected argument '" + args.positional.front() + "' for " + args.command +
                   " (each data file needs its own --data)"};
}

}  // namespace modelgen::internal
