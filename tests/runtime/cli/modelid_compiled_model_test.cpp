// modelid on a description it does not ship (tests/model/loadable/puma560.yaml): its model is
// generated, compiled and cached the first time a command evaluates it, loaded from the cache
// after, rebuilt when the entry is corrupted or belongs to another description, and replaced by
// the numeric reference, with one note, when the cache cannot be written, no compiler runs or
// --no-compile asks. The runs give --progress, which shows the compilation. Each test has a
// cache folder of its own (MODELGEN_CACHE_DIR); the loaded model's values against the numeric
// reference are tests/model/loaded_model_test.cpp's.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_runner.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDescription = "tests/model/loadable/puma560.yaml";

// Sets an environment variable for the test's modelid runs and restores it after.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnvironment() {
    if (old_.empty()) {
      ::unsetenv(name_);
    } else {
      ::setenv(name_, old_.c_str(), 1);
    }
  }

 private:
  const char* name_;
  std::string old_;
};

std::vector<fs::path> files_with_extension(const fs::path& folder, const std::string& extension) {
  std::vector<fs::path> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    if (entry.path().extension() == extension) found.push_back(entry.path());
  }
  return found;
}

// A designed trajectory without its comment lines (they repeat the command line).
std::string trajectory_values(const fs::path& path) {
  std::istringstream in(test::read_text(path));
  std::string values;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) != 0) values += line + "\n";
  }
  return values;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class CompiledModel : public testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::test_folder("compiled");
    cache_ = folder_ / "cache";
  }

  // A short design on `description`: it evaluates the model (the regressor over a period).
  std::string design_arguments(const std::string& description, const std::string& output,
                               const std::string& more = "") const {
    return "design --robot " + description + " --period 5 --harmonics 2 --starts 1 " +
           "--max-evaluations 20 --progress -o " + test::quoted(folder_ / output) + " " + more;
  }
  test::CliRun design(const std::string& output, const std::string& more = "") const {
    return test::modelid(design_arguments(test::quoted_source(kDescription), output, more));
  }

  fs::path folder_, cache_;
};

TEST_F(CompiledModel, FirstUseCompilesAndLaterRunsLoadTheCachedLibrary) {
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", cache_.string());
  const test::CliRun first = design("first.yaml");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_TRUE(contains(first.err, "modelid: compiling the model of ")) << first.err;
  EXPECT_TRUE(contains(first.err, " generated files (-std=c++11 -O1 -fPIC) in ")) << first.err;
  ASSERT_EQ(files_with_extension(cache_, ".so").size(), 1u);
  EXPECT_TRUE(contains(test::read_text(files_with_extension(cache_, ".key").at(0)),
                       "angle-tolerance 0.0001"));

  const test::CliRun second = design("second.yaml");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_FALSE(contains(second.err, "compiling")) << second.err;
  EXPECT_FALSE(contains(second.err, "note:")) << second.err;
  EXPECT_EQ(files_with_extension(cache_, ".so").size(), 1u);
  EXPECT_EQ(trajectory_values(folder_ / "first.yaml"), trajectory_values(folder_ / "second.yaml"));
}

TEST_F(CompiledModel, NoCompileAndBadInputCompileNothing) {
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", cache_.string());
  const test::CliRun numeric = design("numeric.yaml", "--no-compile");
  ASSERT_EQ(numeric.exit_code, 0) << numeric.err;
  EXPECT_TRUE(contains(numeric.err, "note: --no-compile: ")) << numeric.err;
  EXPECT_TRUE(contains(numeric.err, "numeric reference (about 100x slower")) << numeric.err;
  // Refused options are refused before the model is evaluated: nothing is compiled.
  const test::CliRun refused = design("refused.yaml", "--margin 2");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_TRUE(files_with_extension(cache_, ".so").empty());
}

TEST_F(CompiledModel, TheKeyChangesWithTheAngleToleranceAndTheDescription) {
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", cache_.string());
  ASSERT_EQ(design("a.yaml").exit_code, 0);
  ASSERT_EQ(design("b.yaml", "--angle-tolerance 1e-5").exit_code, 0);
  EXPECT_EQ(files_with_extension(cache_, ".so").size(), 2u);
  // The same description with one more comment line: another SHA-256, another entry.
  const fs::path edited = folder_ / "puma560.yaml";
  test::write_text(edited,
                   "# edited\n" + test::read_text(fs::path(MODELGEN_SOURCE_DIR) / kDescription));
  const test::CliRun run = test::modelid(design_arguments(test::quoted(edited), "c.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(contains(run.err, "compiling")) << run.err;
  EXPECT_EQ(files_with_extension(cache_, ".so").size(), 3u);
}

TEST_F(CompiledModel, ACorruptedOrForeignLibraryIsRebuilt) {
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", cache_.string());
  ASSERT_EQ(design("a.yaml").exit_code, 0);
  const fs::path library = files_with_extension(cache_, ".so").at(0);
  test::write_text(library, "not a shared library");
  const test::CliRun corrupted = design("b.yaml");
  ASSERT_EQ(corrupted.exit_code, 0) << corrupted.err;
  EXPECT_TRUE(contains(corrupted.err, "note: rebuilding " + library.string())) << corrupted.err;
  EXPECT_EQ(trajectory_values(folder_ / "a.yaml"), trajectory_values(folder_ / "b.yaml"));

  // The library of another description (another --angle-tolerance gives the same SHA-256
  // but another entry; an edited file gives another SHA-256) under this entry's name.
  const fs::path edited = folder_ / "edited.yaml";
  test::write_text(edited,
                   test::read_text(fs::path(MODELGEN_SOURCE_DIR) / kDescription) + "# edited\n");
  ASSERT_EQ(test::modelid(design_arguments(test::quoted(edited), "c.yaml")).exit_code, 0);
  for (const fs::path& other : files_with_extension(cache_, ".so")) {
    if (other != library) fs::copy_file(other, library, fs::copy_options::overwrite_existing);
  }
  const test::CliRun foreign = design("d.yaml");
  ASSERT_EQ(foreign.exit_code, 0) << foreign.err;
  EXPECT_TRUE(contains(foreign.err, "note: rebuilding " + library.string())) << foreign.err;
  EXPECT_EQ(trajectory_values(folder_ / "a.yaml"), trajectory_values(folder_ / "d.yaml"));
}

TEST_F(CompiledModel, AnUnwritableCacheGivesTheNumericReferenceWithANote) {
  // A cache "folder" below a regular file can never be created, even by root.
  test::write_text(folder_ / "file", "");
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", (folder_ / "file" / "cache").string());
  const test::CliRun run = design("a.yaml");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(contains(run.err, "note: cannot write the model cache ")) << run.err;
  EXPECT_TRUE(contains(run.err, "using the numeric reference instead")) << run.err;
  EXPECT_TRUE(fs::exists(folder_ / "a.yaml"));
}

TEST_F(CompiledModel, AReadOnlyCacheFolderGivesTheNumericReferenceWithANote) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  fs::create_directories(cache_);
  fs::permissions(cache_, fs::perms::owner_read | fs::perms::owner_exec);
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", cache_.string());
  const test::CliRun run = design("a.yaml");
  fs::permissions(cache_, fs::perms::owner_all);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(contains(run.err, "note: cannot write the model cache ")) << run.err;
}

TEST_F(CompiledModel, NoCompilerOrACompileErrorGivesTheNumericReferenceAndNamesTheLog) {
  ScopedEnvironment cache("MODELGEN_CACHE_DIR", cache_.string());
  {
    ScopedEnvironment compiler("CXX", (folder_ / "no-such-compiler").string());
    const test::CliRun run = design("a.yaml");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(contains(run.err, "was not found (set CXX)")) << run.err;
    EXPECT_TRUE(contains(run.err, "using the numeric reference instead")) << run.err;
  }
  {
    ScopedEnvironment compiler("CXX", "false");  // a compiler that fails every file
    const test::CliRun run = design("b.yaml");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(contains(run.err, "the compiler 'false' exited with status 1; its output is in "))
        << run.err;
    // The compiler is part of the cache key: this entry's log is the one named.
    const std::size_t at = run.err.find("its output is in ");
    ASSERT_NE(at, std::string::npos);
    const std::string log = run.err.substr(at + 17, run.err.find(';', at) - at - 17);
    EXPECT_TRUE(contains(test::read_text(log), "flags -std=c++11 -O1 -fPIC")) << log;
  }
  EXPECT_TRUE(files_with_extension(cache_, ".so").empty());
  EXPECT_EQ(trajectory_values(folder_ / "a.yaml"), trajectory_values(folder_ / "b.yaml"));
}

TEST_F(CompiledModel, TwoProcessesFillingTheSameCacheCompileOnce) {
  const std::string modelid = test::quoted(test::executable_path("modelid"));
  std::string script = "cd " + test::quoted(MODELGEN_SOURCE_DIR) +
                       "; export MODELGEN_CACHE_DIR=" + test::quoted(cache_) + "; ";
  for (const char* run : {"a", "b"}) {
    script += "(" + modelid + " " + design_arguments(kDescription, std::string(run) + ".yaml") +
              " > " + test::quoted(folder_ / run) + ".err 2>&1; echo $? > " +
              test::quoted(folder_ / run) + ".exit) & ";
  }
  script += "wait";
  ASSERT_EQ(std::system(script.c_str()), 0);
  int compiles = 0;
  for (const char* run : {"a", "b"}) {
    const std::string err = test::read_text(folder_ / (std::string(run) + ".err"));
    EXPECT_EQ(test::read_text(folder_ / (std::string(run) + ".exit")), "0\n") << err;
    EXPECT_FALSE(contains(err, "note:")) << err;
    compiles += contains(err, "modelid: compiling") ? 1 : 0;
  }
  EXPECT_EQ(compiles, 1);
  EXPECT_EQ(files_with_extension(cache_, ".so").size(), 1u);
  EXPECT_EQ(trajectory_values(folder_ / "a.yaml"), trajectory_values(folder_ / "b.yaml"));
}

}  // namespace
}  // namespace modelgen
