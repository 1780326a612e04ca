// Progress of long modelid runs on stderr: one line updated in place on a terminal, a few
// plain lines in a log.
#pragma once

#include <chrono>
#include <string>

namespace modelgen::internal {

/// Reports how much of `total` units of work is done. On a terminal (isatty(2)) one line,
/// "modelid: LABEL 42% (about 40 s left) DETAIL" (the time left from the pace so far, once a
/// second and 1 % of the work are done), rewritten in place at most ten times a second and erased
/// by finish(). Otherwise (a file, a pipe) nothing, unless the user asked with --progress
/// (show_progress_in_logs): then one line at each quarter of the work at most: four lines in a
/// log, never a stream of updates.
/// Whether progress lines go to a stderr that is not a terminal (modelid --progress). Off by
/// default: scripts and tests read stderr for warnings and errors.
void show_progress_in_logs(bool show);

/// Prints "modelid: TEXT" as a line of its own where progress is shown (a terminal, or a log
/// with --progress), over a progress line being drawn; nothing otherwise. For one-off steps
/// ("compiling the model ...").
void progress_message(const std::string& text);

class Progress {
 public:
  Progress(std::string label, long long total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// `done` units of the total are finished; `detail` (a file name, say) follows the
  /// percentage. Cheap enough to call once per sample.
  void update(long long done, const std::string& detail = "");
  /// Marks the work finished: erases the terminal line. Called by the destructor if needed.
  void finish();

 private:
  std::string label_;
  long long total_;
  bool terminal_;
  bool finished_ = false;
  bool line_shown_ = false;
  int quarters_printed_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace modelgen::internal
