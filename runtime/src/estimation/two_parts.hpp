// Work split in two halves, the second in a helper thread: identify() and the least-squares
// fits both cut their rows this way, with a fixed split so results do not depend on threading.
#pragma once

#include <exception>
#include <system_error>
#include <thread>

namespace modelgen::detail {

/// Runs part(0, true) in the calling thread and part(1, false) in a second thread when
/// `parallel`, else part(0, true) then part(1, true) here (also when no thread can be had).
/// When a part throws, `on_error()` is called (to tell the other part to stop) and, in order,
/// the second part is skipped; the first exception is rethrown once both are done.
template <class Part, class OnError>
void run_two_parts(bool parallel, const Part& part, const OnError& on_error) {
  std::exception_ptr error[2];
  const auto guarded = [&](int i, bool caller) {
    try {
      part(i, caller);
    } catch (...) {
      error[i] = std::current_exception();
      on_error();
    }
  };
  std::thread helper;
  if (parallel) {
    try {
      helper = std::thread(guarded, 1, false);
    } catch (const std::system_error&) {
      parallel = false;  // no thread to be had: the same work, in order
    }
  }
  guarded(0, true);
  if (parallel) {
    helper.join();
  } else if (!error[0]) {
    guarded(1, true);
  }
  for (const std::exception_ptr& e : error) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace modelgen::detail
