#pragma once
// Video output beside the rendering: the render loop hands frames to a
// writer thread of ours (issue 7: video must not be the bottleneck). Two ways
// to encode them, the same codecs and settings (x264 for MP4/MKV/MOV/AVI, VP9
// for WebM; odd sizes padded by one column or row):
// - in-process with FFmpeg's libraries (VideoEncoder, after to_yuv420), in
//   builds with them (IBFVS_HAVE_LIBAV: the Debian build);
// - through a pipe to the ffmpeg program: always for GIF (it makes the
//   palette); for every format where the build has no libav (the pip
//   package: its Python finds the program of imageio-ffmpeg) or where
//   IBFVS_FFMPEG names the program to use.

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ibfvs/core/image/image.h"
#include "ibfvs/core/support/file_names.h"
#if IBFVS_HAVE_LIBAV
#include "ibfvs/video/video_encoder.h"
#endif

namespace ibfvs {

/// True when `path` has a video extension (.mp4, .mkv, .webm, .mov, .avi, .gif).
bool is_video_path(const std::filesystem::path& path);

/// The ffmpeg program's command line that reads width x height RGBA frames
/// (rows bottom-up) from its standard input at `fps` and writes `out` in the
/// format its extension names, with the settings of the in-process encoder.
/// `program` is the path or name of ffmpeg; both are quoted for the shell.
std::string ffmpeg_pipe_command(const std::string& program, const std::filesystem::path& format,
                                const std::filesystem::path& out, int width, int height,
                                double fps);

class VideoWriter {
 public:
  /// Opens the encoder or starts ffmpeg. Throws InputError when that fails,
  /// naming the path (with how to get ffmpeg where it is missing).
  VideoWriter(const std::filesystem::path& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Queues one RGBA8 frame (rows bottom-up, as read back) for the writer
  /// thread; blocks only while kQueued frames are waiting. Throws InputError
  /// if encoding has failed.
  void write(ImageU8 frame);
  /// A frame the writer thread is done with, to read the next one into
  /// without allocating (empty when none is free yet).
  [[nodiscard]] ImageU8 spare();
  /// Writes what is queued, finishes the file and gives it its name (until
  /// then it has a temporary one: a writer destroyed without close(), by an
  /// error or an exception, leaves no file). Throws InputError if that failed.
  void close();

 private:
  static constexpr std::size_t kQueued = 4;
  void feed();  // the writer thread

  std::filesystem::path path_;
  PendingFile pending_;  // written under a temporary name, renamed by close()
#if IBFVS_HAVE_LIBAV
  std::unique_ptr<VideoEncoder> encoder_;  // in-process: all but GIF
#endif
  std::FILE* pipe_ = nullptr;  // or the ffmpeg program
  int width_, height_;
  bool closed_ = false;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ImageU8> queue_;
  std::vector<ImageU8> spares_;    // written frames, for spare()
  std::vector<std::uint8_t> yuv_;  // the writer thread's I420 buffer
  bool pad_ = false;               // the pipe: frames padded to an even size
  bool closing_ = false;
  std::string error_;  // set by the writer thread
  std::thread writer_;
};

}  // namespace ibfvs
