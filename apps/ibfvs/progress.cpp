#include "ibfvs/progress.h"

#include <cstdio>
#include <string>

#include <unistd.h>

namespace ibfvs::app {

Progress::Progress(int total, bool enabled)
    : total_(total),
      enabled_(enabled && isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() {
  finish();
}

void Progress::update(int done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fps = elapsed > 0 ? done / elapsed : 0.0;
  const double left = fps > 0 ? (total_ - done) / fps : 0.0;
  constexpr int width = 30;
  const int filled = total_ > 0 ? width * done / total_ : width;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, ' ');
  std::fprintf(stderr, "\r[%s] %d/%d frames  %.1f fps  %d:%02d left ", bar.c_str(), done, total_,
               fps, static_cast<int>(left) / 60, static_cast<int>(left) % 60);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%80s\r", "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace ibfvs::app
