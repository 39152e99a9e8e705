#include "ibfvs/video/video_encoder.h"

#include <cstring>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
}

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace ibfvs {

VideoEncoder::VideoEncoder(const std::filesystem::path& path, int width, int height, double fps,
                           std::string name)
    : path_(path),
      name_(name.empty() ? path.string() : std::move(name)),
      width_(width),
      height_(height) {
  try {
    open(fps);
  } catch (...) {
    release();  // the destructor does not run for a constructor that throws
    throw;
  }
}

void VideoEncoder::open(double fps) {
  const std::filesystem::path& path = path_;
  const int width = width_, height = height_;
  if (width < 2 || height < 2 || width % 2 != 0 || height % 2 != 0)
    throw InputError(name_ + ": the encoder needs an even width and height");
  av_log_set_level(AV_LOG_ERROR);  // x264's statistics are not ours to print
  // "file:" so that a name with a colon is not read as a protocol.
  const std::string url = "file:" + path.string();
  int code = avformat_alloc_output_context2(&format_, nullptr, nullptr, url.c_str());
  if (code < 0 || format_ == nullptr) fail("no container for this extension", code);
  const bool webm = lower_extension(path) == ".webm";
  const char* encoder_name = webm ? "libvpx-vp9" : "libx264";
  const AVCodec* encoder = avcodec_find_encoder_by_name(encoder_name);
  if (encoder == nullptr)
    throw InputError(name_ + ": FFmpeg has no " + encoder_name + " encoder here");
  stream_ = avformat_new_stream(format_, nullptr);
  codec_ = avcodec_alloc_context3(encoder);
  if (stream_ == nullptr || codec_ == nullptr) fail("out of memory", AVERROR(ENOMEM));
  codec_->width = width;
  codec_->height = height;
  codec_->pix_fmt = AV_PIX_FMT_YUV420P;
  codec_->framerate = av_d2q(fps, 100000);
  codec_->time_base = av_inv_q(codec_->framerate);
  // BT.601 limited range, as to_yuv420 writes it, said in the stream.
  codec_->color_range = AVCOL_RANGE_MPEG;
  codec_->colorspace = AVCOL_SPC_SMPTE170M;
  codec_->color_primaries = AVCOL_PRI_SMPTE170M;
  codec_->color_trc = AVCOL_TRC_SMPTE170M;
  codec_->thread_count = 1;  // the writer thread; the cores are the renderer's
  if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* options = nullptr;
  if (webm) {
    codec_->bit_rate = 0;  // constant quality
    av_dict_set(&options, "crf", "32", 0);
  } else {
    // crf 18 keeps the fine noise texture; ultrafast leaves the cores to rendering.
    av_dict_set(&options, "preset", "ultrafast", 0);
    av_dict_set(&options, "crf", "18", 0);
  }
  code = avcodec_open2(codec_, encoder, &options);
  av_dict_free(&options);
  if (code < 0) fail("cannot open the encoder", code);
  code = avcodec_parameters_from_context(stream_->codecpar, codec_);
  if (code < 0) fail("cannot set the stream parameters", code);
  stream_->time_base = codec_->time_base;
  if ((format_->oformat->flags & AVFMT_NOFILE) == 0) {
    code = avio_open(&format_->pb, url.c_str(), AVIO_FLAG_WRITE);
    if (code < 0) fail("cannot open for writing", code);
  }
  code = avformat_write_header(format_, nullptr);
  if (code < 0) fail("cannot write the header", code);
  frame_ = av_frame_alloc();
  packet_ = av_packet_alloc();
  if (frame_ == nullptr || packet_ == nullptr) fail("out of memory", AVERROR(ENOMEM));
  frame_->format = AV_PIX_FMT_YUV420P;
  frame_->width = width;
  frame_->height = height;
  code = av_frame_get_buffer(frame_, 0);
  if (code < 0) fail("cannot allocate a frame", code);
}

VideoEncoder::~VideoEncoder() {
  release();
}

void VideoEncoder::release() {
  av_packet_free(&packet_);
  av_frame_free(&frame_);
  avcodec_free_context(&codec_);
  if (format_ != nullptr) {
    if ((format_->oformat->flags & AVFMT_NOFILE) == 0) avio_closep(&format_->pb);
    avformat_free_context(format_);
    format_ = nullptr;
  }
}

void VideoEncoder::fail(const char* what, int code) const {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  throw InputError(name_ + ": " + what + " (" + text + ")");
}

void VideoEncoder::encode(std::span<const std::uint8_t> i420) {
  const std::size_t luma = static_cast<std::size_t>(width_) * height_;
  if (i420.size() != luma + luma / 2) throw InputError(name_ + ": a frame of the wrong size");
  int code = av_frame_make_writable(frame_);
  if (code < 0) fail("cannot write a frame", code);
  const std::uint8_t* planes[3] = {i420.data(), i420.data() + luma, i420.data() + luma * 5 / 4};
  const int widths[3] = {width_, width_ / 2, width_ / 2};
  const int heights[3] = {height_, height_ / 2, height_ / 2};
  for (int p = 0; p < 3; ++p)
    av_image_copy_plane(frame_->data[p], frame_->linesize[p], planes[p], widths[p], widths[p],
                        heights[p]);
  frame_->pts = next_pts_++;
  code = avcodec_send_frame(codec_, frame_);
  if (code < 0) fail("the encoder refused a frame", code);
  drain();
}

void VideoEncoder::drain() {
  for (;;) {
    const int code = avcodec_receive_packet(codec_, packet_);
    if (code == AVERROR(EAGAIN) || code == AVERROR_EOF) return;
    if (code < 0) fail("encoding failed", code);
    // Every frame lasts one frame interval. x264 leaves the duration unset,
    // and MP4's edit list then ends at the last frame's start, so players
    // (and ffprobe) drop that frame.
    if (packet_->duration == 0) packet_->duration = 1;
    av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
    packet_->stream_index = stream_->index;
    const int written = av_interleaved_write_frame(format_, packet_);  // takes the packet
    if (written < 0) fail("cannot write to the file", written);
  }
}

void VideoEncoder::finish() {
  if (finished_) return;
  finished_ = true;
  const int code = avcodec_send_frame(codec_, nullptr);  // flush
  if (code < 0) fail("cannot flush the encoder", code);
  drain();
  const int trailer = av_write_trailer(format_);
  if (trailer < 0) fail("cannot finish the file", trailer);
  if ((format_->oformat->flags & AVFMT_NOFILE) == 0) {
    const int closed = avio_closep(&format_->pb);
    if (closed < 0) fail("cannot close the file", closed);
  }
}

}  // namespace ibfvs
