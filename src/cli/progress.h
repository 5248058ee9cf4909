// Progress of a long `coxmesh trace` on standard error.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "coxmesh/util/stopwatch.h"

namespace coxmesh::cli {

// Progress on stderr once a run has lasted about a second: one updated line on a terminal, plain
// lines (at most one every 2 s) otherwise. Never used with --json or --quiet.
class ProgressDisplay {
 public:
  ProgressDisplay() : tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()), last_(start_) {}
  ~ProgressDisplay() { clear(); }

  void traced(std::size_t simplices) {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || (shown_ && std::chrono::duration<double>(now - last_).count() < (tty_ ? 0.1 : 2.0))) return;
    last_ = now;
    show("tracing: " + std::to_string(simplices) + " simplices, " +
         std::to_string(static_cast<long long>(simplices / elapsed)) + " simplices/s, " + seconds(elapsed));
  }
  // A later phase (cell complex, topology, writing): shown only when progress is already on screen.
  void phase(const std::string& what) {
    if (shown_) show(what + "... (" + seconds(seconds_since(start_)) + ")");
  }
  void clear() {
    if (tty_ && shown_) std::fputs("\r\033[K", stderr);
    shown_ = false;
  }

 private:
  static std::string seconds(double s) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f s", s);
    return buffer;
  }
  void show(const std::string& line) {
    if (tty_)
      std::fprintf(stderr, "\r\033[K  %s", line.c_str());
    else
      std::fprintf(stderr, "coxmesh: %s\n", line.c_str());
    std::fflush(stderr);
    shown_ = true;
  }

  bool tty_, shown_ = false;
  Clock::time_point start_, last_;
};

}  // namespace coxmesh::cli
