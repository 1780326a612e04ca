// All-or-nothing writing of generated files: temporaries, then a journal that commits the new
// set, then rename(2) of each temporary over its destination. A failure before the journal
// leaves the old set; a failure after it restores the old files from hard-linked backups; a
// kill after it is completed by the next run in the same folder (roll forward), so a killed
// run never leaves a mixed set behind once modelgen runs again, nor stray hidden files.

#include "generator/output/file_set.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "modelgen/model/error.hpp"

namespace modelgen::gen {

namespace fs = std::filesystem;

namespace test_hooks {
void (*after_rename)(std::size_t renamed) = nullptr;
}

void FileSet::add(std::string name, std::string content) {
  files_.push_back({std::move(name), std::move(content)});
}

void FileSet::retire(std::string name) { retired_.push_back(std::move(name)); }

void FileSet::set_owner(std::string generated_mark, std::string owner_mark) {
  generated_mark_ = std::move(generated_mark);
  owner_mark_ = std::move(owner_mark);
}

namespace {

constexpr const char* kJournal = ".modelgen-commit";

bool same_content(const fs::path& path, const std::string& content) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream existing;
  existing << in.rdbuf();
  return existing.str() == content;
}

// Writes `content` to a new file at `path` and flushes it to the disk; on failure, returns the
// system's reason (strerror), so a full disk says "No space left on device".
std::string write_new_file(const fs::path& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return std::strerror(errno);
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? std::strerror(errno) : "nothing written";
      ::close(fd);
      return reason;
    }
    written += static_cast<std::size_t>(n);
  }
  // The journal commits the set: its temporaries must be on the disk before it is.
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    return reason;
  }
  if (::close(fd) != 0) return std::strerror(errno);
  return "";
}

std::string first_line(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::getline(in, line);
  return line;
}

// An exclusive lock on the output directory for the whole write: two runs into one folder (a
// parallel build generating twice) take turns, so neither completes the other's journal while
// it is still renaming. Released when the object goes.
class DirectoryLock {
 public:
  explicit DirectoryLock(const fs::path& directory)
      : fd_(::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0) {
      while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
      }
    }
  }
  ~DirectoryLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_;
};

bool process_alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

// Finishes what a killed run committed (its journal lists "temporary\tdestination" lines, and
// "\tname" for a file to remove): every temporary still there is renamed into place, retired
// files are removed, then backups, leftovers of runs that no longer exist and the journal go.
void recover_interrupted_run(const fs::path& directory) {
  std::error_code ignored;
  const fs::path journal = directory / kJournal;
  if (fs::exists(journal, ignored)) {
    std::ifstream in(journal);
    std::string line;
    bool complete = false;
    std::vector<std::pair<std::string, std::string>> moves;
    while (std::getline(in, line)) {
      if (line == "end") {
        complete = true;
        break;
      }
      const std::size_t tab = line.find('\t');
      if (tab != std::string::npos) moves.emplace_back(line.substr(0, tab), line.substr(tab + 1));
    }
    // A journal without its last line was cut short: the set was never committed.
    if (complete) {
      for (const auto& [temporary, destination] : moves) {
        if (temporary.empty()) {
          fs::remove(directory / destination, ignored);
        } else if (fs::exists(directory / temporary, ignored)) {
          fs::rename(directory / temporary, directory / destination, ignored);
        }
      }
    }
    fs::remove(journal, ignored);
  }
  // ".<name>.tmp-<pid>", ".<name>.old-<pid>" and ".modelgen-commit.tmp-<pid>" of dead runs.
  static const std::regex leftover(R"(^\..+\.(tmp|old)-([0-9]+)$)");
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(directory, ignored)) {
    const std::string name = entry.path().filename().string();
    std::smatch match;
    if (std::regex_match(name, match, leftover) && !process_alive(std::stol(match[2].str()))) {
      stale.push_back(entry.path());
    }
  }
  for (const fs::path& path : stale) fs::remove(path, ignored);
}

// Which existing files this set may replace or retire (FileSet::set_owner).
struct Ownership {
  const std::string& generated_mark;
  const std::string& owner_mark;

  // Whether an existing file was generated, and from another input than this set's.
  bool generated(const fs::path& path) const {
    return !generated_mark.empty() && first_line(path).find(generated_mark) != std::string::npos;
  }
  bool foreign(const fs::path& path) const {
    return generated(path) && first_line(path).find(owner_mark) == std::string::npos;
  }
};

void create_output_directory(const std::string& directory) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec || !fs::is_directory(directory)) {
    throw InputError({directory}, "cannot create the output directory" +
                                      (ec ? ": " + ec.message() : std::string()));
  }
}

// Refuse before touching anything if a destination is something other than a file, or the
// output of another input.
void check_destinations(const std::string& directory, const std::vector<OutputFile>& files,
                        const Ownership& ownership) {
  for (const OutputFile& file : files) {
    const fs::path destination = fs::path(directory) / file.name;
    if (fs::exists(fs::symlink_status(destination)) && !fs::is_regular_file(destination)) {
      throw InputError({destination.string()}, "exists and is not a regular file; not replaced");
    }
    if (fs::exists(destination) && ownership.foreign(destination)) {
      throw InputError({destination.string()},
                       "was generated from another description (its first line: '" +
                           first_line(destination) +
                           "'); not replaced: generate each description into a folder of its own "
                           "(no file was changed)");
    }
  }
}

// The retired files still in `directory` that are this set's to remove.
std::vector<std::string> files_to_retire(const std::string& directory,
                                         const std::vector<std::string>& retired_names,
                                         const Ownership& ownership) {
  std::vector<std::string> retired;
  for (const std::string& name : retired_names) {
    const fs::path path = fs::path(directory) / name;
    if (!fs::is_regular_file(fs::symlink_status(path))) continue;
    if (!ownership.generated_mark.empty() &&
        (!ownership.generated(path) || ownership.foreign(path))) {
      continue;  // not ours
    }
    retired.push_back(name);
  }
  return retired;
}

// The temporaries, backups and journal of one write_to in one directory, so that a failure at
// any step can undo everything done so far before it throws.
class Replacements {
 public:
  explicit Replacements(const std::string& directory)
      : directory_(directory),
        suffix_(std::to_string(::getpid())),
        journal_(directory_ / kJournal),
        journal_temporary_(directory_ / (std::string(kJournal) + ".tmp-" + suffix_)) {}

  bool empty() const { return replacements_.empty(); }

  // Writes each file whose content changed to a temporary beside its destination.
  void write_temporaries(const std::vector<OutputFile>& files) {
    for (const OutputFile& file : files) {
      const fs::path destination = directory_ / file.name;
      if (same_content(destination, file.content)) continue;
      Replacement r;
      r.name = file.name;
      r.destination = destination;
      r.temporary = directory_ / ("." + file.name + ".tmp-" + suffix_);
      r.backup = directory_ / ("." + file.name + ".old-" + suffix_);
      replacements_.push_back(r);
      const std::string reason = write_new_file(r.temporary, file.content);
      if (!reason.empty()) {
        roll_back();
        throw InputError({destination.string()},
                         "cannot write the file: " + reason + " (no file was changed)");
      }
    }
  }

  // The commit point: once the journal exists, the new set is what the folder will hold, even
  // if this process dies during the renames below (the next run completes them).
  void commit(const std::vector<std::string>& retired) {
    std::string journal_text;
    for (const Replacement& r : replacements_) {
      journal_text += r.temporary.filename().string() + "\t" + r.name + "\n";
    }
    for (const std::string& name : retired) journal_text += "\t" + name + "\n";
    journal_text += "end\n";
    std::string reason = write_new_file(journal_temporary_, journal_text);
    if (reason.empty()) {
      std::error_code ec;
      fs::rename(journal_temporary_, journal_, ec);
      if (ec) reason = ec.message();
    }
    if (!reason.empty()) {
      roll_back();
      throw InputError({journal_.string()},
                       "cannot write the file: " + reason + " (no file was changed)");
    }
  }

  // Every new file is complete on disk; now swap them in, keeping a hard link to each old file
  // until all swaps succeeded so that a failure can restore the previous set exactly.
  void swap_in() {
    std::error_code ec;
    std::size_t renamed = 0;
    for (Replacement& r : replacements_) {
      if (fs::exists(r.destination)) {
        fs::create_hard_link(r.destination, r.backup, ec);
        if (ec) {
          roll_back();
          throw InputError({r.destination.string()},
                           "cannot replace the file: " + ec.message() + " (no file was changed)");
        }
        r.backed_up = true;
      }
      fs::rename(r.temporary, r.destination, ec);
      if (ec) {
        roll_back();
        throw InputError({r.destination.string()}, "cannot replace the file: " + ec.message() +
                                                       " (no file was changed)");
      }
      r.replaced = true;
      if (test_hooks::after_rename != nullptr) test_hooks::after_rename(++renamed);
    }
  }

  // The new set is in place: retired files, backups and the journal go.
  void finish(const std::vector<std::string>& retired) const {
    std::error_code ignored;
    for (const std::string& name : retired) fs::remove(directory_ / name, ignored);
    for (const Replacement& r : replacements_) {
      if (r.backed_up) fs::remove(r.backup, ignored);
    }
    fs::remove(journal_, ignored);
  }

 private:
  struct Replacement {
    std::string name;
    fs::path temporary, destination, backup;
    bool backed_up = false, replaced = false;
  };

  // Undo everything done so far: new files out, old files back, temporaries and journal gone.
  void roll_back() const {
    std::error_code ignored;
    for (auto it = replacements_.rbegin(); it != replacements_.rend(); ++it) {
      if (it->backed_up) {
        fs::rename(it->backup, it->destination, ignored);
      } else if (it->replaced) {
        fs::remove(it->destination, ignored);
      }
      fs::remove(it->temporary, ignored);
    }
    fs::remove(journal_temporary_, ignored);
    fs::remove(journal_, ignored);
  }

  const fs::path directory_;
  const std::string suffix_;
  const fs::path journal_, journal_temporary_;
  std::vector<Replacement> replacements_;
};

}  // namespace

void FileSet::write_to(const std::string& directory) const {
  create_output_directory(directory);
  const DirectoryLock lock(directory);
  recover_interrupted_run(directory);
  const Ownership ownership{generated_mark_, owner_mark_};
  check_destinations(directory, files_, ownership);
  Replacements replacements(directory);
  replacements.write_temporaries(files_);
  const std::vector<std::string> retired = files_to_retire(directory, retired_, ownership);
  if (replacements.empty() && retired.empty()) return;
  replacements.commit(retired);
  replacements.swap_in();
  replacements.finish(retired);
}

}  // namespace modelgen::gen
