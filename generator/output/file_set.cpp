// All-or-nothing writing of generated files, in one of two ways. When the output folder holds
// only this set's files (or does not exist), the new set is built in a sibling folder and
// swapped in with one rename (directory_swap.hpp): the folder shows the old set or the new one,
// whatever happens. Otherwise (the user's own files beside the set, or a file system that
// cannot exchange folders) a journal: temporaries, then a journal that commits the new set,
// then rename(2) of each temporary over its destination. A failure before the journal leaves
// the old set; a failure after it restores the old files from hard-linked backups; a kill
// after it is completed by the next run in the same folder (roll forward), which modelgen
// does first thing (recover_output_directory), even a run that then fails.

#include "generator/output/file_set.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "generator/output/directory_swap.hpp"
#include "generator/output/file_system.hpp"
#include "modelgen/model/error.hpp"

namespace modelgen::gen {

namespace fs = std::filesystem;
using detail::first_line;
using detail::same_content;
using detail::step_done;
using detail::write_new_file;

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

// Finishes what a killed run committed (its journal lists "temporary\tdestination" lines, and
// "\tname" for a file to remove): every temporary still there is renamed into place, retired
// files are removed, then the journal goes (backups and temporaries: detail::remove_leftovers).
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
    step_done();
  }
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
      step_done();
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
    step_done();
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
        step_done();
      }
      fs::rename(r.temporary, r.destination, ec);
      if (ec) {
        roll_back();
        throw InputError({r.destination.string()}, "cannot replace the file: " + ec.message() +
                                                       " (no file was changed)");
      }
      r.replaced = true;
      step_done();
      if (test_hooks::after_rename != nullptr) test_hooks::after_rename(++renamed);
    }
  }

  // The new set is in place: retired files, backups and the journal go.
  void finish(const std::vector<std::string>& retired) const {
    std::error_code ignored;
    for (const std::string& name : retired) {
      fs::remove(directory_ / name, ignored);
      step_done();
    }
    for (const Replacement& r : replacements_) {
      if (r.backed_up) fs::remove(r.backup, ignored);
    }
    fs::remove(journal_, ignored);
    step_done();
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

// The folder `directory` names, absolute, with its symbolic links resolved (a link to a folder
// keeps pointing to the folder that gets the new set); empty when it cannot be swapped at all.
fs::path swap_target(const std::string& directory) {
  std::error_code ec;
  fs::path path = fs::weakly_canonical(fs::absolute(directory, ec), ec);
  if (ec) return {};
  if (path.filename().empty()) path = path.parent_path();  // a trailing separator
  if (path.filename().empty() || path == path.root_path()) return {};
  return path;
}

// Whether every entry of the folder is a file the set accounts for (one of its files, a file
// it retires, or a file generated from its input), so that replacing the whole folder takes
// nothing else away; fills the plan's old names and the files it keeps by hard link.
bool only_this_sets_files(const fs::path& folder, const std::vector<OutputFile>& files,
                          const std::vector<std::string>& retired, const Ownership& ownership,
                          detail::SwapPlan& plan) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (!fs::is_regular_file(fs::symlink_status(entry.path(), ec))) return false;
    plan.old_names.push_back(name);
    const auto same_name = [&](const OutputFile& file) { return file.name == name; };
    const auto found = std::find_if(files.begin(), files.end(), same_name);
    if (found != files.end()) {
      if (same_content(entry.path(), found->content)) plan.linked.push_back(name);
      continue;
    }
    if (std::find(retired.begin(), retired.end(), name) != retired.end()) continue;
    if (!ownership.generated(entry.path()) || ownership.foreign(entry.path())) return false;
    plan.linked.push_back(name);  // generated from this input by an earlier run: kept
  }
  return !ec;
}

}  // namespace

void FileSet::write_to(const std::string& directory) const {
  detail::reset_steps();
  const Ownership ownership{generated_mark_, owner_mark_};
  const fs::path target = swap_target(directory);
  const bool flat = std::none_of(files_.begin(), files_.end(), [](const OutputFile& file) {
    return file.name.find('/') != std::string::npos;
  });
  std::error_code ec;
  // No folder yet: the new one appears complete, by one rename of the folder built beside it.
  if (flat && !target.empty() && !fs::exists(fs::symlink_status(target, ec))) {
    detail::remove_leftovers(target);
    fs::create_directories(target.parent_path(), ec);
    detail::SwapPlan plan{target, {}, {}, {}};
    for (const OutputFile& file : files_) plan.written.push_back(&file);
    if (!ec && detail::swap_in_directory(plan) == detail::SwapResult::kDone) return;
  }
  create_output_directory(directory);
  const detail::DirectoryLock lock(directory);
  recover_interrupted_run(directory);
  detail::remove_leftovers(target.empty() ? fs::path(directory) : target);
  check_destinations(directory, files_, ownership);
  const std::vector<std::string> retired = files_to_retire(directory, retired_, ownership);
  detail::SwapPlan plan{target, {}, {}, {}};
  if (flat && !target.empty() && only_this_sets_files(target, files_, retired, ownership, plan)) {
    for (const OutputFile& file : files_) {
      if (std::find(plan.linked.begin(), plan.linked.end(), file.name) == plan.linked.end()) {
        plan.written.push_back(&file);
      }
    }
    if (plan.written.empty() && plan.linked.size() == plan.old_names.size()) return;  // the same
    if (detail::swap_in_directory(plan) == detail::SwapResult::kDone) return;
  }
  Replacements replacements(directory);
  replacements.write_temporaries(files_);
  if (replacements.empty() && retired.empty()) return;
  replacements.commit(retired);
  replacements.swap_in();
  replacements.finish(retired);
}

void recover_output_directory(const std::string& directory) {
  detail::reset_steps();
  const fs::path target = swap_target(directory);
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    if (!target.empty()) detail::remove_leftovers(target);  // a new folder never swapped in
    return;
  }
  const detail::DirectoryLock lock(directory);
  if (lock.held()) recover_interrupted_run(directory);
  detail::remove_leftovers(target.empty() ? fs::path(directory) : target);
}

}  // namespace modelgen::gen
