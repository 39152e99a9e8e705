// The splits of polygon lists seen before (mesh/polygon.h, SplitMemory).
#include <algorithm>
#include <array>
#include <limits>
#include <string>

#include "ibfvs/core/mesh/polygon.h"
#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/isolation.h"
#include "ibfvs/core/support/limits.h"

namespace ibfvs {

// One list of polygons as it came (on `points` points) and its split.
struct SplitMemory::Entry {
  std::uint64_t hash = 0, points = 0;
  std::vector<std::uint32_t> offsets, ids;
  std::shared_ptr<const PolygonSplit> split;
  std::uint64_t made = 0, used = 0;
  [[nodiscard]] std::uint64_t bytes() const {
    return (offsets.size() + ids.size() + split->polygon.size()) * sizeof(std::uint32_t) +
           split->triangles.size() * sizeof(Triangle);
  }
};

namespace {

// splitmix64's finaliser on every offset and id, four lanes (consecutive
// values' multiplications overlap), folded with the counts: which kept
// list to compare in full.
template <std::signed_integral Index>
std::uint64_t digest(const PolygonList<Index>& polygons, std::uint64_t points) {
  const auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  std::array<std::uint64_t, 4> lanes{mix(points), mix(polygons.offsets.size()),
                                     mix(polygons.ids.size()), 0x9e3779b97f4a7c15ull};
  const auto fold = [&](std::span<const Index> values, std::uint64_t salt) {
    std::size_t k = 0;
    for (; k + 4 <= values.size(); k += 4)
      for (std::size_t l = 0; l < 4; ++l)
        lanes[l] = mix(lanes[l] ^ (static_cast<std::uint64_t>(values[k + l]) + salt));
    for (; k < values.size(); ++k)
      lanes[0] = mix(lanes[0] ^ (static_cast<std::uint64_t>(values[k]) + salt));
  };
  fold(polygons.offsets, 0x243f6a8885a308d3ull);
  fold(polygons.ids, 0x13198a2e03707344ull);
  return mix(lanes[0] ^ mix(lanes[1] ^ mix(lanes[2] ^ mix(lanes[3]))));
}

template <std::signed_integral Index>
bool same_values(const std::vector<std::uint32_t>& kept, std::span<const Index> given) {
  if (kept.size() != given.size()) return false;
  for (std::size_t k = 0; k < kept.size(); ++k)
    if (given[k] < 0 || static_cast<std::uint64_t>(given[k]) != kept[k]) return false;
  return true;
}

// The values as 32-bit numbers, or false where one does not fit (a list of
// over 4 billion ids, or an id no triangle can hold): not kept then.
template <std::signed_integral Index>
bool narrow(std::span<const Index> values, std::vector<std::uint32_t>& out) {
  out.resize(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (values[k] < 0 ||
        static_cast<std::uint64_t>(values[k]) > std::numeric_limits<std::uint32_t>::max())
      return false;
    out[k] = static_cast<std::uint32_t>(values[k]);
  }
  return true;
}

}  // namespace

SplitMemory::SplitMemory(std::uint64_t budget)
    : budget_(budget > 0 ? budget : std::min<std::uint64_t>(memory_limit() / 16, 1ull << 30)) {}

SplitMemory::~SplitMemory() = default;

std::size_t SplitMemory::size() const {
  return entries_.size();
}

template <std::signed_integral Index>
std::shared_ptr<const PolygonSplit> SplitMemory::split(const PolygonList<Index>& polygons,
                                                       std::span<const glm::vec3> points) {
  const std::uint64_t hash = digest(polygons, points.size());
  for (const std::unique_ptr<Entry>& e : entries_)
    if (e->hash == hash && e->points == points.size() &&
        same_values(e->offsets, polygons.offsets) && same_values(e->ids, polygons.ids)) {
      e->used = ++clock_;
      return e->split;
    }
  auto split = std::make_shared<const PolygonSplit>(split_polygons(polygons, points));
  auto entry = std::make_unique<Entry>();
  if (narrow(polygons.offsets, entry->offsets) && narrow(polygons.ids, entry->ids)) {
    entry->hash = hash;
    entry->points = points.size();
    entry->split = split;
    keep(std::move(entry));
  }
  return split;
}

template std::shared_ptr<const PolygonSplit> SplitMemory::split(const PolygonList<int>&,
                                                                std::span<const glm::vec3>);
template std::shared_ptr<const PolygonSplit> SplitMemory::split(const PolygonList<long>&,
                                                                std::span<const glm::vec3>);
template std::shared_ptr<const PolygonSplit> SplitMemory::split(const PolygonList<long long>&,
                                                                std::span<const glm::vec3>);

void SplitMemory::keep(std::unique_ptr<Entry> entry) {
  entry->made = ++made_;
  entry->used = ++clock_;
  bytes_ += entry->bytes();
  entries_.push_back(std::move(entry));
  // The least recently used go first; the newest stays, whatever its size.
  while (bytes_ > budget_ && entries_.size() > 1) {
    const auto oldest =
        std::min_element(entries_.begin(), entries_.end() - 1,
                         [](const std::unique_ptr<Entry>& a, const std::unique_ptr<Entry>& b) {
                           return a->used < b->used;
                         });
    bytes_ -= (*oldest)->bytes();
    entries_.erase(oldest);
  }
}

void SplitMemory::put_since(ByteWriter& out, std::uint64_t since) const {
  std::uint64_t count = 0;
  for (const std::unique_ptr<Entry>& e : entries_) count += e->made > since ? 1 : 0;
  out.put(count);
  for (const std::unique_ptr<Entry>& e : entries_) {
    if (e->made <= since) continue;
    out.put(e->hash);
    out.put(e->points);
    out.put(e->offsets);
    out.put(e->ids);
    out.put(e->split->triangles);
    out.put(e->split->polygon);
    out.put(static_cast<std::uint64_t>(e->split->dropped));
  }
}

void SplitMemory::take(ByteReader& in) {
  const auto count = in.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < count; ++k) {
    auto entry = std::make_unique<Entry>();
    auto split = std::make_shared<PolygonSplit>();
    entry->hash = in.get<std::uint64_t>();
    entry->points = in.get<std::uint64_t>();
    entry->offsets = in.get_vector<std::uint32_t>();
    entry->ids = in.get_vector<std::uint32_t>();
    split->triangles = in.get_vector<Triangle>();
    split->polygon = in.get_vector<std::uint32_t>();
    split->dropped = static_cast<std::size_t>(in.get<std::uint64_t>());
    // What a split of these polygons can be: a polygon and points of each
    // triangle that are there.
    const std::size_t polygons = entry->offsets.empty() ? 0 : entry->offsets.size() - 1;
    bool sound = split->polygon.size() == split->triangles.size();
    for (std::size_t t = 0; sound && t < split->triangles.size(); ++t)
      sound = split->polygon[t] < polygons && split->triangles[t][0] < entry->points &&
              split->triangles[t][1] < entry->points && split->triangles[t][2] < entry->points;
    if (!sound) throw InputError("polygon splits: a triangle refers to what is not there");
    const bool known = std::any_of(entries_.begin(), entries_.end(), [&](const auto& e) {
      return e->hash == entry->hash && e->points == entry->points && e->offsets == entry->offsets &&
             e->ids == entry->ids;
    });
    if (known) continue;
    entry->split = std::move(split);
    keep(std::move(entry));
  }
}

}  // namespace ibfvs
