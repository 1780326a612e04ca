// modelgen --loadable into BUILD/gen, then one compiler run per listed file (as many at once
// as there are cores) and one link.

#include "runtime/cli/compiled/model_build.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "runtime/cli/compiled/subprocess.hpp"

namespace modelgen::internal {

namespace fs = std::filesystem;

namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string generator_command(const ModelBuild& build, const fs::path& output) {
  std::string command = shell_quoted(generator_program()) + " " +
                        shell_quoted(fs::absolute(build.description)) + " -o " +
                        shell_quoted(output) + " --loadable --scalar double --angle-tolerance " +
                        number_text(build.options.angle_tolerance);
  if (!build.options.name.empty()) command += " --name " + shell_quoted(build.options.name);
  if (!build.options.base_link.empty()) {
    command += " --base " + shell_quoted(build.options.base_link);
  }
  if (!build.options.tip_link.empty()) command += " --tip " + shell_quoted(build.options.tip_link);
  if (build.options.mimic_as_joint) command += " --mimic-as-joint";
  return command;
}

// The manifest's "loadable_sources", as paths in `output`; empty when it lists none.
std::vector<fs::path> loadable_sources(const fs::path& output) {
  for (const fs::directory_entry& entry : fs::directory_iterator(output)) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
    if (!manifest.is_object() || !manifest.contains("loadable_sources")) continue;
    std::vector<fs::path> sources;
    for (const nlohmann::json& name : manifest["loadable_sources"]) {
      if (name.is_string()) sources.push_back(output / name.get<std::string>());
    }
    return sources;
  }
  return {};
}

std::string compiler_failure(const ChildExit& exit) {
  if (exit.status == 127) return "the compiler '" + host_compiler() + "' was not found (set CXX)";
  return "the compiler '" + host_compiler() + "' exited with status " + std::to_string(exit.status);
}

// Compiles every source to an object beside it, then links them into build.library.
std::string compile_and_link(const ModelBuild& build, const std::vector<fs::path>& sources) {
  std::vector<std::string> compiles;
  std::string link = host_compiler() + " -shared -o " + shell_quoted(build.library);
  for (const fs::path& source : sources) {
    const fs::path object = source.string() + ".o";
    compiles.push_back(host_compiler() + " " + kLoadableCompileFlags + " -c " +
                       shell_quoted(source) + " -o " + shell_quoted(object));
    link += " " + shell_quoted(object);
  }
  const int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (const ChildExit& exit : run_shell_commands(compiles, build.log, jobs)) {
    if (!exit.ok()) return compiler_failure(exit);
  }
  const ChildExit linked = run_shell_commands({link}, build.log, 1).front();
  return linked.ok() ? "" : compiler_failure(linked);
}

}  // namespace

std::string host_compiler() {
  const char* cxx = std::getenv("CXX");
  return cxx != nullptr && *cxx != '\0' ? std::string(cxx) : std::string("c++");
}

fs::path generator_program() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path sibling = self.parent_path() / "modelgen";
    if (fs::exists(sibling, error)) return sibling;
  }
  return "modelgen";
}

BuildOutcome build_model_library(const ModelBuild& build) {
  const auto start = std::chrono::steady_clock::now();
  BuildOutcome outcome;
  const fs::path output = build.folder / "gen";
  const ChildExit generated =
      run_shell_commands({generator_command(build, output)}, build.log, 1).front();
  if (!generated.ok()) {
    outcome.failure = generated.status == 127
                          ? "modelgen was not found beside modelid nor on PATH"
                          : "modelgen exited with status " + std::to_string(generated.status);
    return outcome;
  }
  const std::vector<fs::path> sources = loadable_sources(output);
  if (sources.empty()) {
    outcome.failure = "modelgen's manifest lists no loadable sources";
    return outcome;
  }
  outcome.failure = compile_and_link(build, sources);
  outcome.compiled_files = static_cast<int>(sources.size());
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace modelgen::internal
