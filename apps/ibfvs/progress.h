#pragma once
// A one-line progress bar on stderr for long renders: frames done, frames per
// second, time left. Silent when stderr is not a terminal.

#include <chrono>

namespace ibfvs::app {

class Progress {
 public:
  /// `enabled` false (or stderr not a terminal) makes every call a no-op.
  Progress(int total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void update(int done);
  /// Clears the line.
  void finish();

 private:
  int total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace ibfvs::app
