// Option parsing and the atomic file write of modelid.

#include "runtime/cli/arguments.hpp"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace modelgen::internal {

const std::string& Arguments::one(const std::string& name) const {
  auto found = options.find(name);
  if (found == options.end()) throw UsageError{command + " needs " + name};
  if (found->second.size() != 1) throw UsageError{name + " given more than once"};
  return found->second.front();
}

const std::vector<std::string>& Arguments::all(const std::string& name) const {
  static const std::vector<std::string> kNone;
  auto found = options.find(name);
  return found == options.end() ? kNone : found->second;
}

Arguments parse_arguments(int argc, char** argv, const std::map<std::string, OptionKind>& allowed) {
  Arguments args;
  args.command = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 1 && arg[0] == '-') {
      auto found = allowed.find(arg);
      if (found == allowed.end()) {
        throw UsageError{"unknown option '" + arg + "' for " + args.command};
      }
      std::vector<std::string>& values = args.options[arg];
      if (found->second == OptionKind::kFlag) {
        values.emplace_back();
      } else {
        if (i + 1 >= argc) throw UsageError{arg + " needs a value"};
        values.push_back(argv[++i]);
      }
      if (found->second != OptionKind::kRepeated && values.size() > 1) {
        throw UsageError{arg + " given twice"};
      }
    } else {
      args.positional.push_back(arg);
    }
  }
  return args;
}

double parse_number(const std::string& text, const std::string& option) {
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw UsageError{option + " must be a number, not '" + text + "'"};
  }
  return value;
}

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

void reject_positional(const Arguments& args) {
  if (args.positional.empty()) return;
  throw UsageError{"unexpected argument '" + args.positional.front() + "' for " + args.command +
                   " (each data file needs its own --data)"};
}

}  // namespace modelgen::internal
