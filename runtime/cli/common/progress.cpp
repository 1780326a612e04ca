// Progress lines on stderr; the terminal test is done once per indicator.

#include "runtime/cli/common/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace modelgen::internal {

namespace {

constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
bool log_progress = false;

// " (about 40 s left)" from the pace so far, once there is a pace to tell (a second and 1 % in).
std::string time_left(std::chrono::steady_clock::duration elapsed, long long done,
                      long long total) {
  const double seconds = std::chrono::duration<double>(elapsed).count();
  if (seconds < 1.0 || done * 100 < total || done >= total) return "";
  const double left = seconds * static_cast<double>(total - done) / static_cast<double>(done);
  char text[48];
  if (left < 90) {
    std::snprintf(text, sizeof text, " (about %.0f s left)", std::max(1.0, left));
  } else {
    std::snprintf(text, sizeof text, " (about %.0f min left)", left / 60);
  }
  return text;
}

}  // namespace

void show_progress_in_logs(bool show) { log_progress = show; }

void progress_message(const std::string& text) {
  if (::isatty(STDERR_FILENO) == 1) {
    std::fprintf(stderr, "\r\033[Kmodelid: %s\n", text.c_str());
  } else if (log_progress) {
    std::fprintf(stderr, "modelid: %s\n", text.c_str());
  }
  std::fflush(stderr);
}

Progress::Progress(std::string label, long long total)
    : label_(std::move(label)),
      total_(std::max(total, 1LL)),
      terminal_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - kRedrawInterval) {}

Progress::~Progress() { finish(); }

void Progress::update(long long done, const std::string& detail) {
  if (finished_) return;
  const auto now = std::chrono::steady_clock::now();
  const int percent = static_cast<int>(100 * std::clamp(done, 0LL, total_) / total_);
  const std::string tail = time_left(now - start_, std::clamp(done, 0LL, total_), total_) +
                           (detail.empty() ? "" : " " + detail);
  if (terminal_) {
    if (now - last_draw_ < kRedrawInterval) return;
    last_draw_ = now;
    // \r and "erase to end of line": the line is redrawn in place.
    std::fprintf(stderr, "\rmodelid: %s %3d%%%s\033[K", label_.c_str(), percent, tail.c_str());
    std::fflush(stderr);
    line_shown_ = true;
    return;
  }
  if (!log_progress) return;
  const int quarter = percent / 25;
  if (quarter <= quarters_printed_) return;
  quarters_printed_ = quarter;
  std::fprintf(stderr, "modelid: %s %d%%%s\n", label_.c_str(), percent, tail.c_str());
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (terminal_ && line_shown_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
}

}  // namespace modelgen::internal
