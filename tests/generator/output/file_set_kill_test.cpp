// A run of FileSet::write_to killed (as by kill -9: no unwinding) after every one of its steps
// in turn: the output folder must hold the complete old set or the complete new set, byte for
// byte, right after the kill when the folder held only the set's files (one swap of folders),
// and at the latest after the next run, a failing one included, when it held the user's own
// files too (file by file under a journal that the next run completes).

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "generator/output/file_set.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

namespace fs = std::filesystem;

using Contents = std::map<std::string, std::string>;  // name -> bytes, hidden names included

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ =
        fs::temp_directory_path() / ("modelgen_file_set_kill_test_" + std::to_string(::getpid()) +
                                     "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

Contents contents(const fs::path& directory) {
  Contents result;
  for (const auto& entry : fs::directory_iterator(directory)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    result[entry.path().filename().string()] = bytes.str();
  }
  return result;
}

void fill(const fs::path& directory, const Contents& files) {
  fs::remove_all(directory);
  fs::create_directories(directory);
  for (const auto& [name, bytes] : files) {
    std::ofstream(directory / name, std::ios::binary) << bytes;
  }
}

std::string describe(const Contents& files) {
  std::string text;
  for (const auto& [name, bytes] : files) text += "  " + name + ": '" + bytes + "'\n";
  return text;
}

// Runs write_to in a child process that dies right after step `stop`; returns whether it died
// there (false: the write has fewer steps and completed).
bool write_and_die_after_step(const FileSet& files, const fs::path& out, std::size_t stop) {
  const pid_t child = ::fork();
  if (child == 0) {
    static std::size_t limit;
    limit = stop;
    test_hooks::after_step = [](std::size_t step) {
      if (step == limit) ::_exit(42);
    };
    try {
      files.write_to(out.string());
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  EXPECT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 1) << "the write failed";
  return WEXITSTATUS(status) == 42;
}

// The set the tests replace: one file changed, one the same, one added, one retired, and a
// file of this input's earlier runs that the set neither writes nor retires (kept).
const char* const kMark = "// made by gen from a.in\n";
Contents old_set() {
  return {{"a.hpp", std::string(kMark) + "old header\n"},
          {"a.cpp", std::string(kMark) + "the same source\n"},
          {"a_f1.cpp", std::string(kMark) + "old function\n"},
          {"a_gone.cpp", std::string(kMark) + "retired function\n"},
          {"a_kept.cpp", std::string(kMark) + "earlier function\n"}};
}
Contents new_set() {
  return {{"a.hpp", std::string(kMark) + "new header, longer\n"},
          {"a.cpp", std::string(kMark) + "the same source\n"},
          {"a_f1.cpp", std::string(kMark) + "new function\n"},
          {"a_f2.cpp", std::string(kMark) + "added function\n"},
          {"a_kept.cpp", std::string(kMark) + "earlier function\n"}};
}
FileSet file_set() {
  FileSet files;
  files.set_owner("// made by gen ", " from a.in");
  for (const char* name : {"a.hpp", "a.cpp", "a_f1.cpp", "a_f2.cpp"}) {
    files.add(name, new_set().at(name));
  }
  files.retire("a_gone.cpp");
  return files;
}

enum class NextRun { kFailing, kSuccessful };

// Kills a write of file_set() into `out`, filled with `before`, after each of its steps, and
// checks the folder after the kill (when `atomic`) and after the next run.
void kill_at_every_step(const fs::path& out, const Contents& before, const Contents& after,
                        bool atomic, NextRun next) {
  std::size_t stop = 1;
  for (; stop < 200; ++stop) {
    fill(out, before);
    const FileSet files = file_set();
    if (!write_and_die_after_step(files, out, stop)) break;
    const Contents killed = contents(out);
    if (atomic) {
      EXPECT_TRUE(killed == before || killed == after)
          << "killed after step " << stop << ", the folder holds\n"
          << describe(killed);
    }
    if (next == NextRun::kFailing) {
      recover_output_directory(out.string());  // what a run that then fails does first
    } else {
      file_set().write_to(out.string());
    }
    const Contents repaired = contents(out);
    if (next == NextRun::kSuccessful) {
      EXPECT_EQ(repaired, after) << "after step " << stop << "\n" << describe(repaired);
    } else {
      EXPECT_TRUE(repaired == before || repaired == after)
          << "killed after step " << stop << ", then recovered:\n"
          << describe(repaired);
    }
    EXPECT_EQ(contents(out.parent_path()).size(), 1u) << "a sibling folder was left behind";
  }
  EXPECT_GT(stop, 5u) << "the write had fewer steps than files";
  EXPECT_LT(stop, 200u);
  EXPECT_EQ(contents(out), after) << "the write that was not killed";
}

TEST(FileSetKill, AFolderOfTheSetsOwnFilesIsNeverMixedAndANextRunCleansUp) {
  TempDir tmp;
  kill_at_every_step(tmp.path() / "out", old_set(), new_set(), true, NextRun::kFailing);
}

TEST(FileSetKill, AFolderOfTheSetsOwnFilesThenASuccessfulRunGivesTheNewSet) {
  TempDir tmp;
  kill_at_every_step(tmp.path() / "out", old_set(), new_set(), true, NextRun::kSuccessful);
}

TEST(FileSetKill, BesideTheUsersFilesTheNextFailingRunRepairsTheFolder) {
  TempDir tmp;
  Contents before = old_set(), after = new_set();
  before["notes.txt"] = after["notes.txt"] = "the user's own file\n";
  kill_at_every_step(tmp.path() / "out", before, after, false, NextRun::kFailing);
}

TEST(FileSetKill, BesideTheUsersFilesTheNextSuccessfulRunGivesTheNewSet) {
  TempDir tmp;
  Contents before = old_set(), after = new_set();
  before["notes.txt"] = after["notes.txt"] = "the user's own file\n";
  kill_at_every_step(tmp.path() / "out", before, after, false, NextRun::kSuccessful);
}

TEST(FileSetKill, ANewFolderAppearsComplete) {
  TempDir tmp;
  const fs::path out = tmp.path() / "out";
  std::size_t stop = 1;
  for (; stop < 100; ++stop) {
    fs::remove_all(out);
    if (!write_and_die_after_step(file_set(), out, stop)) break;
    if (fs::exists(out)) {
      EXPECT_EQ(contents(out), (Contents{{"a.hpp", new_set().at("a.hpp")},
                                         {"a.cpp", new_set().at("a.cpp")},
                                         {"a_f1.cpp", new_set().at("a_f1.cpp")},
                                         {"a_f2.cpp", new_set().at("a_f2.cpp")}}))
          << "killed after step " << stop;
    }
    recover_output_directory(out.string());
    file_set().write_to(out.string());
    EXPECT_EQ(contents(tmp.path()).size(), 1u) << "a sibling folder was left behind";
  }
  EXPECT_GT(stop, 4u);
}

TEST(FileSetKill, ThroughASymbolicLinkTheFolderItNamesIsReplacedWithItsPermissions) {
  TempDir tmp;
  const fs::path real = tmp.path() / "real", link = tmp.path() / "link";
  fill(real, old_set());
  ::chmod(real.c_str(), 0750);
  fs::create_directory_symlink("real", link);
  file_set().write_to(link.string());
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(contents(real), new_set());
  struct stat info {};
  ASSERT_EQ(::stat(real.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0750u);
  EXPECT_EQ(contents(tmp.path()).size(), 2u);
}

TEST(FileSetKill, ModelgenRepairsTheFolderBeforeItFailsOnABadDescription) {
  // A folder with the user's notes, left mixed by a kill between two renames; then modelgen on
  // a broken description into it: exit 1, and the committed set completed.
  TempDir tmp;
  const fs::path out = tmp.path() / "out";
  Contents before = old_set(), after = new_set();
  before["notes.txt"] = after["notes.txt"] = "the user's own file\n";
  std::size_t stop = 1;
  bool mixed = false;
  for (; stop < 200 && !mixed; ++stop) {
    fill(out, before);
    if (!write_and_die_after_step(file_set(), out, stop)) break;
    Contents visible = contents(out);
    std::erase_if(visible, [](const auto& entry) { return entry.first[0] == '.'; });
    mixed = visible != before && visible != after;
  }
  ASSERT_TRUE(mixed) << "no step left the folder mixed: nothing to repair";
  const test::CliRun run = test::modelgen(
      test::quoted(test::source_path("tests/bad_inputs/yaml/antecedent_cycle.yaml")) + " -o " +
      test::quoted(out.string()));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(contents(out), after);
}

}  // namespace
}  // namespace modelgen::gen
