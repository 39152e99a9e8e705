#include "ibfvs/video/video_writer.h"

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace ibfvs {
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

namespace {

// The image grown to an even size by repeating its last column and its top
// row (rows bottom-up: the new row goes below the picture when shown top-down,
// as ffmpeg's pad filter puts it).
void pad_to_even(const ImageU8& in, ImageU8& out) {
  out = ImageU8(in.width + in.width % 2, in.height + in.height % 2, 4);
  const int shift = out.height - in.height;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const int sx = std::min(x, in.width - 1), sy = std::max(y - shift, 0);
      std::memcpy(&out.pixels[(static_cast<std::size_t>(y) * out.width + x) * 4],
                  &in.pixels[(static_cast<std::size_t>(sy) * in.width + sx) * 4], 4);
    }
}

}  // namespace

std::string ffmpeg_pipe_command(const std::string& program, const std::filesystem::path& format,
                                const std::filesystem::path& out, int width, int height,
                                double fps) {
  const std::string ext = lower_extension(format);
  std::ostringstream cmd;
  cmd << shell_quote(program) << " -nostdin -y -loglevel error -f rawvideo -pix_fmt rgba -s "
      << width << "x" << height << " -r " << fps << " -i - -vf vflip ";  // GL rows are bottom-up
  if (ext == ".webm")  // VideoEncoder's settings (video_encoder.cpp)
    cmd << "-c:v libvpx-vp9 -pix_fmt yuv420p -b:v 0 -crf 32 ";
  else if (ext != ".gif")
    cmd << "-c:v libx264 -pix_fmt yuv420p -preset ultrafast -crf 18 ";
  // The container from the extension the user gave (the file is written
  // under a temporary name); "file:" because "a:b.mp4" is a file.
  const std::string muxer = ext == ".mkv" ? "matroska" : ext.substr(1);
  cmd << "-f " << muxer << " " << shell_quote("file:" + out.string());
  return cmd.str();
}

namespace {

// The program IBFVS_FFMPEG names (the pip package names imageio-ffmpeg's);
// empty where it is unset.
std::string named_ffmpeg() {
  const char* named = std::getenv("IBFVS_FFMPEG");
  return named ? named : "";
}

}  // namespace

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps)
    : path_(path), pending_(path), width_(width), height_(height) {
  const bool gif = lower_extension(path) == ".gif";
  const std::string named = named_ffmpeg();
#if IBFVS_HAVE_LIBAV
  if (!gif && named.empty()) {
    encoder_ = std::make_unique<VideoEncoder>(pending_.temporary(), width + width % 2,
                                              height + height % 2, fps, path.string());
    writer_ = std::thread(&VideoWriter::feed, this);
    return;
  }
#endif
  // The program named, else `ffmpeg` on PATH.
  const std::string program = !named.empty() ? named : program_on_path("ffmpeg") ? "ffmpeg" : "";
  if (program.empty())
    throw InputError(path.string() + ": writing " + (gif ? "a GIF" : "video") +
                     " needs the ffmpeg program: pip install imageio-ffmpeg (the Python package "
                     "finds it), apt-get install ffmpeg, or IBFVS_FFMPEG=/path/to/ffmpeg; "
                     "or write PNG frames with --out frame%04d.png");
  if (!named.empty() && access(named.c_str(), X_OK) != 0)
    throw InputError(path.string() + ": IBFVS_FFMPEG names no program that runs (" + named + ")");
  // A dying ffmpeg must not kill us with SIGPIPE; fwrite reports the error.
  std::signal(SIGPIPE, SIG_IGN);
  // Every format but GIF wants an even size: padded here as VideoEncoder's
  // frames are (feed).
  const int w = gif ? width : width + width % 2, h = gif ? height : height + height % 2;
  // In a session of its own: a Ctrl-C at the terminal is ours to handle
  // (a shorter, finished file), not ffmpeg's.
  const std::string cmd = ffmpeg_pipe_command(program, path, pending_.temporary(), w, h, fps);
  pipe_ = popen(("exec setsid " + cmd).c_str(), "w");
  if (!pipe_) throw InputError(path.string() + ": cannot start ffmpeg");
  pad_ = !gif;
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
  ImageU8 padded;
  for (;;) {
    ImageU8 frame;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty()) break;  // closing, all written
      frame = std::move(queue_.front());
      queue_.pop_front();
    }
    changed_.notify_all();  // room in the queue
    std::string failure;
    const bool odd = frame.width % 2 != 0 || frame.height % 2 != 0;
#if IBFVS_HAVE_LIBAV
    if (encoder_) {
      try {
        if (odd) pad_to_even(frame, padded);
        to_yuv420(odd ? padded : frame, yuv_);
        encoder_->encode(yuv_);
      } catch (const std::exception& e) {
        failure = e.what();
      }
    } else
#endif
    {
      if (pad_ && odd) pad_to_even(frame, padded);
      const ImageU8& out = pad_ && odd ? padded : frame;
      if (std::fwrite(out.pixels.data(), 1, out.pixels.size(), pipe_) != out.pixels.size())
        failure = path_.string() + ": ffmpeg stopped accepting frames (see its message above)";
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!failure.empty()) {
      error_ = failure;
      queue_.clear();
      closing_ = true;
      changed_.notify_all();
      return;
    }
    if (spares_.size() < kQueued) spares_.push_back(std::move(frame));
  }
#if IBFVS_HAVE_LIBAV
  if (encoder_) {
    try {
      encoder_->finish();
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
    }
  }
#endif
}

void VideoWriter::write(ImageU8 frame) {
  if (closed_) throw InputError(path_.string() + ": video already closed");
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
  if (closed_) return;
  closed_ = true;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (writer_.joinable()) writer_.join();
  int status = 0;
  if (pipe_) {
    status = pclose(pipe_);
    pipe_ = nullptr;
  }
  if (!error_.empty()) throw InputError(error_);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw InputError(path_.string() + ": ffmpeg failed to write the video");
  pending_.commit();
}

}  // namespace ibfvs
