// Cache entries are files NAME-KEY.so (the library), .log (the last build's compiler output),
// .key (the key's text, for a curious user) and .lock (flock), all in one folder. A build happens
// in NAME-KEY.build-PID/ and only its finished library is renamed onto NAME-KEY.so.

#include "runtime/cli/compiled/model_cache.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "modelgen/model/generated_format.hpp"
#include "modelgen/model/loadable_model.h"
#include "modelgen/model/sha256.hpp"
#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/common/version.hpp"
#include "runtime/cli/compiled/model_build.hpp"
#include "runtime/cli/compiled/reference_agreement.hpp"
#include "runtime/cli/compiled/subprocess.hpp"

namespace modelgen::internal {

namespace fs = std::filesystem;

namespace {

constexpr const char* kNumericCost =
    "using the numeric reference instead (the same model, about 100x slower in closed-loop "
    "fits and simulation)";

void note(const std::string& text) { std::cerr << "modelid: note: " << text << "\n"; }

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? std::string(value) : std::string();
}

// "path size mtime" of a program file: a rebuilt modelgen makes new entries.
std::string program_identity(const fs::path& program) {
  std::error_code error;
  const auto size = fs::file_size(program, error);
  if (error) return program.string();
  const auto time = fs::last_write_time(program, error).time_since_epoch().count();
  return program.string() + " " + std::to_string(size) + " " + std::to_string(time);
}

// The held exclusive lock of an entry, released when the process ends at the latest.
class EntryLock {
 public:
  explicit EntryLock(const fs::path& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT, 0644)) {
    if (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~EntryLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the flock
  }
  EntryLock(const EntryLock&) = delete;
  EntryLock& operator=(const EntryLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_;
};

// The library at `path`, loaded and checked against the description; nullopt with `why` set.
std::optional<ModelLibrary> open_checked(const fs::path& path,
                                         const DescriptionToCompile& description,
                                         std::string& why) {
  try {
    ModelLibrary library =
        ModelLibrary::open(path.string(), description.reference->description_sha256());
    why = disagreement(*library.identification_model(), *description.reference);
    if (why.empty()) return library;
  } catch (const ModelLibraryError& error) {
    why = error.what();
  }
  return std::nullopt;
}

// Builds the entry's library in a folder of its own and renames it onto `library`.
std::string build_entry(const DescriptionToCompile& description, const fs::path& library,
                        const fs::path& log) {
  const fs::path folder = library.string().substr(0, library.string().size() - 3) + ".build-" +
                          std::to_string(::getpid());
  std::error_code error;
  fs::remove_all(folder, error);
  if (!fs::create_directories(folder, error)) return "cannot create " + folder.string();
  std::ofstream(log, std::ios::trunc) << "# " << cache_key_text(description) << "\n";
  progress_message("compiling the model of " + description.path.string() +
                   " for this machine (first use; kept in " + library.parent_path().string() +
                   ") ...");
  const ModelBuild build{description.path, description.options, folder, folder / "model.so", log};
  const BuildOutcome outcome = build_model_library(build);
  if (outcome.ok()) fs::rename(build.library, library, error);
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  if (!outcome.ok()) return outcome.failure + "; its output is in " + log.string();
  if (error) return "cannot write " + library.string() + ": " + error.message();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", outcome.seconds);
  progress_message("compiled " + std::to_string(outcome.compiled_files) + " generated files (" +
                   kLoadableCompileFlags + ") in " + seconds + " s");
  return "";
}

}  // namespace

fs::path model_cache_folder() {
  if (const std::string dir = environment("MODELGEN_CACHE_DIR"); !dir.empty()) return dir;
  if (const std::string dir = environment("XDG_CACHE_HOME"); !dir.empty()) {
    return fs::path(dir) / "modelgen";
  }
  if (const std::string home = environment("HOME"); !home.empty()) {
    return fs::path(home) / ".cache" / "modelgen";
  }
  return {};
}

std::string cache_key_text(const DescriptionToCompile& description) {
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.17g", description.options.angle_tolerance);
  const std::string compiler = host_compiler();
  return "description " + description.reference->description_sha256() + "\nangle-tolerance " +
         tolerance + "\nname " + description.options.name + "\nbase " +
         description.options.base_link + "\ntip " + description.options.tip_link +
         "\nmimic-as-joint " + (description.options.mimic_as_joint ? "yes" : "no") + "\nmodelid " +
         kModelidVersion + " format " + std::to_string(kGeneratedFormatVersion) + " abi " +
         std::to_string(MODELGEN_LOADABLE_ABI_VERSION) + "\nmodelgen " +
         program_identity(generator_program()) + "\ncompiler " + compiler + " (" +
         first_output_line(compiler + " --version") + ")\nflags " + kLoadableCompileFlags + "\n";
}

std::optional<ModelLibrary> compiled_model(const DescriptionToCompile& description) {
  const fs::path folder = model_cache_folder();
  if (folder.empty()) {
    note("no cache folder (set MODELGEN_CACHE_DIR or HOME); " + std::string(kNumericCost));
    return std::nullopt;
  }
  const std::string key_text = cache_key_text(description);
  const fs::path entry =
      folder / (description.reference->name() + "-" + sha256_hex(key_text).substr(0, 24));
  const fs::path library = entry.string() + ".so", log = entry.string() + ".log";
  std::string why;
  std::error_code error;
  if (fs::exists(library, error)) {
    if (auto loaded = open_checked(library, description, why)) return loaded;
  }
  fs::create_directories(folder, error);
  EntryLock lock(entry.string() + ".lock");
  if (!lock.held()) {
    note("cannot write the model cache " + folder.string() + "; " + kNumericCost);
    return std::nullopt;
  }
  // Another modelid may have built it while this one waited for the lock.
  if (fs::exists(library, error)) {
    if (auto loaded = open_checked(library, description, why)) return loaded;
    note("rebuilding " + library.string() + ": " + why);
  }
  std::ofstream(entry.string() + ".key", std::ios::trunc) << key_text;
  if (const std::string failure = build_entry(description, library, log); !failure.empty()) {
    note("could not compile the model of " + description.path.string() + ": " + failure + "; " +
         kNumericCost);
    return std::nullopt;
  }
  if (auto loaded = open_checked(library, description, why)) return loaded;
  note("the compiled model " + library.string() + " cannot be used: " + why + "; " + kNumericCost);
  return std::nullopt;
}

}  // namespace modelgen::internal
