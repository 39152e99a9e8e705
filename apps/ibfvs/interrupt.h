#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a long render: the first asks the
// render loop to stop after the frame under way, so that the output is
// finished properly (a shorter, valid video); the second is the default
// action again, for a render that does not stop.

#include <csignal>

namespace ibfvs::app {

class InterruptGuard {
 public:
  InterruptGuard();   // installs the handlers
  ~InterruptGuard();  // restores the previous ones
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// The signal that asked to stop (SIGINT, SIGTERM), or 0.
  [[nodiscard]] static int requested();
  /// "Ctrl-C" or "SIGTERM", for messages.
  [[nodiscard]] static const char* name(int signal);

 private:
  struct sigaction previous_int_ {
  }, previous_term_{};
};

}  // namespace ibfvs::app
