#pragma once
// In-process video encoding with FFmpeg's libraries (libavcodec, libavformat):
// I420 frames in, an MP4/MKV/MOV/AVI (x264) or WebM (VP9) file out. Used by
// VideoWriter on its writer thread; no pipe, no second process.

#include <cstdint>
#include <filesystem>
#include <span>

struct AVFormatContext;
struct AVCodecContext;
struct AVStream;
struct AVFrame;
struct AVPacket;

namespace ibfvs {

class VideoEncoder {
 public:
  /// Opens `path` for width x height (both even) at `fps`; the container
  /// follows the extension. Throws InputError naming `name` (the path the
  /// user asked for, when `path` is a temporary one), by default the path.
  VideoEncoder(const std::filesystem::path& path, int width, int height, double fps,
               std::string name = {});
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  /// One frame: the Y plane, then U and V at half resolution, rows top-down
  /// (to_yuv420). Throws InputError when the encoder or the file fails.
  void encode(std::span<const std::uint8_t> i420);
  /// Flushes the encoder and writes the file's trailer.
  void finish();

 private:
  void open(double fps);  // the constructor's work
  void release();         // frees whatever is allocated
  void drain();           // writes every packet the encoder has ready
  [[noreturn]] void fail(const char* what, int code) const;

  std::filesystem::path path_;
  std::string name_;  // for messages
  int width_, height_;
  AVFormatContext* format_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVStream* stream_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  std::int64_t next_pts_ = 0;
  bool finished_ = false;
};

}  // namespace ibfvs
