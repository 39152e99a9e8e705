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
  const std::string ext = lower_extension(path);
  yuv420_ = ext != ".gif" && width % 2 == 0 && height % 2 == 0;
  std::string input, filters, codec;
  if (yuv420_) {
    input = "-pix_fmt yuv420p";  // converted by feed(), rows top-down
  } else {
    input = "-pix_fmt rgba";
    filters = "vflip";                                               // GL rows are bottom-up
    if (ext != ".gif") filters += ",pad=ceil(iw/2)*2:ceil(ih/2)*2";  // yuv420p needs even sizes
  }
  // BT.601 limited range, said in the stream, so players do not guess.
  const std::string colour =
      "-colorspace smpte170m -color_primaries smpte170m -color_trc smpte170m -color_range tv";
  if (ext == ".webm") {
    codec = "-c:v libvpx-vp9 -b:v 0 -crf 32 -pix_fmt yuv420p " + colour;
  } else if (ext != ".gif") {
    // crf 18 keeps the fine noise texture; ultrafast leaves the cores to
    // rendering (docs/performance.md has the cost against no output).
    codec = "-c:v libx264 -preset ultrafast -crf 18 -pix_fmt yuv420p " + colour;
  }
  std::ostringstream cmd;
  cmd << "ffmpeg -nostdin -y -loglevel error -f rawvideo " << input << " -s " << width << "x"
      << height << " -r " << fps << " -i - ";
  if (!filters.empty()) cmd << "-vf " << shell_quote(filters) << " ";
  cmd << codec << " " << shell_quote("file:" + path.string());  // "a:b.mp4" is a file
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
    std::vector<std::uint8_t>* bytes = &frame.pixels;
    if (yuv420_) {
      to_yuv420(frame, yuv_);
      bytes = &yuv_;
    }
    if (std::fwrite(bytes->data(), 1, bytes->size(), pipe_) != bytes->size()) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = path_.string() + ": ffmpeg stopped accepting frames (see its message above)";
      queue_.clear();
      closing_ = true;
      changed_.notify_all();
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (spares_.size() < kQueued) spares_.push_back(std::move(frame));
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

ImageU8 VideoWriter::spare() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.empty()) return {};
  ImageU8 frame = std::move(spares_.back());
  spares_.pop_back();
  return frame;
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
