#include "mesh_precheck.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/text.h"

namespace ibfvs::detail {
namespace {

namespace fs = std::filesystem;

// The most vertices one polygon may have: far above any real file, low enough
// that a corrupt count is caught here.
constexpr long long kMaxPolygon = 1 << 16;

class Checker {
 public:
  explicit Checker(const fs::path& path) : path_(path) {}
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_.string() + ": " + problem);
  }
  [[noreturn]] void fail_line(std::size_t line, const std::string& problem) const {
    fail("line " + std::to_string(line) + ": " + problem);
  }

 private:
  fs::path path_;
};

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// A number that a float holds (what OpenMesh reads into).
bool is_number(std::string_view w) {
  if (!w.empty() && w.front() == '+') w.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
  return ec == std::errc() && end == w.data() + w.size() && std::isfinite(v) &&
         std::abs(v) <= std::numeric_limits<float>::max();
}

bool to_integer(std::string_view w, long long& v) {
  if (!w.empty() && w.front() == '+') w.remove_prefix(1);
  const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
  return ec == std::errc() && end == w.data() + w.size();
}

// Lines of a text, numbered from 1, with the blank ones skipped.
template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t number = 0, start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    ++number;
    const std::vector<std::string_view> w = words(text.substr(start, end - start));
    if (!w.empty() && !f(number, w)) return;
    start = end + 1;
  }
}

// ------------------------------------------------------------------ OFF

void precheck_off_binary(const Checker& c, std::string_view data) {
  // Big-endian int32 counts, float32 coordinates; each face: n, n indices,
  // a colour count and that many floats.
  std::size_t at = 0;
  const auto next = [&](const char* what) {
    if (at + 4 > data.size()) c.fail("truncated binary OFF (" + std::string(what) + ")");
    std::uint32_t v = 0;
    std::memcpy(&v, data.data() + at, 4);
    at += 4;
    if constexpr (std::endian::native == std::endian::little) v = __builtin_bswap32(v);
    return v;
  };
  const std::uint32_t nv = next("counts"), nf = next("counts");
  next("counts");
  if (nv > data.size() / 12 || nf > data.size() / 16)
    c.fail("the binary OFF header declares " + std::to_string(nv) + " vertices and " +
           std::to_string(nf) + " faces, more than the file holds");
  at += 12 * static_cast<std::size_t>(nv);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const std::uint32_t n = next("a face");
    if (n < 3 || n > kMaxPolygon)
      c.fail("binary OFF face " + std::to_string(f) + " has " + std::to_string(n) + " vertices");
    for (std::uint32_t k = 0; k < n; ++k)
      if (next("a face") >= nv)
        c.fail("binary OFF face " + std::to_string(f) + " names a vertex out of range");
    const std::uint32_t colours = next("a face");
    if (colours > 4) c.fail("binary OFF face " + std::to_string(f) + " has a bad colour count");
    at += 4 * static_cast<std::size_t>(colours);
  }
  if (at > data.size()) c.fail("truncated binary OFF");
}

}  // namespace

void precheck_off(const fs::path& path, const std::string& text) {
  const Checker c(path);
  // The magic word: [ST][C][N]OFF (OpenMesh's variants); 4OFF and nOFF are
  // not surfaces in 3D.
  const std::vector<std::string_view> first = [&] {
    std::vector<std::string_view> w;
    for_each_line(text, [&](std::size_t, const std::vector<std::string_view>& line) {
      w = line;
      return false;
    });
    return w;
  }();
  if (first.empty()) c.fail("not an OFF file (no OFF keyword)");
  const std::string_view magic = first[0];
  const std::size_t off = magic.find("OFF");
  if (off == std::string_view::npos || off + 3 != magic.size())
    c.fail("not an OFF file (the first word is " + excerpt(magic) + ")");
  for (const char ch : magic.substr(0, off))
    if (ch != 'S' && ch != 'T' && ch != 'C' && ch != 'N')
      c.fail("unsupported OFF variant " + excerpt(magic) +
             " (4D and n-dimensional OFF are not surfaces)");
  if (first.size() > 1 && first[1] == "BINARY") {
    const std::size_t body = text.find('\n');
    if (body == std::string::npos) c.fail("truncated binary OFF (no data)");
    precheck_off_binary(c, std::string_view(text).substr(body + 1));
    return;
  }
  // Counts: NV NF [NE] after the magic word, on its line or the next.
  enum class Part { Magic, Counts, Vertices, Faces, Done } part = Part::Magic;
  long long nv = 0, nf = 0, seen = 0;
  for_each_line(text, [&](std::size_t number, const std::vector<std::string_view>& w) {
    std::size_t i = 0;
    if (part == Part::Magic) {
      part = Part::Counts;
      i = 1;
      if (w.size() == 1) return true;
    }
    if (part == Part::Counts) {
      // Exactly three, as OpenMesh reads them: with two, it would take the
      // first coordinate for the edge count and misread the rest.
      long long edges = 0;
      if (w.size() - i != 3 || !to_integer(w[i], nv) || !to_integer(w[i + 1], nf) ||
          !to_integer(w[i + 2], edges) || nv < 0 || nf < 0 || edges < 0)
        c.fail_line(number, "expected the counts 'VERTICES FACES EDGES'");
      if (nv == 0 || nf == 0)
        c.fail_line(number, nf == 0 ? "the header declares no faces: not a surface mesh"
                                    : "the header declares no vertices: not a surface mesh");
      part = Part::Vertices;
      return true;
    }
    if (part == Part::Vertices) {
      if (w.size() < 3) c.fail_line(number, "a vertex needs 3 coordinates");
      for (const std::string_view x : w)
        if (!is_number(x)) c.fail_line(number, excerpt(x) + " is not a number");
      if (++seen == nv) part = nf > 0 ? Part::Faces : Part::Done, seen = 0;
      return part != Part::Done;
    }
    long long k = 0;
    if (!to_integer(w[0], k) || k < 3 || k > kMaxPolygon)
      c.fail_line(number, "a face needs a vertex count of 3 or more, not " + excerpt(w[0]));
    if (w.size() < static_cast<std::size_t>(k) + 1)
      c.fail_line(number, "a face of " + std::to_string(k) + " vertices lists " +
                              std::to_string(w.size() - 1));
    for (std::size_t j = 1; j < w.size(); ++j) {
      long long index = 0;
      if (j <= static_cast<std::size_t>(k)) {
        if (!to_integer(w[j], index) || index < 0 || index >= nv)
          c.fail_line(number, "vertex index " + excerpt(w[j]) + " is out of range (the file has " +
                                  std::to_string(nv) + " vertices)");
      } else if (!is_number(w[j])) {
        c.fail_line(number, excerpt(w[j]) + " is not a number");
      }
    }
    if (++seen == nf) part = Part::Done;
    return part != Part::Done;
  });
  if (part != Part::Done)
    c.fail("truncated: the header declares " + std::to_string(nv) + " vertices and " +
           std::to_string(nf) + " faces, and fewer follow");
}

// ------------------------------------------------------------------ OBJ

void precheck_obj(const fs::path& path) {
  const Checker c(path);
  const std::string text = file_text(path);
  long long counts[3] = {0, 0, 0};  // v, vt, vn given so far
  static constexpr const char* kNames[3] = {"vertex", "texture coordinate", "normal"};
  for_each_line(text, [&](std::size_t number, std::vector<std::string_view> w) {
    if (w[0].front() == '#') return true;
    for (std::size_t i = 0; i < w.size(); ++i)
      if (w[i].front() == '#') w.resize(i);
    const std::string_view key = w[0];
    const auto numbers = [&](std::size_t least, int kind) {
      if (w.size() < least + 1)
        c.fail_line(number,
                    "'" + std::string(key) + "' needs " + std::to_string(least) + " numbers");
      for (std::size_t i = 1; i < w.size(); ++i)
        if (!is_number(w[i])) c.fail_line(number, excerpt(w[i]) + " is not a number");
      ++counts[kind];
    };
    if (key == "v") {
      numbers(3, 0);
    } else if (key == "vt") {
      numbers(1, 1);
    } else if (key == "vn") {
      numbers(3, 2);
    } else if (key == "f") {
      if (w.size() < 4) c.fail_line(number, "a face needs 3 or more vertices");
      for (std::size_t i = 1; i < w.size(); ++i) {
        std::string_view ref = w[i];
        for (int part = 0; part < 3; ++part) {
          const std::size_t slash = ref.find('/');
          const std::string_view index = ref.substr(0, slash);
          if (index.empty() && part == 1 && slash != std::string_view::npos) {
            ref.remove_prefix(slash + 1);  // i//n
            continue;
          }
          long long k = 0;
          if (!to_integer(index, k) || k == 0)
            c.fail_line(number, "bad face vertex " + excerpt(w[i]));
          const long long resolved = k > 0 ? k : counts[part] + k + 1;
          if (resolved < 1 || resolved > counts[part])
            c.fail_line(number, "the face names " + std::string(kNames[part]) + " " +
                                    std::to_string(k) + " but " + std::to_string(counts[part]) +
                                    " are given before it");
          if (slash == std::string_view::npos) break;
          if (part == 2) c.fail_line(number, "bad face vertex " + excerpt(w[i]));
          ref.remove_prefix(slash + 1);
        }
      }
    }
    return true;
  });
}

// ------------------------------------------------------------------ PLY

namespace {

struct PlyProperty {
  std::string name;
  int size = 0;        // bytes of a scalar, or of a list's items
  int count_size = 0;  // lists: bytes of the length; 0: a scalar
  bool integer = false;
  bool is_unsigned = false;  // uchar, uint8, ushort, ...: the integer types named u...
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

int type_size(std::string_view t, bool& integer) {
  static const std::array<std::pair<std::string_view, int>, 16> kTypes = {{{"char", 1},
                                                                           {"uchar", 1},
                                                                           {"int8", 1},
                                                                           {"uint8", 1},
                                                                           {"short", 2},
                                                                           {"ushort", 2},
                                                                           {"int16", 2},
                                                                           {"uint16", 2},
                                                                           {"int", 4},
                                                                           {"uint", 4},
                                                                           {"int32", 4},
                                                                           {"uint32", 4},
                                                                           {"float", -4},
                                                                           {"float32", -4},
                                                                           {"double", -8},
                                                                           {"float64", -8}}};
  for (const auto& [name, size] : kTypes)
    if (name == t) {
      integer = size > 0;
      return std::abs(size);
    }
  return 0;
}

bool is_face_indices(const PlyElement& e, const PlyProperty& p) {
  return e.name == "face" && p.count_size &&
         (p.name == "vertex_indices" || p.name == "vertex_index");
}

// An unsigned or signed little/big-endian integer of `size` bytes at `p`.
long long read_integer(const char* p, int size, bool big, bool is_signed) {
  unsigned long long v = 0;
  for (int k = 0; k < size; ++k) {
    const auto byte = static_cast<unsigned char>(p[big ? k : size - 1 - k]);
    v = (v << 8) | byte;
  }
  if (is_signed && size < 8 && (v >> (8 * size - 1)) & 1) v |= ~0ULL << (8 * size);
  return static_cast<long long>(v);
}

}  // namespace

void precheck_ply(const fs::path& path) {
  const Checker c(path);
  const std::string data = file_text(path);
  std::vector<PlyElement> elements;
  std::string format;
  std::size_t at = 0, number = 0;
  bool ended = false;
  while (!ended) {
    const std::size_t end = data.find('\n', at);
    if (end == std::string::npos) c.fail("truncated PLY header (no end_header)");
    const std::vector<std::string_view> w = words(std::string_view(data).substr(at, end - at));
    at = end + 1;
    ++number;
    if (w.empty()) c.fail_line(number, "an empty line in the PLY header");
    const std::string_view key = w[0];
    if (number == 1) {
      if (key != "ply" || w.size() != 1) c.fail("not a PLY file (the first line is not 'ply')");
    } else if (key == "format") {
      if (w.size() != 3 || w[2] != "1.0" ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        c.fail_line(number, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      format = w[1];
    } else if (key == "comment" || key == "obj_info") {
      // OpenMesh reads the header word by word, so a keyword in a comment
      // counts as one there (the fuzzers found an 'element' in an obj_info).
      for (std::size_t k = 1; k < w.size(); ++k)
        if (w[k] == "element" || w[k] == "property" || w[k] == "format" || w[k] == "end_header")
          c.fail_line(number,
                      "a " + std::string(key) + " holding the keyword '" + std::string(w[k]) + "'");
    } else if (key == "element") {
      PlyElement e;
      if (w.size() != 3 || !to_integer(w[2], e.count) || e.count < 0)
        c.fail_line(number, "expected 'element NAME COUNT'");
      e.name = w[1];
      elements.push_back(std::move(e));
    } else if (key == "property") {
      if (elements.empty()) c.fail_line(number, "a property before any element");
      PlyProperty p;
      if (w.size() == 3) {
        p.size = type_size(w[1], p.integer);
        p.is_unsigned = p.integer && w[1].starts_with('u');
        p.name = w[2];
      } else if (w.size() == 5 && w[1] == "list") {
        bool count_integer = false;
        p.count_size = type_size(w[2], count_integer);
        p.size = type_size(w[3], p.integer);
        p.is_unsigned = p.integer && w[3].starts_with('u');
        if (!count_integer) p.count_size = 0, p.size = 0;
        p.name = w[4];
      }
      if (p.size == 0)
        c.fail_line(number,
                    "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      elements.back().properties.push_back(std::move(p));
    } else if (key == "end_header") {
      ended = true;
    } else {
      c.fail_line(number, "unknown PLY header keyword " + excerpt(key));
    }
  }
  if (format.empty()) c.fail("the PLY header has no format line");
  // Every element's items take at least a byte each (the fuzzers found
  // OpenMesh reserving gigabytes for an element of no properties).
  for (const PlyElement& e : elements)
    if (static_cast<unsigned long long>(e.count) > data.size())
      c.fail("the header declares " + std::to_string(e.count) + " " + e.name +
             " items, more than a file of " + std::to_string(data.size()) + " bytes can hold");
  long long vertices = -1;
  for (const PlyElement& e : elements)
    if (e.name == "vertex") vertices = e.count;
  if (vertices < 0) c.fail("the PLY header declares no vertex element");

  const std::string_view body = std::string_view(data).substr(at);
  if (format == "ascii") {
    // Whitespace-separated values, element after element.
    std::size_t i = 0;
    const auto next = [&](const PlyElement& e) {
      while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i]))) ++i;
      const std::size_t start = i;
      while (i < body.size() && !std::isspace(static_cast<unsigned char>(body[i]))) ++i;
      if (i == start) c.fail("truncated: the " + e.name + " data ends early");
      return body.substr(start, i - start);
    };
    for (const PlyElement& e : elements)
      for (long long item = 0; item < e.count && !e.properties.empty(); ++item)
        for (const PlyProperty& p : e.properties) {
          long long n = 1;
          if (p.count_size) {
            const std::string_view w = next(e);
            if (!to_integer(w, n) || n < 0 || n > kMaxPolygon)
              c.fail("bad list length " + excerpt(w) + " in " + e.name + " " +
                     std::to_string(item));
            if (is_face_indices(e, p) && n < 3)
              c.fail("face " + std::to_string(item) + " has fewer than 3 vertices");
          }
          for (long long k = 0; k < n; ++k) {
            const std::string_view w = next(e);
            long long v = 0;
            if (is_face_indices(e, p)) {
              if (!to_integer(w, v) || v < 0 || v >= vertices)
                c.fail("face " + std::to_string(item) + ": vertex index " + excerpt(w) +
                       " is out of range (the file has " + std::to_string(vertices) + " vertices)");
            } else if (p.integer ? !to_integer(w, v) : !is_number(w)) {
              c.fail(e.name + " " + std::to_string(item) + ": " + excerpt(w) + " is not a " +
                     (p.integer ? "whole number" : "number"));
            } else if (p.is_unsigned && v < 0) {
              // OpenMesh's ASCII reader stops reading at the sign and then
              // loops on what follows, growing a list without end (the
              // fuzzers found it with a colour of -255).
              c.fail(e.name + " " + std::to_string(item) + ": " + excerpt(w) +
                     " is negative, but " + p.name + " is unsigned");
            }
          }
        }
    return;
  }
  const bool big = format == "binary_big_endian";
  std::size_t pos = 0;
  for (const PlyElement& e : elements)
    for (long long item = 0; item < e.count && !e.properties.empty(); ++item)
      for (const PlyProperty& p : e.properties) {
        long long n = 1;
        if (p.count_size) {
          if (pos + p.count_size > body.size())
            c.fail("truncated: the " + e.name + " data ends early");
          n = read_integer(body.data() + pos, p.count_size, big, true);
          pos += p.count_size;
          if (n < 0 || n > kMaxPolygon)
            c.fail("bad list length " + std::to_string(n) + " in " + e.name + " " +
                   std::to_string(item));
          if (is_face_indices(e, p) && n < 3)
            c.fail("face " + std::to_string(item) + " has fewer than 3 vertices");
        }
        const std::size_t bytes = static_cast<std::size_t>(n) * static_cast<std::size_t>(p.size);
        if (pos + bytes > body.size()) c.fail("truncated: the " + e.name + " data ends early");
        if (is_face_indices(e, p))
          for (long long k = 0; k < n; ++k) {
            const long long v = read_integer(body.data() + pos + k * p.size, p.size, big, true);
            if (v < 0 || v >= vertices)
              c.fail("face " + std::to_string(item) + ": vertex index " + std::to_string(v) +
                     " is out of range (the file has " + std::to_string(vertices) + " vertices)");
          }
        pos += bytes;
      }
}

}  // namespace ibfvs::detail
