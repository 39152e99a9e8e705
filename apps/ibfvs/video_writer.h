#pragma once
// Video output through the ffmpeg program: raw frames go down a pipe, and
// ffmpeg encodes in its own process, beside the rendering. A thread of ours
// feeds the pipe, so the render loop only hands frames over (issue 7: video
// must not be the bottleneck). For encoders that take YUV 4:2:0 (MP4, MKV,
// MOV, AVI, WebM) and even image sizes the writer thread converts each frame
// (to_yuv420, about 4 times cheaper than ffmpeg's conversion here) and pipes
// 1.5 bytes per pixel instead of 4. GIF and odd sizes go as RGBA.

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ibfvs/core/image.h"

namespace ibfvs::app {

/// True when `path` has a video extension (.mp4, .mkv, .webm, .mov, .avi, .gif).
bool is_video_path(const std::filesystem::path& path);

class VideoWriter {
 public:
  /// Starts ffmpeg. Throws InputError when ffmpeg is missing or cannot start.
  VideoWriter(const std::filesystem::path& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Queues one RGBA8 frame (rows bottom-up, as read back) for the writer
  /// thread; blocks only while kQueued frames are waiting. Throws InputError
  /// if ffmpeg has stopped.
  void write(ImageU8 frame);
  /// A frame the writer thread is done with, to read the next one into
  /// without allocating (empty when none is free yet).
  [[nodiscard]] ImageU8 spare();
  /// True when frames travel as YUV 4:2:0.
  [[nodiscard]] bool yuv420() const { return yuv420_; }
  /// Writes what is queued, waits for ffmpeg; throws InputError if it failed.
  void close();

 private:
  static constexpr std::size_t kQueued = 4;
  void feed();  // the writer thread

  std::filesystem::path path_;
  std::FILE* pipe_ = nullptr;
  int width_, height_;
  bool yuv420_ = false;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ImageU8> queue_;
  std::vector<ImageU8> spares_;    // written frames, for spare()
  std::vector<std::uint8_t> yuv_;  // the writer thread's I420 buffer
  bool closing_ = false;
  std::string error_;  // set by the writer thread
  std::thread writer_;
};

}  // namespace ibfvs::app
