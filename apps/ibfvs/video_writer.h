#pragma once
// Video output through the ffmpeg program: raw RGBA frames go down a pipe, and
// ffmpeg encodes in its own process, beside the rendering.

#include <cstdio>
#include <filesystem>

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

  /// Writes one RGBA8 frame (rows bottom-up, as read back). Throws InputError
  /// if ffmpeg has stopped.
  void write(const ImageU8& frame);
  /// Waits for ffmpeg; throws InputError if it failed.
  void close();

 private:
  std::filesystem::path path_;
  std::FILE* pipe_ = nullptr;
  int width_, height_;
};

}  // namespace ibfvs::app
