// The loader of generated models built as shared libraries refuses, with a ModelLibraryError
// naming the file and what differs, every library it must not use: a missing file, a file that
// is not a library, a library without the entry point, and tables of another layout version,
// size, generated format or description, or with impossible sizes or a missing function. The
// tables are one-joint fakes (loadable/fake_table.cpp) compiled here, each valid but for one
// change; the unchanged one loads. A real generated model: loaded_model_test.cpp.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "modelgen/model/generated_format.hpp"
#include "modelgen/model/model_library.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/shared_library.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

const std::string kSha256(64, 'a');

// The fake table compiled with `definitions` into `name` in the test's folder.
fs::path fake_library(const fs::path& folder, const std::string& name,
                      const std::string& definitions) {
  const fs::path library = folder / name;
  const std::string flags = "-O0 -I" + test::source_path("runtime/include") +
                            " -DFAKE_FORMAT_VERSION=" + std::to_string(kGeneratedFormatVersion) +
                            " '-DFAKE_SHA256=\"" + kSha256 + "\"' " + definitions;
  const test::Compiled compiled = test::compile_shared_library(
      {test::source_path("tests/model/loadable/fake_table.cpp")}, library, flags);
  EXPECT_TRUE(compiled.ok) << compiled.log;
  return library;
}

// The message of the ModelLibraryError opening `library` gives, after checking that it names
// the file as where() and at the start of what().
std::string refusal(const fs::path& library, const std::string& sha256 = kSha256) {
  try {
    ModelLibrary::open(library.string(), sha256);
  } catch (const ModelLibraryError& e) {
    EXPECT_EQ(e.where().file, library.string());
    EXPECT_EQ(std::string(e.what()).rfind(library.string() + ": error: ", 0), 0u) << e.what();
    return e.what();
  }
  ADD_FAILURE() << library << " was loaded";
  return "";
}

TEST(ModelLibrary, RefusesAMissingFileWithTheSystemsReason) {
  const fs::path missing = test::test_folder("model_library") / "no_such_model.so";
  const std::string message = refusal(missing);
  EXPECT_NE(message.find("cannot load the model library"), std::string::npos) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
}

TEST(ModelLibrary, RefusesAFileThatIsNotALibrary) {
  const fs::path folder = test::test_folder("model_library");
  test::write_text(folder / "model.so", "not a shared library\n");
  const std::string message = refusal(folder / "model.so");
  EXPECT_NE(message.find("cannot load the model library"), std::string::npos) << message;
  // dlerror's own words.
  EXPECT_TRUE(message.find("file too short") != std::string::npos ||
              message.find("invalid ELF header") != std::string::npos)
      << message;
}

TEST(ModelLibrary, RefusesALibraryWithoutTheEntryPoint) {
  const fs::path folder = test::test_folder("model_library");
  test::write_text(folder / "other.cpp", "extern \"C\" int other_library(void) { return 1; }\n");
  const fs::path library = folder / "other.so";
  const test::Compiled compiled = test::compile_shared_library({folder / "other.cpp"}, library, "");
  ASSERT_TRUE(compiled.ok) << compiled.log;
  const std::string message = refusal(library);
  EXPECT_NE(message.find("not a modelgen model library"), std::string::npos) << message;
  EXPECT_NE(message.find("undefined symbol: modelgen_loadable_model_v1"), std::string::npos)
      << message;
}

TEST(ModelLibrary, LoadsTheFakeTableAsItStands) {
  const fs::path library = fake_library(test::test_folder("model_library"), "fake.so", "");
  const ModelLibrary loaded = ModelLibrary::open(library.string(), kSha256);
  EXPECT_EQ(loaded.table().dof, 1);
  const std::unique_ptr<IdentificationModel> model = loaded.identification_model();
  EXPECT_EQ(model->name(), "fake");
  EXPECT_EQ(model->description_sha256(), kSha256);
  EXPECT_EQ(model->base_param_names(), std::vector<std::string>{"ZZ1"});
}

TEST(ModelLibrary, RefusesATableOfAnotherVersionSizeOrDescription) {
  const fs::path folder = test::test_folder("model_library");
  const int format = kGeneratedFormatVersion;
  const struct {
    const char* name;
    std::string definitions;
    std::string message;
  } cases[] = {
      {"abi.so", "-DFAKE_ABI_VERSION=1",
       "error: model table version 1, this runtime reads 2: generate it again"},
      {"size.so", "-DFAKE_STRUCT_SIZE=8", "error: model table of 8 bytes, this runtime's has "},
      {"format.so", "-UFAKE_FORMAT_VERSION -DFAKE_FORMAT_VERSION=" + std::to_string(format - 1),
       "error: generated format " + std::to_string(format - 1) + ", this runtime reads " +
           std::to_string(format)},
      {"dof.so", "-DFAKE_DOF=0", "error: bad model table: its dof is 0, not 1 to 32"},
      {"dof33.so", "-DFAKE_DOF=33", "error: bad model table: its dof is 33, not 1 to 32"},
      {"null.so", "-DFAKE_NULL_FUNCTION", "error: bad model table: a function is missing (null)"},
  };
  for (const auto& c : cases) {
    const std::string message = refusal(fake_library(folder, c.name, c.definitions));
    EXPECT_NE(message.find(c.message), std::string::npos) << c.name << ": " << message;
  }
  // The unchanged table for another description.
  const std::string other(64, 'b');
  const std::string message = refusal(fake_library(folder, "fake.so", ""), other);
  EXPECT_NE(message.find("error: built for another description: generated from SHA-256 " + kSha256 +
                         ", the description's is " + other),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace modelgen
