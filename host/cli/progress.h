// Progress on long work, on stderr: a bar redrawn in place on a terminal, a line
// every few percent otherwise (logs, CI), so a user always sees that work goes on.
#pragma once

#include <chrono>
#include <string>

namespace h4::host::cli {

class Progress {
 public:
  /// `total` steps of `what` (e.g. "identification"); total 0 means unknown.
  Progress(std::string what, int total);
  ~Progress();
  /// Reports `done` steps and what is happening now.
  void Update(int done, const std::string& status = "");
  /// Ends the bar with a final message.
  void Finish(const std::string& message = "done");

 private:
  std::string what_;
  int total_;
  int last_percent_logged_ = -100;
  double last_log_seconds_ = -1.0;
  bool tty_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace h4::host::cli
