#pragma once
// The page writer's parts (web_page.cpp puts them together): the header as
// JSON (nlohmann-json, in the shape web/schema/page.schema.json gives), the
// binary block of arrays, and the looks.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "ibfvs/core/scene/scene_prep.h"
#include "ibfvs/core/support/names.h"
#include "ibfvs/page/web_page.h"

namespace ibfvs::page {

/// The header's JSON: members in the order written, numbers in single
/// precision (the page's values are floats: the shortest text that reads
/// back as the same float).
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool,
                                  std::int64_t, std::uint64_t, float>;

[[nodiscard]] Json vec3(const glm::vec3& v);
[[nodiscard]] Json matrix(const glm::mat4& m);

/// The binary block: arrays appended at 4-byte boundaries, each named in the
/// header by an array reference (its offset, and its length in elements or
/// with a codec in encoded bytes).
class Block {
 public:
  template <typename T>
  Json add(const std::vector<T>& values) {
    return add_bytes(values.data(), values.size() * sizeof(T), values.size());
  }
  /// Per-vertex arrays (`components` values a vertex, 4..256 bytes in all)
  /// through meshoptimizer's vertex codec, which the page's runtime decodes
  /// with the same library's decoder (npm meshoptimizer).
  template <typename T>
  Json add_vertices(const std::vector<T>& values, std::size_t components) {
    return add_encoded_vertices(values.data(), values.size(), components * sizeof(T), components);
  }
  /// Triangle indices through meshoptimizer's index codec.
  Json add_indices(const std::vector<std::uint32_t>& indices, std::size_t vertices);
  [[nodiscard]] const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  Json add_bytes(const void* data, std::size_t bytes, std::size_t length);
  Json add_encoded_vertices(const void* data, std::size_t elements, std::size_t stride,
                            std::size_t components);
  std::vector<std::uint8_t> bytes_;
};

/// A style that takes the page's data, with the scene in its look.
struct Restyle {
  EnumName<Style> style;
  PreparedScene scene;
};

/// Every style that takes the scene's data (restyled), in table order.
[[nodiscard]] std::vector<Restyle> restyles(const PreparedScene& p);

/// The page's looks: the scene's own first (named by its style where it is
/// that style's look), then each style that takes the same data, each once.
/// `finest`: the columns and rows of the page's noise phases.
[[nodiscard]] Json looks(const PreparedScene& p, const std::vector<Restyle>& styles,
                         glm::ivec2 finest, glm::vec3 centre, bool moving);

/// What the arrays are made from: every step's data, and the box the
/// positions are stored in.
struct SceneSteps {
  std::vector<StepData> data;
  std::vector<int> step_mesh;  ///< 0 the first step's mesh, k > 0 the k-th mesh of its own
  bool moving = false;
  glm::vec3 lo{0.0f}, hi{0.0f};
};

/// The header's "arrays", their bytes appended to `block`. Fills the
/// report's motion and mesh counts.
[[nodiscard]] Json arrays(const PreparedScene& p, const SceneSteps& steps,
                          const std::vector<float>& phases, Block& block, WebPageReport* report);

}  // namespace ibfvs::page
