#pragma once
// Pieces of the display stage D(F_t) (RenderSettings::filter_length and
// contrast) that the GPU pass and the CPU reference (ReferenceIbfvs) share.
//
//   the filter along the flow: Gaussian weights exp(-2 (d / L)^2) at a few
//   taps out to L on both sides of the pixel along its displacement, taps
//   off the surface left out (VTK's LIC smooths along the flow so);
//
//   the contrast stage (paper 3.4: "contrast can be improved separately"):
//   values moved to mean 0.5 and a chosen standard deviation, with the mean
//   and deviation of the surface on a grid of sample points, averaged over
//   frames, so the brightness does not pump as a per-frame min/max stretch
//   does. Tested by its properties (tests/render/quality_gltest.cpp).

#include <glm/glm.hpp>

#include "ibfvs/core/image/image.h"

namespace ibfvs {

/// Sample points per side of the statistics grid: 32 (1024 points, summed by
/// one fragment every 4th frame into a running average: on llvmpipe 4096
/// cost 0.25 ms a frame; the shown RMS contrast varies by about 1% from
/// frame to frame, docs/quality.md), or the largest power of two that fits
/// the image.
int display_stats_size(int width, int height);

/// The display filter's taps per side for a length L: ceil(L / 3), at most 16
/// (0 for L = 0), spaced L / (taps + 1/2) apart: 2.3-2.7 pixels, along lines
/// that vary slowly along the flow (closer taps: A +0.001-0.002 on the
/// motorbike, docs/quality.md, for a third more reads).
int filter_taps(float length);
float filter_spacing(float length);
/// The weight exp(-2 (d / L)^2) of tap k (1-based) on each side.
float filter_weight(float length, int k);

/// How far across the flow sharpening takes a tap's two neighbours, in
/// pixels: the gain then peaks at lines 3 pixels apart, where the streaks
/// are (docs/quality.md, "thin lines"). The shader and ReferenceIbfvs both
/// read it.
inline constexpr float kSharpenReach = 1.5f;

/// The compensated warp (Resample::Compensated): F_t's bilinear sample at
/// t(x) plus c times its excess over the mean of its two neighbours
/// kSharpenReach pixels across the flow (the reads sharpening takes
/// anyway), with c = s v / kSharpenReach^2 for v the variance of the
/// bilinear weights across the flow (f (1 - f) per axis, f the fraction
/// of t(x) between texels). At s = 1 that takes back exactly the blur
/// (variance) a bilinear sample adds across the flow, and no frequency
/// gains (the loop stays stable at any alpha). Larger s gains at some
/// frequency (at most 1.06 at s = 2, one-dimensional analysis), and the
/// loop keeps (1 - alpha) of it each frame: s = 1 + min(10 alpha, 1) keeps
/// that product at most 1 for any alpha (0.95 at the default 0.1, where
/// s = 2). The Catmull-Rom warp (five more reads) gave
/// A 0.914 and W 0.97 px on the motorbike; this one 0.927 and 0.98, with
/// frames about 10% shorter in ParaView (docs/quality.md).
float compensation_scale(float alpha);

/// The tap texture (the display filter's taps, beside a grey F_t when the
/// filter and sharpening are on) holds 8 bits a channel: llvmpipe filters
/// RGBA8 texels on a fast path, and the motorbike's ParaView frame is 7%
/// shorter than with RGBA16F, A and W unchanged (docs/quality.md). Per
/// texel: the sharpened value, spread by tap_value_scale about 0.5; the log
/// of the eye depth between the frame's near and far planes (0: no
/// surface); the unit direction of the pixel's displacement, as 0.5 + 0.5 d
/// (0.5, 0.5 where it did not move). The shader and ReferenceIbfvs share
/// these; unorm8() is the 8-bit storage.
float tap_value_scale(float sharpen);
float encode_tap_value(float value, float scale);
float decode_tap_value(float stored, float scale);
/// (ln lo, 1 / (ln hi - ln lo)) from a projection's near and far planes
/// (perspective or orthographic), lo at least hi / 1000: a frame's depth map.
glm::vec2 tap_depth_map(const glm::mat4& projection);
/// The stored depth of an eye depth under a map: in [1, 255] / 255.
float encode_tap_depth(float depth, glm::vec2 map);
/// How far apart two stored depths may lie on one surface: 5% of the depth
/// and one step of rounding.
float tap_depth_tolerance(glm::vec2 map);
glm::vec2 encode_tap_direction(glm::vec2 displacement);
float unorm8(float value);

}  // namespace ibfvs
