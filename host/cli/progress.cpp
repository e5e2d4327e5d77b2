// Progress reporting; see progress.h.
#include "host/cli/progress.h"

#include <algorithm>
#include <cstdio>

#include <fmt/core.h>
#include <unistd.h>

#include "common/timing/clock.h"

namespace h4::host::cli {

Progress::Progress(std::string what, int total)
    : what_(std::move(what)),
      total_(total),
      tty_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  if (!finished_ && tty_) std::fputc('\n', stderr);
}

void Progress::Update(int done, const std::string& status) {
  const double seconds = SecondsSince(start_);
  const int percent = total_ > 0 ? std::clamp(100 * done / total_, 0, 100) : 0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = kWidth * percent / 100;
    fmt::print(stderr, "\r{} [{:.{}}{:>{}}] {}/{} {:>5.1f}s {:<40.40}", what_,
               "##############################", filled, "", kWidth - filled, done, total_, seconds,
               status);
    std::fflush(stderr);
  } else if (total_ > 0 ? (percent >= last_percent_logged_ + 10 || done == total_)
                        : (seconds >= last_log_seconds_ + 1.0)) {
    // Not a terminal: a line every 10 % (or every second when the total is unknown).
    last_percent_logged_ = percent;
    last_log_seconds_ = seconds;
    if (total_ > 0) {
      fmt::print(stderr, "{}: {}/{} ({:.1f}s) {}\n", what_, done, total_, seconds, status);
    } else {
      fmt::print(stderr, "{}: {:.1f}s {}\n", what_, seconds, status);
    }
  }
}

void Progress::Finish(const std::string& message) {
  const double seconds = SecondsSince(start_);
  if (tty_) std::fputc('\n', stderr);
  fmt::print(stderr, "{}: {} ({:.1f}s)\n", what_, message, seconds);
  finished_ = true;
}

}  // namespace h4::host::cli
