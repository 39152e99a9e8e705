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

/// Bilinear sample of channel c at (x, y) in pixels, texel centres at +0.5,
/// clamped at the edges (a GL_LINEAR texture with CLAMP_TO_EDGE).
float sample_bilinear(const ImageF& image, float x, float y, int c);

}  // namespace ibfvs
