// glTF 2.0 export of a mesh with a texture map, through tinygltf (Debian's
// libtinygltf-dev). The model is assembled here; tinygltf serialises it.

#include "ibfvs/core/mesh/mesh_io.h"

#include <fstream>
#include <iterator>
#include <limits>

#include <tiny_gltf.h>
#include <glm/common.hpp>

#include "ibfvs/core/support/error.h"
#include "ibfvs/core/support/file_names.h"

namespace fs = std::filesystem;

namespace ibfvs {
namespace {

// Appends `bytes` to the buffer, padded to four bytes, and returns a view on it.
int add_view(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* b = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), b, b + size);
  data.resize((data.size() + 3) / 4 * 4, 0);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int add_accessor(tinygltf::Model& model, int view, int component, int type, std::size_t count,
                 std::vector<double> min = {}, std::vector<double> max = {}) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.type = type;
  a.count = count;
  a.minValues = std::move(min);
  a.maxValues = std::move(max);
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size()) - 1;
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the texture image");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

void write_gltf_textured(const TriMesh& mesh, const std::vector<glm::vec2>& uv,
                         const fs::path& path, const fs::path& texture_png) {
  if (uv.size() != mesh.vertex_count())
    throw InputError(path.string() + ": one texture coordinate per vertex is needed");
  const std::string ext = lower_extension(path);
  if (ext != ".gltf" && ext != ".glb")
    throw InputError(path.string() + ": a glTF file must end in .gltf or .glb");
  const bool binary = ext == ".glb";
  const bool has_n = mesh.normals.size() == mesh.vertex_count();

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "ibfvs";
  model.buffers.resize(1);
  model.extensionsUsed.push_back("KHR_materials_unlit");

  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  std::vector<glm::vec2> flipped(uv.size());
  for (std::size_t i = 0; i < uv.size(); ++i) flipped[i] = {uv[i].x, 1.0f - uv[i].y};

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  const std::size_t n = mesh.vertex_count();
  prim.attributes["POSITION"] = add_accessor(
      model,
      add_view(model, mesh.positions.data(), n * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
  if (has_n)
    prim.attributes["NORMAL"] = add_accessor(
        model,
        add_view(model, mesh.normals.data(), n * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER),
        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  prim.attributes["TEXCOORD_0"] = add_accessor(
      model, add_view(model, flipped.data(), n * sizeof(glm::vec2), TINYGLTF_TARGET_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
  prim.indices = add_accessor(
      model,
      add_view(model, mesh.triangles.data(), mesh.triangles.size() * sizeof(Triangle),
               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, mesh.triangles.size() * 3);

  tinygltf::Image image;
  image.mimeType = "image/png";
  if (binary) {
    const std::vector<unsigned char> png = read_bytes(texture_png);
    image.bufferView = add_view(model, png.data(), png.size(), 0);
  } else {
    if (!fs::exists(texture_png))
      throw InputError(texture_png.string() + ": the texture image does not exist");
    image.uri = texture_png.filename().string();
  }
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  model.textures.push_back(texture);

  // The texture already holds the shading the user chose; unlit shows it as is.
  tinygltf::Material material;
  material.name = "ibfvs_texture";
  material.pbrMetallicRoughness.baseColorTexture.index = 0;
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  material.doubleSided = true;
  material.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
  model.materials.push_back(material);
  prim.material = 0;

  tinygltf::Mesh gmesh;
  gmesh.name = "ibfvs_surface";
  gmesh.primitives.push_back(prim);
  model.meshes.push_back(gmesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  // The PNG is written by ibfvs; tinygltf must only refer to it (or embed it).
  writer.SetImageWriter(nullptr, nullptr);
  if (!writer.WriteGltfSceneToFile(&model, path.string(), false, false, true, binary))
    throw InputError(path.string() + ": cannot write the glTF file");
}

}  // namespace ibfvs
