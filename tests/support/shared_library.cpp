// One compiler run through the shell, its output kept in a log beside the library.

#include "tests/support/shared_library.hpp"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace modelgen::test {

namespace {

std::string quote(const std::filesystem::path& path) {
  std::string text = "'";
  for (char c : path.string()) text += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return text + "'";
}

}  // namespace

Compiled compile_shared_library(const std::vector<std::filesystem::path>& sources,
                                const std::filesystem::path& library, const std::string& flags) {
  const std::filesystem::path log = library.string() + ".log";
  std::string command = quote(MODELGEN_TEST_CXX_COMPILER) + " -std=c++11 -shared -fPIC " + flags;
  for (const std::filesystem::path& source : sources) command += " " + quote(source);
  command += " -o " + quote(library) + " > " + quote(log) + " 2>&1";
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(command.c_str());
  Compiled result;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.ok = status == 0;
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  result.log = command + "\n" + text.str();
  return result;
}

}  // namespace modelgen::test
