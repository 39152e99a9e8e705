#include "ibfvs/render/overlay_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include <glm/geometric.hpp>

#include <stb/stb_easy_font.h>

namespace ibfvs {
namespace {

glm::vec3 colour_of(int kind) {
  for (const KindStyle& k : kind_styles())
    if (k.kind == kind) return glm::vec3(k.rgb[0], k.rgb[1], k.rgb[2]) / 255.0f;
  return glm::vec3(1.0f);
}

// A quad of four corners: (0, 1, 2) and (1, 3, 2). Each corner moves to
// `to`'s (the same corner at the next step), bulging by `bulge`'s (its
// point and other); drawn in `span`.
void quad(OverlayGeometry& g, const OverlayVertex (&v)[4], const OverlayVertex (&to)[4],
          const OverlayVertex (&bulge)[4], MorphSpan span) {
  const auto base = static_cast<std::uint32_t>(g.vertices.size());
  for (int i = 0; i < 4; ++i) {
    OverlayVertex c = v[i];
    c.point_to = to[i].point;
    c.other_to = to[i].other;
    c.point_bulge = bulge[i].point;
    c.other_bulge = bulge[i].other;
    c.span = static_cast<float>(span);
    g.vertices.push_back(c);
  }
  for (const std::uint32_t i : {0u, 1u, 2u, 1u, 3u, 2u}) g.indices.push_back(base + i);
}

void quad(OverlayGeometry& g, const OverlayVertex (&v)[4], MorphSpan span = MorphSpan::Whole) {
  const OverlayVertex none[4] = {};
  quad(g, v, v, none, span);
}

// The segment a-b's corners.
void segment_corners(OverlayVertex (&v)[4], const glm::vec3& a, const glm::vec3& b,
                     const glm::vec3& colour) {
  // Each end's side is measured from its own direction to the other end,
  // which is the opposite one: the far end's sides are swapped.
  v[0] = {a, b, {-1.0f, 1.0f}, colour, kOverlayLine};
  v[1] = {a, b, {-1.0f, -1.0f}, colour, kOverlayLine};
  v[2] = {b, a, {-1.0f, -1.0f}, colour, kOverlayLine};
  v[3] = {b, a, {-1.0f, 1.0f}, colour, kOverlayLine};
}

void rectangle(OverlayGeometry& g, glm::vec2 lo, glm::vec2 hi, const glm::vec3& colour, float shape,
               MorphSpan span = MorphSpan::Whole) {
  quad(g,
       {{glm::vec3(lo.x, lo.y, 0.0f), {}, {-1.0f, -1.0f}, colour, shape},
        {glm::vec3(hi.x, lo.y, 0.0f), {}, {1.0f, -1.0f}, colour, shape},
        {glm::vec3(lo.x, hi.y, 0.0f), {}, {-1.0f, 1.0f}, colour, shape},
        {glm::vec3(hi.x, hi.y, 0.0f), {}, {1.0f, 1.0f}, colour, shape}},
       span);
}

// Text in pixels, its baseline's top left at `top_left` (y up), each of
// stb_easy_font's pixels `scale` wide.
void text(OverlayGeometry& g, const std::string& line, glm::vec2 top_left, int scale,
          MorphSpan span) {
  std::vector<char> chars(line.begin(), line.end());
  chars.push_back('\0');
  std::vector<float> buffer(chars.size() * 270 * 4);  // stb's bound: 270 bytes a character
  unsigned char white[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(0.0f, 0.0f, chars.data(), white, buffer.data(),
                                        static_cast<int>(buffer.size() * sizeof(float)));
  const auto s = static_cast<float>(scale);
  for (int q = 0; q < quads; ++q) {
    // Four vertices of x, y, z and a colour's four bytes; y down.
    const float* v = &buffer[static_cast<std::size_t>(q) * 16];
    const glm::vec2 lo(top_left.x + s * v[0], top_left.y - s * v[9]);
    const glm::vec2 hi(top_left.x + s * v[8], top_left.y - s * v[1]);
    rectangle(g, lo, hi, glm::vec3(1.0f), kOverlayPixels, span);
  }
}

// The legend of one step's counts (bottom up from the bottom left corner),
// drawn in `span`.
void legend(OverlayGeometry& g, const FlowTopology& topology, glm::ivec2 size, MorphSpan span) {
  const OverlaySizes sizes = overlay_sizes(size.y);
  const auto s = static_cast<float>(sizes.text_scale);
  const float row = 12.0f * s, swatch = 9.0f * s, pad = 4.0f * s;
  struct Entry {
    int kind;
    std::size_t count;
  };
  std::vector<Entry> entries;
  for (const KindStyle& k : kind_styles()) {
    const std::size_t count = k.kind >= 10 ? topology.count(static_cast<LineKind>(k.kind))
                                           : topology.count(static_cast<CriticalKind>(k.kind));
    if (count > 0) entries.push_back({k.kind, count});
  }
  if (entries.empty()) return;
  float width = 0.0f;
  std::vector<std::string> labels;
  for (const Entry& e : entries) {
    std::string label;
    for (const KindStyle& k : kind_styles())
      if (k.kind == e.kind) label = std::string(k.name) + " (" + std::to_string(e.count) + ")";
    std::vector<char> chars(label.begin(), label.end());
    chars.push_back('\0');
    width = std::max(width, s * static_cast<float>(stb_easy_font_width(chars.data())));
    labels.push_back(label);
  }
  const glm::vec2 origin(pad, pad);
  const float box_w = pad * 3.0f + swatch + width, box_h = pad * 2.0f + row * entries.size();
  rectangle(g, origin, origin + glm::vec2(box_w, box_h), glm::vec3(0.08f), kOverlayPixels, span);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const float y = origin.y + pad + row * static_cast<float>(entries.size() - 1 - i);
    const glm::vec2 sw(origin.x + pad, y + 0.5f * (row - swatch));
    const glm::vec3 colour = colour_of(entries[i].kind);
    if (entries[i].kind >= 10)  // a line: a bar with the lines' dark rim
      rectangle(g, sw + glm::vec2(0.0f, 0.3f * swatch), sw + glm::vec2(swatch, 0.7f * swatch),
                colour, kOverlayPixels, span);
    else
      rectangle(g, sw, sw + glm::vec2(swatch), colour,
                kOverlayLegendKind + static_cast<float>(entries[i].kind), span);
    text(g, labels[i], glm::vec2(sw.x + swatch + pad, y + row - 2.0f * s), sizes.text_scale, span);
  }
}

bool same_counts(const FlowTopology& a, const FlowTopology& b) {
  for (const KindStyle& k : kind_styles()) {
    const bool line = k.kind >= 10;
    if ((line ? a.count(static_cast<LineKind>(k.kind))
              : a.count(static_cast<CriticalKind>(k.kind))) !=
        (line ? b.count(static_cast<LineKind>(k.kind))
              : b.count(static_cast<CriticalKind>(k.kind))))
      return false;
  }
  return true;
}

}  // namespace

OverlaySizes overlay_sizes(int height) {
  OverlaySizes s;
  s.line_width = std::max(2.0f, static_cast<float>(height) / 200.0f);
  s.glyph = std::max(9.0f, static_cast<float>(height) / 45.0f);
  s.text_scale = std::max(1, static_cast<int>(std::lround(static_cast<float>(height) / 700.0f)));
  return s;
}

OverlayGeometry build_overlay(const TopologyMorph& morph, glm::ivec2 size) {
  OverlayGeometry g;
  for (const FeatureMorph& f : morph.features) {
    const glm::vec3 colour = colour_of(f.kind);
    if (f.point) {
      const auto shape = static_cast<float>(f.kind);
      const glm::vec3 &p = f.from[0], &q = f.to[0], &h = f.bulge[0];
      const OverlayVertex to{q}, bulge{h};
      quad(g,
           {{p, {}, {-1.0f, -1.0f}, colour, shape},
            {p, {}, {1.0f, -1.0f}, colour, shape},
            {p, {}, {-1.0f, 1.0f}, colour, shape},
            {p, {}, {1.0f, 1.0f}, colour, shape}},
           {to, to, to, to}, {bulge, bulge, bulge, bulge}, f.span);
      continue;
    }
    const std::size_t n = f.from.size();
    for (std::size_t i = 0; i + 1 < n + (f.closed ? 1 : 0); ++i) {
      const std::size_t j = (i + 1) % n;
      OverlayVertex a[4], b[4], h[4];
      segment_corners(a, f.from[i], f.from[j], colour);
      segment_corners(b, f.to[i], f.to[j], colour);
      segment_corners(h, f.bulge[i], f.bulge[j], colour);
      quad(g, a, b, h, f.span);
    }
  }
  if (same_counts(morph.first, morph.second)) {
    legend(g, morph.first, size, MorphSpan::Whole);
  } else {
    legend(g, morph.first, size, MorphSpan::FirstHalf);
    legend(g, morph.second, size, MorphSpan::SecondHalf);
  }
  return g;
}

OverlayGeometry build_overlay(const FlowTopology& topology, glm::ivec2 size) {
  return build_overlay(hold(topology), size);
}

std::vector<int> overlay_reference(const FlowTopology& topology, const glm::mat4& view,
                                   const glm::mat4& projection, glm::ivec2 size,
                                   const ImageF& depth) {
  std::vector<int> out(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y), 0);
  const OverlaySizes sizes = overlay_sizes(size.y);
  // A point's pixel position and window depth, lifted as the pass lifts it.
  const auto project = [&](const glm::vec3& p, glm::vec3& at) {
    glm::vec4 eye = view * glm::vec4(p, 1.0f);
    eye = glm::vec4(glm::vec3(eye) * (1.0f - kOverlayLift), eye.w);
    const glm::vec4 c = projection * eye;
    if (!(c.w > 0.0f)) return false;
    at = glm::vec3(c) / c.w;
    at = glm::vec3((at.x * 0.5f + 0.5f) * static_cast<float>(size.x),
                   (at.y * 0.5f + 0.5f) * static_cast<float>(size.y), at.z * 0.5f + 0.5f);
    // Far off the picture (near the eye's plane): left out, and no pixel
    // index beyond an int.
    return std::abs(at.x) < 1e6f && std::abs(at.y) < 1e6f;
  };
  const auto paint = [&](int x, int y, float z, int kind) {
    if (x < 0 || y < 0 || x >= size.x || y >= size.y) return;
    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(size.x) +
                          static_cast<std::size_t>(x);
    if (z <= depth.pixels[i * static_cast<std::size_t>(depth.channels)]) out[i] = kind;
  };
  for (const FeatureLine& l : topology.lines.lines) {
    const std::size_t n = l.points.size();
    for (std::size_t i = 0; i + 1 < n + (l.closed ? 1 : 0); ++i) {
      glm::vec3 a, b;
      if (!project(l.points[i].position, a) || !project(l.points[(i + 1) % n].position, b))
        continue;
      const float len = glm::length(glm::vec2(b - a));
      const int steps = std::max(1, static_cast<int>(std::ceil(len * 2.0f)));
      for (int k = 0; k <= steps; ++k) {  // the line's centre, every half pixel
        const glm::vec3 p = a + (b - a) * (static_cast<float>(k) / static_cast<float>(steps));
        paint(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)), p.z,
              static_cast<int>(l.kind));
      }
    }
  }
  for (const CriticalPoint& p : topology.critical.points) {
    glm::vec3 c;
    if (!project(p.position, c)) continue;
    const float r = 0.35f * sizes.glyph;  // within every shape's inner part
    for (int y = static_cast<int>(std::floor(c.y - r)); y <= static_cast<int>(c.y + r); ++y)
      for (int x = static_cast<int>(std::floor(c.x - r)); x <= static_cast<int>(c.x + r); ++x)
        if (std::hypot(x + 0.5f - c.x, y + 0.5f - c.y) <= r)
          paint(x, y, c.z, static_cast<int>(p.kind));
  }
  return out;
}

}  // namespace ibfvs
