// What every fuzz target shares: the input bytes as a file (the loaders read paths, and the
// extension picks the loader), and the rule that decides what is a finding. A loader may refuse
// its input only with modelgen::Error (a positioned message, exit 1 in the programs); any other
// exception would reach the user as "internal error" (exit 3) and is reported as a crash, as
// AddressSanitizer and UndefinedBehaviorSanitizer report theirs.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "modelgen/model/error.hpp"

namespace modelgen::fuzz {

/// Writes `data` to a file of this process with the given extension and returns its path.
inline std::string input_file(const std::uint8_t* data, std::size_t size, const char* extension) {
  const std::string path =
      "/tmp/modelgen_fuzz_" + std::to_string(::getpid()) + "." + std::string(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// Runs `load`; a modelgen::Error is a refusal (fine), any other exception aborts the run.
template <typename Load>
void expect_only_input_errors(Load&& load) {
  try {
    load();
  } catch (const modelgen::Error&) {
    // A refusal with a message: what bad input must get.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: not an input error (would be exit 3): %s\n", e.what());
    std::abort();
  }
}

}  // namespace modelgen::fuzz
