#include "ibfvs/video_writer.h"

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "ibfvs/core/error.h"
#include "ibfvs/core/file_names.h"

namespace ibfvs::app {
namespace {

bool program_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::istringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && access((dir + "/" + name).c_str(), X_OK) == 0) return true;
  return false;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool is_video_path(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".mp4" || ext == ".mkv" || ext == ".webm" || ext == ".mov" || ext == ".avi" ||
         ext == ".gif";
}

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  if (!program_on_path("ffmpeg"))
    throw InputError(path.string() +
                     ": writing video needs the ffmpeg program (apt-get install ffmpeg); "
                     "or write PNG frames with --out frame%04d.png");
  // A dying ffmpeg must not kill us with SIGPIPE; fwrite reports the error.
  std::signal(SIGPIPE, SIG_IGN);
  std::string filters = "vflip";  // GL rows are bottom-up
  std::string codec;
  const std::string ext = path.extension().string();
  if (ext == ".webm") {
    codec = "-c:v libvpx-vp9 -b:v 0 -crf 32 -pix_fmt yuv420p";
  } else if (ext != ".gif") {
    // yuv420p needs even dimensions; crf 18 keeps the fine noise texture;
    // ultrafast leaves the cores to rendering (300 frames at 1024^2 to MP4:
    // 1.30x the time of no output, 1.59x with veryfast on 2 cores).
    filters += ",pad=ceil(iw/2)*2:ceil(ih/2)*2";
    codec = "-c:v libx264 -preset ultrafast -crf 18 -pix_fmt yuv420p";
  }
  std::ostringstream cmd;
  cmd << "ffmpeg -nostdin -y -loglevel error -f rawvideo -pix_fmt rgba -s " << width << "x"
      << height << " -r " << fps << " -i - -vf " << shell_quote(filters) << " " << codec << " "
      << shell_quote("file:" + path.string());  // "a:b.mp4" is a file, not a protocol
  const std::string command = cmd.str();
  pipe_ = popen(command.c_str(), "w");
  if (!pipe_) throw InputError(path.string() + ": cannot start ffmpeg");
  writer_ = std::thread(&VideoWriter::feed, this);
}

VideoWriter::~VideoWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (writer_.joinable()) writer_.join();
  if (pipe_) pclose(pipe_);
}

void VideoWriter::feed() {
  for (;;) {
    ImageU8 frame;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;  // closing, all written
      frame = std::move(queue_.front());
      queue_.pop_front();
    }
    changed_.notify_all();  // room in the queue
    if (std::fwrite(frame.pixels.data(), 1, frame.pixels.size(), pipe_) != frame.pixels.size()) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = path_.string() + ": ffmpeg stopped accepting frames (see its message above)";
      queue_.clear();
      closing_ = true;
      changed_.notify_all();
      return;
    }
  }
}

void VideoWriter::write(ImageU8 frame) {
  if (!pipe_) throw InputError(path_.string() + ": video already closed");
  if (frame.width != width_ || frame.height != height_ || frame.channels != 4)
    throw InputError(path_.string() + ": frame size changed");
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < kQueued || closing_; });
  if (!error_.empty()) throw InputError(error_);
  if (closing_) throw InputError(path_.string() + ": video already closed");
  queue_.push_back(std::move(frame));
  lock.unlock();
  changed_.notify_all();
}

void VideoWriter::close() {
  if (!pipe_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (writer_.joinable()) writer_.join();
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  if (!error_.empty()) throw InputError(error_);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw InputError(path_.string() + ": ffmpeg failed to write the video");
}

}  // namespace ibfvs::app
