// All-or-nothing writing of generated files (STYLE.md section 9): exact bytes on disk, files
// with unchanged content left untouched (same inode, same modification time), and on every
// failure an InputError, no temporary left behind and no destination file replaced.

#include "generator/output/file_set.hpp"

#include <algorithm>
#include <csignal>
#include <cstring>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "modelgen/model/error.hpp"

namespace modelgen::gen {
namespace {

namespace fs = std::filesystem;

// A fresh empty directory, removed with everything in it at the end of the test.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() / ("modelgen_file_set_test_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ignored);
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

void write(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

// Names in `directory`, sorted, hidden ones included.
std::vector<std::string> names(const fs::path& directory) {
  std::vector<std::string> result;
  for (const auto& entry : fs::directory_iterator(directory)) {
    result.push_back(entry.path().filename().string());
  }
  std::sort(result.begin(), result.end());
  return result;
}

// Temporaries write_to may have left: ".<name>.tmp-<pid>" anywhere under `directory`.
std::vector<std::string> temporaries(const fs::path& directory) {
  std::vector<std::string> result;
  for (const auto& entry : fs::recursive_directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp-") != std::string::npos) result.push_back(entry.path().string());
  }
  return result;
}

ino_t inode(const fs::path& path) {
  struct stat info {};
  EXPECT_EQ(::stat(path.c_str(), &info), 0) << path;
  return info.st_ino;
}

// Sets the modification time an hour back and returns it as the file system stored it, so a
// rewrite, even within the file system's timestamp resolution, shows as a change.
fs::file_time_type age(const fs::path& path) {
  fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::hours(1));
  return fs::last_write_time(path);
}

// Hidden files a run may leave: temporaries, backups, the journal.
std::vector<std::string> hidden(const fs::path& directory) {
  std::vector<std::string> result;
  for (const std::string& name : names(directory)) {
    if (!name.empty() && name[0] == '.') result.push_back(name);
  }
  return result;
}

// Runs write_to in a child process that dies (as under kill -9: no unwinding, no cleanup)
// right after the rename number `stop_after`.
void write_and_die_after_rename(const FileSet& files, const fs::path& out, std::size_t stop_after) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    static std::size_t limit;
    limit = stop_after;
    test_hooks::after_rename = [](std::size_t renamed) {
      if (renamed == limit) ::_exit(42);
    };
    try {
      files.write_to(out.string());
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 42) << "the child was to die between its renames";
}

TEST(FileSet, ARunKilledBetweenItsRenamesIsCompletedByTheNextRun) {
  TempDir tmp;
  const fs::path out = tmp.path() / "kr150";
  fs::create_directories(out);
  write(out / "kr150.hpp", "old header\n");
  write(out / "kr150.cpp", "old source\n");
  write(out / "kr150.json", "old manifest\n");
  write(out / "notes.txt", "the user's own file\n");
  FileSet files;
  files.add("kr150.hpp", "new header\n");
  files.add("kr150.cpp", "new source\n");
  files.add("kr150.json", "new manifest\n");
  write_and_die_after_rename(files, out, 1);
  ASSERT_EQ(read(out / "kr150.hpp"), "new header\n") << "the kill came after the first rename";

  // The next run, whatever it writes (here nothing), first finishes the committed set.
  FileSet{}.write_to(out.string());
  EXPECT_EQ(read(out / "kr150.hpp"), "new header\n");
  EXPECT_EQ(read(out / "kr150.cpp"), "new source\n");
  EXPECT_EQ(read(out / "kr150.json"), "new manifest\n");
  EXPECT_EQ(read(out / "notes.txt"), "the user's own file\n");
  EXPECT_EQ(hidden(out), std::vector<std::string>{});
  EXPECT_EQ(names(out),
            (std::vector<std::string>{"kr150.cpp", "kr150.hpp", "kr150.json", "notes.txt"}));
}

TEST(FileSet, RetiredFilesGoOnlyWithTheNewSet) {
  TempDir tmp;
  const fs::path out = tmp.path() / "tx40";
  fs::create_directories(out);
  write(out / "tx40_mass_matrix.cpp", "function of an earlier run\n");
  write(out / "notes.txt", "the user's own file\n");
  FileSet files;
  files.add("tx40.hpp", "header\n");
  files.retire("tx40_mass_matrix.cpp");
  files.retire("tx40_never_written.cpp");  // absent: nothing to do
  files.write_to(out.string());
  EXPECT_EQ(names(out), (std::vector<std::string>{"notes.txt", "tx40.hpp"}));
  EXPECT_EQ(hidden(out), std::vector<std::string>{});
}

TEST(FileSet, AnotherInputsFilesAreNeitherReplacedNorRetired) {
  TempDir tmp;
  const fs::path out = tmp.path() / "mixed";
  fs::create_directories(out);
  write(out / "b_x.cpp", "// b_x.cpp: made by gen from b.in. KEEP\nbody of b\n");
  write(out / "a_y.cpp", "// a_y.cpp: made by gen from a.in. KEEP\nold body of a\n");
  write(out / "notes.cpp", "the user's own file\n");
  FileSet files;
  files.set_owner(": made by gen ", " from a.in. KEEP");
  files.add("a.hpp", "// a.hpp: made by gen from a.in. KEEP\n");
  files.retire("b_x.cpp");    // generated from b.in: not ours
  files.retire("a_y.cpp");    // ours: removed
  files.retire("notes.cpp");  // not generated: kept
  files.write_to(out.string());
  EXPECT_EQ(names(out), (std::vector<std::string>{"a.hpp", "b_x.cpp", "notes.cpp"}));

  FileSet clash;
  clash.set_owner(": made by gen ", " from a.in. KEEP");
  clash.add("a.hpp", "// a.hpp: made by gen from a.in. KEEP\nnew\n");
  clash.add("b_x.cpp", "// b_x.cpp: made by gen from a.in. KEEP\n");
  try {
    clash.write_to(out.string());
    FAIL() << "another input's file was replaced";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("was generated from another description"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read(out / "b_x.cpp"), "// b_x.cpp: made by gen from b.in. KEEP\nbody of b\n");
  EXPECT_EQ(read(out / "a.hpp"), "// a.hpp: made by gen from a.in. KEEP\n");
  EXPECT_EQ(hidden(out), std::vector<std::string>{});
}

TEST(FileSet, AFailedWriteKeepsTheFilesItWouldRetire) {
  TempDir tmp;
  const fs::path out = tmp.path() / "tx40";
  fs::create_directories(out);
  write(out / "tx40_mass_matrix.cpp", "function of an earlier run\n");
  fs::create_directories(out / "tx40.hpp");  // a destination that is not a file
  FileSet files;
  files.add("tx40.hpp", "header\n");
  files.retire("tx40_mass_matrix.cpp");
  EXPECT_THROW(files.write_to(out.string()), InputError);
  EXPECT_EQ(read(out / "tx40_mass_matrix.cpp"), "function of an earlier run\n");
}

TEST(FileSet, ARunKilledBeforeRemovingRetiredFilesIsCompletedByTheNextRun) {
  TempDir tmp;
  const fs::path out = tmp.path() / "tx40";
  fs::create_directories(out);
  write(out / "tx40.hpp", "old header\n");
  write(out / "tx40_mass_matrix.cpp", "function of an earlier run\n");
  write(out / "notes.txt", "the user's own file: file by file, under the journal\n");
  FileSet files;
  files.add("tx40.hpp", "new header\n");
  files.retire("tx40_mass_matrix.cpp");
  // Killed after its only rename, before the retired file went.
  write_and_die_after_rename(files, out, 1);
  ASSERT_TRUE(fs::exists(out / "tx40_mass_matrix.cpp"));
  FileSet{}.write_to(out.string());
  EXPECT_EQ(names(out), (std::vector<std::string>{"notes.txt", "tx40.hpp"}));
  EXPECT_EQ(read(out / "tx40.hpp"), "new header\n");
}

TEST(FileSet, AKilledRunThenANewSetLeavesOnlyTheNewSet) {
  TempDir tmp;
  const fs::path out = tmp.path() / "out";
  fs::create_directories(out);
  write(out / "a.hpp", "old header\n");
  write(out / "a.cpp", "old source\n");
  write(out / "notes.txt", "the user's own file: file by file, under the journal\n");
  FileSet killed;
  killed.add("a.hpp", "killed header\n");
  killed.add("a.cpp", "killed source\n");
  write_and_die_after_rename(killed, out, 1);

  FileSet next;
  next.add("a.hpp", "next header\n");
  next.add("a.cpp", "next source\n");
  next.write_to(out.string());
  EXPECT_EQ(read(out / "a.hpp"), "next header\n");
  EXPECT_EQ(read(out / "a.cpp"), "next source\n");
  EXPECT_EQ(names(out), (std::vector<std::string>{"a.cpp", "a.hpp", "notes.txt"}));
}

TEST(FileSet, AFullDiskGivesTheSystemsReasonAndChangesNothing) {
  // A file size limit makes write(2) fail with EFBIG as a full disk fails with ENOSPC; in a
  // child process, so the limit does not outlive the test.
  TempDir tmp;
  write(tmp.path() / "a.hpp", "old header\n");
  const fs::path message_file = tmp.path() / "message.txt";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1024, 1024};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    FileSet files;
    files.add("a.hpp", std::string(100000, 'x'));
    std::string message = "no error";
    try {
      files.write_to(tmp.path().string());
    } catch (const InputError& error) {
      message = error.what();
    }
    write(message_file, message.substr(0, 1000));  // under the limit
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const std::string message = read(message_file);
  fs::remove(message_file);
  EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
  EXPECT_EQ(read(tmp.path() / "a.hpp"), "old header\n");
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.hpp"}));
}

TEST(FileSet, KeepsFilesInOrder) {
  FileSet files;
  files.add("b.hpp", "1");
  files.add("a.cpp", "2");
  ASSERT_EQ(files.files().size(), 2u);
  EXPECT_EQ(files.files()[0].name, "b.hpp");
  EXPECT_EQ(files.files()[0].content, "1");
  EXPECT_EQ(files.files()[1].name, "a.cpp");
  EXPECT_EQ(files.files()[1].content, "2");
}

TEST(FileSet, CreatesTheDirectoryAndWritesExactBytes) {
  TempDir tmp;
  const fs::path out = tmp.path() / "build" / "modelgen" / "kr150_model";
  // 6 + 2 + 16 + 1 + 9 + 1 bytes: the literal without its terminating NUL.
  const std::string binary("line 1\r\nno final newline\0after nul\xff", 35);
  FileSet files;
  files.add("kr150.hpp", "#ifndef X\n#define X\n#endif  // X\n");
  files.add("kr150.cpp", binary);
  files.add("kr150.json", "");
  files.write_to(out.string());

  ASSERT_TRUE(fs::is_directory(out));
  EXPECT_EQ(names(out), (std::vector<std::string>{"kr150.cpp", "kr150.hpp", "kr150.json"}));
  EXPECT_EQ(read(out / "kr150.hpp"), "#ifndef X\n#define X\n#endif  // X\n");
  EXPECT_EQ(read(out / "kr150.cpp"), binary);
  EXPECT_EQ(read(out / "kr150.cpp").size(), 35u);
  EXPECT_TRUE(fs::is_regular_file(out / "kr150.json"));
  EXPECT_EQ(fs::file_size(out / "kr150.json"), 0u);
}

TEST(FileSet, ExistingDirectoryAndUnrelatedFilesAreKept) {
  TempDir tmp;
  write(tmp.path() / "notes.txt", "mine\n");
  FileSet files;
  files.add("a.hpp", "a\n");
  files.write_to(tmp.path().string());
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.hpp", "notes.txt"}));
  EXPECT_EQ(read(tmp.path() / "notes.txt"), "mine\n");
}

TEST(FileSet, IdenticalContentIsNotRewritten) {
  TempDir tmp;
  FileSet files;
  files.add("a.hpp", "header\n");
  files.add("a.cpp", "source\n");
  files.write_to(tmp.path().string());

  const fs::file_time_type hpp_time = age(tmp.path() / "a.hpp");
  const fs::file_time_type cpp_time = age(tmp.path() / "a.cpp");
  const ino_t hpp_inode = inode(tmp.path() / "a.hpp");
  const ino_t cpp_inode = inode(tmp.path() / "a.cpp");

  files.write_to(tmp.path().string());
  EXPECT_EQ(fs::last_write_time(tmp.path() / "a.hpp"), hpp_time);
  EXPECT_EQ(fs::last_write_time(tmp.path() / "a.cpp"), cpp_time);
  EXPECT_EQ(inode(tmp.path() / "a.hpp"), hpp_inode);
  EXPECT_EQ(inode(tmp.path() / "a.cpp"), cpp_inode);
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.cpp", "a.hpp"}));
}

TEST(FileSet, OnlyChangedFilesAreReplaced) {
  TempDir tmp;
  {
    FileSet files;
    files.add("a.hpp", "header\n");
    files.add("a.cpp", "source v1\n");
    files.write_to(tmp.path().string());
  }
  const fs::file_time_type hpp_time = age(tmp.path() / "a.hpp");
  const fs::file_time_type cpp_time = age(tmp.path() / "a.cpp");

  FileSet files;
  files.add("a.hpp", "header\n");
  files.add("a.cpp", "source v2, longer than v1\n");
  files.write_to(tmp.path().string());
  EXPECT_EQ(read(tmp.path() / "a.cpp"), "source v2, longer than v1\n");
  EXPECT_NE(fs::last_write_time(tmp.path() / "a.cpp"), cpp_time);
  EXPECT_EQ(read(tmp.path() / "a.hpp"), "header\n");
  EXPECT_EQ(fs::last_write_time(tmp.path() / "a.hpp"), hpp_time);
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.cpp", "a.hpp"}));
}

TEST(FileSet, ShorterContentTruncatesTheOldFile) {
  TempDir tmp;
  write(tmp.path() / "a.json", "{\"a very long old content\": 1}\n");
  FileSet files;
  files.add("a.json", "{}\n");
  files.write_to(tmp.path().string());
  EXPECT_EQ(read(tmp.path() / "a.json"), "{}\n");
}

TEST(FileSet, DirectoryUnderARegularFileThrowsInputError) {
  TempDir tmp;
  write(tmp.path() / "plain", "not a directory\n");
  const fs::path out = tmp.path() / "plain" / "out";
  FileSet files;
  files.add("a.hpp", "header\n");
  try {
    files.write_to(out.string());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(out.string()), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("error: "), std::string::npos) << error.what();
  }
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"plain"}));
  EXPECT_EQ(read(tmp.path() / "plain"), "not a directory\n");
  EXPECT_TRUE(temporaries(tmp.path()).empty());
}

TEST(FileSet, ReadOnlyDirectoryThrowsInputErrorAndLeavesNothing) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions do not stop writes";
  TempDir tmp;
  const fs::path out = tmp.path() / "out";
  fs::create_directories(out);
  write(out / "a.hpp", "old header\n");
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec);
  FileSet files;
  files.add("a.hpp", "new header\n");
  files.add("a.cpp", "new source\n");
  EXPECT_THROW(files.write_to(out.string()), InputError);
  fs::permissions(out, fs::perms::owner_all);
  EXPECT_EQ(names(out), (std::vector<std::string>{"a.hpp"}));
  EXPECT_EQ(read(out / "a.hpp"), "old header\n");
}

TEST(FileSet, SecondTemporaryFailingReplacesNothing) {
  // The second file's temporary cannot be created (its folder does not exist): the first file
  // must keep its old content.
  TempDir tmp;
  write(tmp.path() / "a.hpp", "old header\n");
  const fs::file_time_type old_time = age(tmp.path() / "a.hpp");
  FileSet files;
  files.add("a.hpp", "new header\n");
  files.add("missing/a.cpp", "new source\n");
  EXPECT_THROW(files.write_to(tmp.path().string()), InputError);
  EXPECT_EQ(read(tmp.path() / "a.hpp"), "old header\n");
  EXPECT_EQ(fs::last_write_time(tmp.path() / "a.hpp"), old_time);
  EXPECT_TRUE(temporaries(tmp.path()).empty());
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.hpp"}));
}

TEST(FileSet, SecondRenameFailingReplacesNothing) {
  // The destination of the second file is an existing directory, so only its rename fails.
  // All-or-nothing: the first file must not have been replaced either.
  TempDir tmp;
  write(tmp.path() / "a.hpp", "old header\n");
  fs::create_directories(tmp.path() / "a.cpp");
  write(tmp.path() / "a.cpp" / "inside.txt", "x\n");
  FileSet files;
  files.add("a.hpp", "new header\n");
  files.add("a.cpp", "new source\n");
  try {
    files.write_to(tmp.path().string());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("a.cpp"), std::string::npos) << error.what();
  }
  EXPECT_EQ(read(tmp.path() / "a.hpp"), "old header\n") << "first file replaced before failure";
  EXPECT_TRUE(fs::is_directory(tmp.path() / "a.cpp"));
  EXPECT_EQ(read(tmp.path() / "a.cpp" / "inside.txt"), "x\n");
  EXPECT_TRUE(temporaries(tmp.path()).empty());
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.cpp", "a.hpp"}));
}

TEST(FileSet, FirstRenameFailingReplacesNothing) {
  TempDir tmp;
  fs::create_directories(tmp.path() / "a.hpp");
  write(tmp.path() / "a.cpp", "old source\n");
  FileSet files;
  files.add("a.hpp", "new header\n");
  files.add("a.cpp", "new source\n");
  EXPECT_THROW(files.write_to(tmp.path().string()), InputError);
  EXPECT_EQ(read(tmp.path() / "a.cpp"), "old source\n");
  EXPECT_TRUE(temporaries(tmp.path()).empty());
  EXPECT_EQ(names(tmp.path()), (std::vector<std::string>{"a.cpp", "a.hpp"}));
}

}  // namespace
}  // namespace modelgen::gen
