// All-or-nothing writing of generated files: temporaries, then a journal that commits the new
// set, then rename(2) of each temporary over its destination. A failure before the journal
// leaves the old set; a failure after it restores the old files from hard-linked backups; a
// kill after it is completed by the next run in the same folder (roll forward), so a killed
// run never leaves a mixed set behind once modelgen runs again, nor stray hidden files.

#include "generator/output/file_set.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

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

}  // namespace

void FileSet::write_to(const std::string& directory) const {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec || !fs::is_directory(directory)) {
    throw InputError({directory}, "cannot create the output directory" +
                                      (ec ? ": " + ec.message() : std::string()));
  }
  recover_interrupted_run(directory);
  // Refuse before touching anything if a destination is something other than a file.
  for (const OutputFile& file : files_) {
    const fs::path destination = fs::path(directory) / file.name;
    if (fs::exists(fs::symlink_status(destination)) && !fs::is_regular_file(destination)) {
      throw InputError({destination.string()}, "exists and is not a regular file; not replaced");
    }
  }
  struct Replacement {
    std::string name;
    fs::path temporary, destination, backup;
    bool backed_up = false, replaced = false;
  };
  std::vector<Replacement> replacements;
  const std::string suffix = std::to_string(::getpid());
  const fs::path journal = fs::path(directory) / kJournal;
  const fs::path journal_temporary = fs::path(directory) / (std::string(kJournal) + ".tmp-" + suffix);
  // Undo everything done so far: new files out, old files back, temporaries and journal gone.
  auto roll_back = [&] {
    std::error_code ignored;
    for (auto it = replacements.rbegin(); it != replacements.rend(); ++it) {
      if (it->backed_up) {
        fs::rename(it->backup, it->destination, ignored);
      } else if (it->replaced) {
        fs::remove(it->destination, ignored);
      }
      fs::remove(it->temporary, ignored);
    }
    fs::remove(journal_temporary, ignored);
    fs::remove(journal, ignored);
  };
  for (const OutputFile& file : files_) {
    const fs::path destination = fs::path(directory) / file.name;
    if (same_content(destination, file.content)) continue;
    Replacement r;
    r.name = file.name;
    r.destination = destination;
    r.temporary = fs::path(directory) / ("." + file.name + ".tmp-" + suffix);
    r.backup = fs::path(directory) / ("." + file.name + ".old-" + suffix);
    replacements.push_back(r);
    const std::string reason = write_new_file(r.temporary, file.content);
    if (!reason.empty()) {
      roll_back();
      throw InputError({destination.string()}, "cannot write the file: " + reason +
                                                   " (no file was changed)");
    }
  }
  std::vector<std::string> retired;
  for (const std::string& name : retired_) {
    if (fs::is_regular_file(fs::symlink_status(fs::path(directory) / name))) retired.push_back(name);
  }
  if (replacements.empty() && retired.empty()) return;
  // The commit point: once the journal exists, the new set is what the folder will hold, even
  // if this process dies during the renames below (the next run completes them).
  std::string journal_text;
  for (const Replacement& r : replacements) {
    journal_text += r.temporary.filename().string() + "\t" + r.name + "\n";
  }
  for (const std::string& name : retired) journal_text += "\t" + name + "\n";
  journal_text += "end\n";
  std::string reason = write_new_file(journal_temporary, journal_text);
  if (reason.empty()) {
    fs::rename(journal_temporary, journal, ec);
    if (ec) reason = ec.message();
  }
  if (!reason.empty()) {
    roll_back();
    throw InputError({journal.string()}, "cannot write the file: " + reason +
                                             " (no file was changed)");
  }
  // Every new file is complete on disk; now swap them in, keeping a hard link to each old file
  // until all swaps succeeded so that a failure can restore the previous set exactly.
  std::size_t renamed = 0;
  for (Replacement& r : replacements) {
    if (fs::exists(r.destination)) {
      fs::create_hard_link(r.destination, r.backup, ec);
      if (ec) {
        roll_back();
        throw InputError({r.destination.string()}, "cannot replace the file: " + ec.message() +
                                                       " (no file was changed)");
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
  std::error_code ignored;
  for (const std::string& name : retired) fs::remove(fs::path(directory) / name, ignored);
  for (const Replacement& r : replacements) {
    if (r.backed_up) fs::remove(r.backup, ignored);
  }
  fs::remove(journal, ignored);
}

}  // namespace modelgen::gen
