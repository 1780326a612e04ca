// Shared libraries built by tests at test time with the build's own C++ compiler (the loadable
// generated models of modelgen/model/model_library.hpp and fake ones).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace modelgen::test {

/// What a compile gave.
struct Compiled {
  bool ok = false;
  double seconds = 0;  // wall time of the compiler run
  std::string log;     // the compiler's output
};

/// Compiles `sources` into the shared library `library` with the compiler that built the
/// project (CMAKE_CXX_COMPILER): -std=c++11 -shared -fPIC, then `flags` ("-O1 -Ifolder").
Compiled compile_shared_library(const std::vector<std::filesystem::path>& sources,
                                const std::filesystem::path& library, const std::string& flags);

}  // namespace modelgen::test
