// glTF 2.0 import: tinygltf parses, this file checks every index, accessor and transform before
// it is used and flattens the node hierarchy into world-space meshes (glTF 2.0 §3.5-3.9). The
// hierarchy is walked with a stack of its own, to a bounded depth; the memory the meshes and the
// referenced images will take is budgeted from counts and image headers before any is expanded
// or decoded (docs/untrusted-input.md).
#include "gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <set>
#include <span>
#include <sstream>

#include "file_scene.h"
#include "glb_container.h"
#include "gltf_animation.h"
#include "gltf_json_types.h"
#include "image_decoding.h"
#include "penumbra/error.h"
#include "scene_file_reading.h"

namespace penumbra::scene {
namespace {

namespace fs = std::filesystem;

// An image's encoded bytes, kept as the file is parsed and decoded only if a material uses it.
struct EncodedImage {
  std::vector<uint8_t> bytes;  // a URI's (a file's, a data URI's)
  int bufferView = -1;         // or these bytes of the file's buffers (checked against them)
};

// What the callbacks handed to tinygltf share: file access and the warnings collected.
struct LoadContext {
  std::string name;
  bool readFiles = false;
  MemoryBudget* budget = nullptr;
  std::vector<std::string> warnings;
  std::map<int, EncodedImage> images;      // by image index
  std::string refusal;                     // the first file refused (not regular, over budget)
  const tinygltf::Model* model = nullptr;  // the one being parsed: its buffers are read by now
};

// Anything there, regular or not, so that readWholeFile refuses a device or FIFO by name (tinygltf
// would only warn that an image it cannot find is missing).
bool fileExists(const std::string& path, void* user) {
  const auto* context = static_cast<const LoadContext*>(user);
  std::error_code ec;
  return context->readFiles && fs::exists(path, ec);
}

std::string expandFilePath(const std::string& path, void*) {
  return path;
}  // no ~ or $VAR

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
  auto* context = static_cast<LoadContext*>(user);
  if (!context->readFiles) {
    if (err) *err += "external file '" + path + "' is not read here\n";
    return false;
  }
  // tinygltf only warns where an image cannot be read: a refusal is kept and thrown after parsing
  // (and nothing is thrown through tinygltf's code).
  try {
    std::optional<std::vector<uint8_t>> bytes =
        readSceneFile(path, "'" + path + "'", context->name, *context->budget);
    if (!bytes) {
      if (err) *err += "cannot open '" + path + "'\n";
      return false;
    }
    *out = std::move(*bytes);
    return true;
  } catch (const Error& e) {
    if (context->refusal.empty()) context->refusal = e.what();
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
  if (err) *err += "penumbra does not write glTF files\n";
  return false;
}

// tinygltf's image callback: keeps the encoded bytes; the importer decodes the images materials
// use (an unused image costs its file, never its texels).
bool loadImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
  auto* context = static_cast<LoadContext*>(user);
  // tinygltf 2.7 hands over an image's buffer view without checking it against its buffer
  // (found by the fuzzer: stb_image then read past the buffer).
  if (image->bufferView >= 0) {
    const tinygltf::BufferView& view = context->model->bufferViews[size_t(image->bufferView)];
    const size_t available = context->model->buffers[size_t(view.buffer)].data.size();
    if (view.byteOffset > available || view.byteLength > available - view.byteOffset ||
        size_t(std::max(size, 0)) != view.byteLength) {
      if (err) {
        *err += "image " + std::to_string(index) + "'s buffer view " +
                std::to_string(image->bufferView) + " (bytes " + std::to_string(view.byteOffset) +
                " + " + std::to_string(view.byteLength) + ") runs past the end of its buffer (" +
                std::to_string(available) + " bytes)\n";
      }
      return false;
    }
  }
  EncodedImage& encoded = context->images[index];
  if (image->bufferView >= 0) {
    encoded.bufferView = image->bufferView;
  } else {
    encoded.bytes.assign(bytes, bytes + std::max(size, 0));
  }
  return true;
}

class Importer {
 public:
  Importer(const tinygltf::Model& model, std::string name,
           const std::map<int, EncodedImage>& images, MemoryBudget& budget)
      : model_(model), name_(std::move(name)), images_(images), budget_(budget) {}

  Scene run(std::vector<std::string> warnings);

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(name_ + ": " + what); }
  void warn(const std::string& what) { scene_.warnings.push_back(name_ + ": " + what); }

  // An accessor's elements, bounds-checked against its buffer view and buffer.
  struct View {
    const uint8_t* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;
  };
  View view(int accessor, const std::string& what) const;
  std::vector<glm::vec3> readVec3(int accessor, const std::string& what) const;
  std::vector<glm::vec2> readTexcoords(int accessor, const std::string& what) const;
  std::vector<uint32_t> readIndices(int accessor, const std::string& what) const;
  std::vector<float> readNumbers(int accessor, int components, AccessorNumbers numbers,
                                 const std::string& what) const;
  void refuseNonFinite(std::span<const float> element, int accessor, size_t index,
                       const std::string& what) const;

  // A node of the scene's trees and where it sits in the world.
  struct NodeInstance {
    int node;
    int parent;  // -1 for a root
    glm::mat4 worldFromNode;
  };
  // What a mesh expands to, once per node that draws it.
  struct MeshCost {
    uint64_t triangles = 0;
    uint64_t bytes = 0;
  };

  glm::mat4 localTransform(int node) const;
  std::vector<NodeInstance> walkHierarchy(const std::vector<int>& roots);
  MeshCost meshCost(int mesh, std::set<int>& imagesUsed) const;
  void budgetMemory(const std::vector<NodeInstance>& instances);
  std::span<const uint8_t> encodedImage(int image) const;
  void addPrimitive(int node, int meshIndex, int primitiveIndex, const glm::mat4& worldFromMesh);
  void applyMaterial(Mesh& mesh, int material, const std::string& where, int& texcoordSet);
  int sceneTexture(int texture, const std::string& where);
  void noteCamera(int node, const glm::mat4& worldFromNode);
  void noteLight(int node, const glm::mat4& worldFromNode);

  const tinygltf::Model& model_;
  std::string name_;
  const std::map<int, EncodedImage>& images_;
  MemoryBudget& budget_;
  Scene scene_;
  std::vector<int> parentCount_;
  std::map<int, int> textureOfImage_;
  std::set<int> blendWarned_;  // materials
  struct PlacedCamera {
    int node;
    int camera;
    glm::mat4 world;
  };
  std::vector<PlacedCamera> cameras_;  // in the order the walk meets their nodes
  std::optional<glm::mat4> lightWorld_;
  int lightIndex_ = -1;
  std::optional<GltfMotion> motion_;  // where the file has animations or skins
};

// Doubles from here up (FLT_MAX plus half its last place) round to infinity as float.
constexpr double kFloatOverflow = 0x1.ffffffp+127;

bool allWithinFloat(const std::vector<double>& values) {
  for (double v : values) {
    if (!(std::abs(v) < kFloatOverflow)) return false;
  }
  return true;
}

// A number as a file would write it ("1e+39", "0.25"), NaN without a sign.
std::string shortText(double v) {
  if (std::isnan(v)) return "nan";
  std::ostringstream text;
  text << v;
  return text.str();
}

size_t componentSize(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const char* componentTypeName(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "an unknown component type";
  }
}

template <typename T>
T load(const uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);  // accessors need not be aligned for the host
  return value;
}

// Component c of the element at p as a float, normalised integers mapped as glTF 2.0 §3.11.
float component(const uint8_t* p, int type, bool normalized, int c) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p + 4 * c);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float v = float(load<uint8_t>(p + c));
      return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float v = float(load<uint16_t>(p + 2 * c));
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = float(load<int8_t>(p + c));
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float v = float(load<int16_t>(p + 2 * c));
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return float(load<uint32_t>(p + 4 * c));
    default: return 0.0f;
  }
}

Importer::View Importer::view(int index, const std::string& what) const {
  if (index < 0 || size_t(index) >= model_.accessors.size()) {
    fail(what + " names accessor " + std::to_string(index) + ", but the file has " +
         std::to_string(model_.accessors.size()) + " accessors");
  }
  const tinygltf::Accessor& a = model_.accessors[size_t(index)];
  const std::string where = what + " (accessor " + std::to_string(index) + ")";
  if (a.sparse.isSparse) fail(where + " is sparse; sparse accessors are not supported");
  View v;
  v.componentType = a.componentType;
  v.components = componentCount(a.type);
  v.normalized = a.normalized;
  v.count = a.count;
  const size_t size = componentSize(a.componentType);
  if (size == 0 || v.components == 0) {
    fail(where + " has component type " + std::to_string(a.componentType) + " and type " +
         std::to_string(a.type) + ", which glTF 2.0 does not define");
  }
  if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size()) {
    fail(where + " names buffer view " + std::to_string(a.bufferView) + ", but the file has " +
         std::to_string(model_.bufferViews.size()));
  }
  const tinygltf::BufferView& bv = model_.bufferViews[size_t(a.bufferView)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size()) {
    fail("buffer view " + std::to_string(a.bufferView) + " names buffer " +
         std::to_string(bv.buffer) + ", but the file has " + std::to_string(model_.buffers.size()));
  }
  const std::vector<unsigned char>& buffer = model_.buffers[size_t(bv.buffer)].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset) {
    fail("buffer view " + std::to_string(a.bufferView) + " (bytes " +
         std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
         ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" +
         std::to_string(buffer.size()) + " bytes" +
         (buffer.empty() ? ": missing or not loaded" : "") + ")");
  }
  const size_t elementSize = size * size_t(v.components);
  v.stride = bv.byteStride != 0 ? bv.byteStride : elementSize;
  if (v.stride < elementSize) {
    fail(where + ": byte stride " + std::to_string(v.stride) + " is less than the element size " +
         std::to_string(elementSize));
  }
  if (v.count > 0) {
    const size_t available = bv.byteLength >= a.byteOffset ? bv.byteLength - a.byteOffset : 0;
    const bool fits = a.byteOffset <= bv.byteLength && available >= elementSize &&
                      (v.count - 1) <= (available - elementSize) / v.stride;
    if (!fits) {
      fail(where + ": " + std::to_string(v.count) + " elements of " + std::to_string(elementSize) +
           " bytes every " + std::to_string(v.stride) + " bytes from offset " +
           std::to_string(a.byteOffset) +
           " run past the end of buffer "
           "view " +
           std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes)");
    }
    v.data = buffer.data() + bv.byteOffset + a.byteOffset;
  }
  return v;
}

std::vector<glm::vec3> Importer::readVec3(int accessor, const std::string& what) const {
  const View v = view(accessor, what);
  if (v.components != 3 || v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    fail(what + " (accessor " + std::to_string(accessor) + ") must be VEC3 of FLOAT; it has " +
         std::to_string(v.components) + " components of " + componentTypeName(v.componentType));
  }
  std::vector<glm::vec3> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.data + i * v.stride;
    out[i] = glm::vec3(load<float>(p), load<float>(p + 4), load<float>(p + 8));
    refuseNonFinite(std::span<const float>(&out[i].x, 3), accessor, i, what);
  }
  return out;
}

// glTF 2.0 §3.6.2.4 allows no NaN or infinity in an accessor (glTF-Validator's
// ACCESSOR_INVALID_FLOAT): refused with the accessor, the element and its values.
void Importer::refuseNonFinite(std::span<const float> element, int accessor, size_t index,
                               const std::string& what) const {
  for (float c : element) {
    if (std::isfinite(c)) continue;
    std::string values;
    for (float e : element) values += (values.empty() ? "" : ", ") + shortText(e);
    fail(what + " (accessor " + std::to_string(accessor) + ") element " + std::to_string(index) +
         " is not finite (" + values + ")");
  }
}

std::vector<glm::vec2> Importer::readTexcoords(int accessor, const std::string& what) const {
  const View v = view(accessor, what);
  const bool typeOk = v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                      (v.normalized && (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                        v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
  if (v.components != 2 || !typeOk) {
    fail(what + " (accessor " + std::to_string(accessor) +
         ") must be VEC2 of FLOAT or of normalized UNSIGNED_BYTE or UNSIGNED_SHORT; it has " +
         std::to_string(v.components) + " components of " + componentTypeName(v.componentType) +
         (v.normalized ? " (normalized)" : ""));
  }
  std::vector<glm::vec2> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.data + i * v.stride;
    out[i] = glm::vec2(component(p, v.componentType, v.normalized, 0),
                       component(p, v.componentType, v.normalized, 1));
    refuseNonFinite(std::span<const float>(&out[i].x, 2), accessor, i, what);
  }
  return out;
}

std::vector<uint32_t> Importer::readIndices(int accessor, const std::string& what) const {
  const View v = view(accessor, what);
  const bool typeOk = v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                      v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                      v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  if (v.components != 1 || !typeOk) {
    fail(what + " (accessor " + std::to_string(accessor) +
         ") must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT; it has " +
         std::to_string(v.components) + " components of " + componentTypeName(v.componentType));
  }
  std::vector<uint32_t> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.data + i * v.stride;
    switch (v.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = load<uint8_t>(p); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: out[i] = load<uint16_t>(p); break;
      default: out[i] = load<uint32_t>(p); break;
    }
  }
  return out;
}

std::vector<float> Importer::readNumbers(int accessor, int components, AccessorNumbers numbers,
                                         const std::string& what) const {
  const View v = view(accessor, what);
  const int t = v.componentType;
  const bool small =
      t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const bool normalizedInteger = v.normalized && (small || t == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                                  t == TINYGLTF_COMPONENT_TYPE_SHORT);
  const bool isFloat = t == TINYGLTF_COMPONENT_TYPE_FLOAT;
  bool typeOk = false;
  const char* expected = "";
  switch (numbers) {
    case AccessorNumbers::Float: typeOk = isFloat, expected = "FLOAT"; break;
    case AccessorNumbers::FloatOrNormalized:
      typeOk = isFloat || normalizedInteger;
      expected = "FLOAT or normalized integers";
      break;
    case AccessorNumbers::SmallUnsigned:
      typeOk = small && !v.normalized;
      expected = "UNSIGNED_BYTE or UNSIGNED_SHORT";
      break;
  }
  if (v.components != components || !typeOk) {
    fail(what + " (accessor " + std::to_string(accessor) + ") must have " +
         std::to_string(components) + " components of " + expected + "; it has " +
         std::to_string(v.components) + " of " + componentTypeName(t) +
         (v.normalized ? " (normalized)" : ""));
  }
  std::vector<float> out(v.count * size_t(components));
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.data + i * v.stride;
    for (int c = 0; c < components; ++c)
      out[i * size_t(components) + size_t(c)] = component(p, t, v.normalized, c);
    refuseNonFinite(std::span<const float>(&out[i * size_t(components)], size_t(components)),
                    accessor, i, what);
  }
  return out;
}

glm::mat4 Importer::localTransform(int index) const {
  const tinygltf::Node& node = model_.nodes[size_t(index)];
  const std::string where = "node " + std::to_string(index);
  const auto checkSize = [&](const std::vector<double>& values, size_t size, const char* what) {
    if (!values.empty() && values.size() != size) {
      fail(where + "'s " + what + " has " + std::to_string(values.size()) + " numbers, not " +
           std::to_string(size));
    }
    // Within float, not only finite as a double: 1e39 became an infinite transform.
    if (!allWithinFloat(values)) fail(where + "'s " + what + " is not finite in single precision");
  };
  checkSize(node.matrix, 16, "matrix");
  checkSize(node.translation, 3, "translation");
  checkSize(node.rotation, 4, "rotation");
  checkSize(node.scale, 3, "scale");
  if (!node.matrix.empty()) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(m)[i] = float(node.matrix[size_t(i)]);  // column-major
    return m;
  }
  glm::mat4 m(1.0f);
  if (!node.translation.empty()) {
    m = glm::translate(m, glm::vec3(float(node.translation[0]), float(node.translation[1]),
                                    float(node.translation[2])));
  }
  if (!node.rotation.empty()) {
    // glTF stores x, y, z, w; glm's constructor takes w first.
    glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                float(node.rotation[2]));
    const float length = glm::length(q);
    if (!(length > 0.0f)) fail(where + "'s rotation is the zero quaternion");
    m *= glm::mat4_cast(q / length);
  }
  if (!node.scale.empty()) {
    m = glm::scale(m, glm::vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
  }
  return m;
}

std::vector<Importer::NodeInstance> Importer::walkHierarchy(const std::vector<int>& roots) {
  std::vector<NodeInstance> instances;
  // The path from the root to the node being walked: each level's node, its world transform and
  // the next child to enter.
  struct Level {
    int node;
    glm::mat4 worldFromNode;
    size_t nextChild;
  };
  std::vector<Level> path;
  std::vector<bool> onPath(model_.nodes.size(), false);
  const auto enter = [&](int node, const glm::mat4& worldFromParent) {
    if (node < 0 || size_t(node) >= model_.nodes.size()) {
      fail("a scene or node names node " + std::to_string(node) + ", but the file has " +
           std::to_string(model_.nodes.size()) + " nodes");
    }
    if (onPath[size_t(node)]) {
      std::string cycle;
      for (const Level& level : path) cycle += std::to_string(level.node) + " -> ";
      fail("the node hierarchy is recursive: " + cycle + std::to_string(node));
    }
    if (path.size() >= size_t(kMaxGltfNodeDepth)) {
      fail("the node hierarchy is deeper than " + std::to_string(kMaxGltfNodeDepth) +
           " levels (node " + std::to_string(node) + " is at level " +
           std::to_string(path.size() + 1) + " below root " + std::to_string(path.front().node) +
           "); penumbra loads at most " + std::to_string(kMaxGltfNodeDepth) + " levels");
    }
    // A strict tree (glTF 2.0 §3.5.3): a node reached twice would also multiply its subtree.
    if (++parentCount_[size_t(node)] > 1) {
      fail("node " + std::to_string(node) +
           " is reached twice (two parents, or a root that is also a child); glTF nodes form "
           "strict trees");
    }
    const glm::mat4 worldFromNode = worldFromParent * localTransform(node);
    instances.push_back({node, path.empty() ? -1 : path.back().node, worldFromNode});
    path.push_back({node, worldFromNode, 0});
    onPath[size_t(node)] = true;
  };
  for (int root : roots) {
    enter(root, glm::mat4(1.0f));
    while (!path.empty()) {
      Level& level = path.back();
      const std::vector<int>& children = model_.nodes[size_t(level.node)].children;
      if (level.nextChild == children.size()) {
        onPath[size_t(level.node)] = false;
        path.pop_back();
        continue;
      }
      const int child = children[level.nextChild++];
      const glm::mat4 worldFromParent = level.worldFromNode;  // enter() may move the path
      enter(child, worldFromParent);
    }
  }
  return instances;
}

// As addPrimitive will expand each primitive: triangle lists, one vertex per triangle corner
// where the file has no normals (flat normals). Primitives addPrimitive will refuse (modes,
// missing positions) cost nothing here; accessors are checked as addPrimitive checks them.
Importer::MeshCost Importer::meshCost(int meshIndex, std::set<int>& imagesUsed) const {
  MeshCost cost;
  const tinygltf::Mesh& mesh = model_.meshes[size_t(meshIndex)];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    const std::string where =
        "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    const auto position = primitive.attributes.find("POSITION");
    if ((mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
         mode != TINYGLTF_MODE_TRIANGLE_FAN) ||
        position == primitive.attributes.end()) {
      continue;
    }
    const uint64_t positions = view(position->second, where + " POSITION").count;
    const uint64_t corners =
        primitive.indices >= 0 ? view(primitive.indices, where + " indices").count : positions;
    const uint64_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? corners / 3
                               : corners >= 3                  ? corners - 2
                                                               : 0;
    const bool hasNormals = primitive.attributes.count("NORMAL") != 0;
    const uint64_t vertices = hasNormals ? positions : 3 * triangles;
    cost.triangles += triangles;
    cost.bytes += sizeof(Mesh) + vertices * sizeof(Vertex) + 3 * triangles * sizeof(uint32_t);

    const int material = primitive.material;
    if (material < 0 || size_t(material) >= model_.materials.size()) continue;
    const int texture =
        model_.materials[size_t(material)].pbrMetallicRoughness.baseColorTexture.index;
    if (texture < 0 || size_t(texture) >= model_.textures.size()) continue;
    const int image = model_.textures[size_t(texture)].source;
    if (image >= 0 && size_t(image) < model_.images.size()) imagesUsed.insert(image);
  }
  return cost;
}

// Every mesh once per node that draws it, every image a drawn material uses at the size its
// header declares: refused here, before any is expanded or decoded.
void Importer::budgetMemory(const std::vector<NodeInstance>& instances) {
  std::vector<std::optional<MeshCost>> costs(model_.meshes.size());
  std::set<int> imagesUsed;
  for (const NodeInstance& instance : instances) {
    const int mesh = model_.nodes[size_t(instance.node)].mesh;
    if (mesh < 0 || size_t(mesh) >= model_.meshes.size()) continue;  // expanding says why
    std::optional<MeshCost>& cost = costs[size_t(mesh)];
    if (!cost) cost = meshCost(mesh, imagesUsed);
    budget_.addGeometry(cost->triangles, cost->bytes);
    // A mesh that may move keeps its vertices as the file gives them beside the posed ones, with
    // joints and weights: under twice the bytes of the posed vertices (PosedMesh).
    if (!model_.animations.empty() || !model_.skins.empty())
      budget_.addGeometry(0, saturatingMultiply(cost->bytes, 2));
  }
  for (int image : imagesUsed) {
    if (const std::optional<ImageSize> size = readImageSize(encodedImage(image))) {
      budget_.addTexture(size->rgbaBytes());
    }
  }
  budget_.check(name_);
}

std::span<const uint8_t> Importer::encodedImage(int image) const {
  const auto found = images_.find(image);
  if (found == images_.end()) return {};
  const EncodedImage& encoded = found->second;
  if (encoded.bufferView < 0) return encoded.bytes;
  // Checked against its buffer when the file was parsed (loadImage).
  const tinygltf::BufferView& view = model_.bufferViews[size_t(encoded.bufferView)];
  return std::span<const uint8_t>(model_.buffers[size_t(view.buffer)].data)
      .subspan(view.byteOffset, view.byteLength);
}

int Importer::sceneTexture(int texture, const std::string& where) {
  if (texture < 0 || size_t(texture) >= model_.textures.size()) {
    fail(where + " names texture " + std::to_string(texture) + ", but the file has " +
         std::to_string(model_.textures.size()));
  }
  const int image = model_.textures[size_t(texture)].source;
  if (image < 0 || size_t(image) >= model_.images.size()) {
    fail("texture " + std::to_string(texture) + " names image " + std::to_string(image) +
         ", but the file has " + std::to_string(model_.images.size()));
  }
  if (auto found = textureOfImage_.find(image); found != textureOfImage_.end())
    return found->second;
  // Decoded once, however many materials use it.
  const tinygltf::Image& source = model_.images[size_t(image)];
  const std::string name = source.uri.empty() ? "image " + std::to_string(image) : source.uri;
  int index = -1;
  if (const std::span<const uint8_t> bytes = encodedImage(image); !bytes.empty()) {
    std::string why;
    if (std::optional<TextureImage> decoded = decodeImage(bytes, name, why)) {
      index = int(scene_.textures.size());
      scene_.textures.push_back(std::move(*decoded));
    } else {
      warn(name + " cannot be used: " + why + "; its materials use their base-colour factor alone");
    }
  } else if (!source.uri.empty()) {
    warn("image '" + source.uri + "' could not be read; its materials use their base-colour " +
         "factor alone");
  }
  textureOfImage_[image] = index;
  return index;
}

void Importer::applyMaterial(Mesh& mesh, int material, const std::string& where, int& texcoordSet) {
  texcoordSet = -1;
  if (material < 0) {  // glTF's default material (§3.9.6): white, opaque, single-sided
    mesh.albedo = glm::vec3(1.0f);
    mesh.doubleSided = false;
    return;
  }
  if (size_t(material) >= model_.materials.size()) {
    fail(where + " names material " + std::to_string(material) + ", but the file has " +
         std::to_string(model_.materials.size()));
  }
  const tinygltf::Material& m = model_.materials[size_t(material)];
  const std::string what = "material " + std::to_string(material);
  const std::vector<double>& factor = m.pbrMetallicRoughness.baseColorFactor;
  // JSON holds no NaN or infinity, but doubles beyond float's range become infinite here.
  if (factor.size() != 4 || !allWithinFloat(factor)) {
    std::string values;
    for (double f : factor) values += (values.empty() ? "" : ", ") + shortText(f);
    fail(what + "'s baseColorFactor must be 4 numbers within single precision (it is [" + values +
         "])");
  }
  // Refused whatever the mode (glTF ignores the cutoff outside MASK): a value no float holds is a
  // broken file.
  if (!allWithinFloat({m.alphaCutoff})) {
    fail(what + "'s alphaCutoff " + shortText(m.alphaCutoff) + " is beyond single precision");
  }
  mesh.albedo =
      glm::clamp(glm::vec3(float(factor[0]), float(factor[1]), float(factor[2])), 0.0f, 1.0f);
  mesh.opacity = std::clamp(float(factor[3]), 0.0f, 1.0f);
  mesh.doubleSided = m.doubleSided;
  if (m.alphaMode == "MASK") {
    mesh.alphaMode = AlphaMode::Mask;
    if (!std::isfinite(m.alphaCutoff) || m.alphaCutoff < 0.0) {
      fail(what + "'s alphaCutoff " + std::to_string(m.alphaCutoff) +
           " is not a non-negative number");
    }
    mesh.alphaCutoff = float(m.alphaCutoff);
  } else if (m.alphaMode == "BLEND") {
    mesh.alphaMode = AlphaMode::Blend;
    // Once per material, as OBJ's `d` below 1: each names its material and its alpha.
    if (blendWarned_.insert(material).second) {
      warn(what + (m.name.empty() ? "" : " ('" + m.name + "')") +
           " is BLEND (baseColorFactor alpha " + std::to_string(mesh.opacity) +
           "): " + kTranslucentMaterialRule);
    }
  } else if (m.alphaMode == "OPAQUE" || m.alphaMode.empty()) {
    mesh.alphaMode = AlphaMode::Opaque;
  } else {
    fail(what + "'s alphaMode '" + m.alphaMode + "' is none of OPAQUE, MASK, BLEND");
  }
  mesh.unlit = m.extensions.count("KHR_materials_unlit") != 0;
  if (m.extensions.count("KHR_materials_pbrSpecularGlossiness") != 0) {
    warn(what + " uses KHR_materials_pbrSpecularGlossiness: its diffuse colour is not read");
  }
  const tinygltf::TextureInfo& info = m.pbrMetallicRoughness.baseColorTexture;
  if (info.index >= 0) {
    mesh.baseColorTexture = sceneTexture(info.index, what);
    if (mesh.baseColorTexture >= 0) texcoordSet = info.texCoord;
  }
}

void Importer::addPrimitive(int node, int meshIndex, int primitiveIndex, const glm::mat4& world) {
  const tinygltf::Primitive& p =
      model_.meshes[size_t(meshIndex)].primitives[size_t(primitiveIndex)];
  const std::string where =
      "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex);
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    const char* names[] = {"points", "lines", "line loops", "line strips"};
    fail(where + " draws " + (mode >= 0 && mode <= 3 ? names[mode] : "an unknown mode") +
         " (mode " + std::to_string(mode) +
         "); only triangles, triangle strips and fans can cast shadows");
  }
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) fail(where + " has no POSITION attribute");

  Mesh mesh;
  int texcoordSet = -1;
  applyMaterial(mesh, p.material, where, texcoordSet);
  if (!p.targets.empty()) warn(where + " has morph targets; drawn without them");

  const std::vector<glm::vec3> positions = readVec3(position->second, where + " POSITION");
  std::vector<glm::vec3> normals;
  if (auto n = p.attributes.find("NORMAL"); n != p.attributes.end()) {
    normals = readVec3(n->second, where + " NORMAL");
    if (normals.size() != positions.size()) {
      fail(where + " has " + std::to_string(normals.size()) + " normals for " +
           std::to_string(positions.size()) + " positions");
    }
  }
  std::vector<glm::vec2> texcoords;
  if (texcoordSet >= 0) {
    const std::string attribute = "TEXCOORD_" + std::to_string(texcoordSet);
    if (auto t = p.attributes.find(attribute); t != p.attributes.end()) {
      texcoords = readTexcoords(t->second, where + " " + attribute);
      if (texcoords.size() != positions.size()) {
        fail(where + " has " + std::to_string(texcoords.size()) + " texture coordinates for " +
             std::to_string(positions.size()) + " positions");
      }
    } else {
      warn(where + " has a base-colour texture but no " + attribute +
           "; it uses the base-colour factor alone");
      mesh.baseColorTexture = -1;
    }
  }

  std::vector<uint32_t> order;
  if (p.indices >= 0) {
    order = readIndices(p.indices, where + " indices");
    for (size_t i = 0; i < order.size(); ++i) {
      if (order[i] >= positions.size()) {
        fail(where + ": index " + std::to_string(order[i]) + " at position " + std::to_string(i) +
             " is out of range (the primitive has " + std::to_string(positions.size()) +
             " vertices)");
      }
    }
  } else {
    order.resize(positions.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = uint32_t(i);
  }
  // Strips and fans as triangle lists, keeping the winding (glTF 2.0 §3.7.2.1).
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    order.resize(order.size() / 3 * 3);
  } else {
    std::vector<uint32_t> list;
    for (size_t i = 2; i < order.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        list.insert(list.end(), {order[0], order[i - 1], order[i]});
      } else if (i % 2 == 0) {
        list.insert(list.end(), {order[i - 2], order[i - 1], order[i]});
      } else {
        list.insert(list.end(), {order[i - 1], order[i - 2], order[i]});
      }
    }
    order = std::move(list);
  }
  if (order.empty()) return;

  const glm::mat3 linear(world);
  const float determinant = glm::determinant(linear);
  // A moving mesh may be scaled from nothing; poseScene places it.
  const bool moves = motion_ && motion_->moves(node);
  if (!moves && (!(std::abs(determinant) > 0.0f) || !std::isfinite(determinant))) {
    warn(where + " sits under a singular transform (a zero scale): it covers nothing, skipped");
    return;
  }
  const glm::mat3 normalFromMesh = glm::transpose(glm::inverse(linear));
  mesh.vertices.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    Vertex& v = mesh.vertices[i];
    v.position = glm::vec3(world * glm::vec4(positions[i], 1.0f));
    v.normal = normals.empty() ? glm::vec3(0.0f) : normalFromMesh * normals[i];
    if (!texcoords.empty()) v.texcoord = texcoords[i];
  }
  // A mirroring transform turns counter-clockwise triangles clockwise: swap two corners back (a
  // skinned mesh's node transform does not apply, glTF 2.0 §3.7.3.1; poseScene turns a moving
  // mesh's winding as its transform mirrors or not).
  const bool skinned = moves && model_.nodes[size_t(node)].skin >= 0;
  const bool mirrored = determinant < 0.0f && !skinned;
  if (mirrored) {
    for (size_t t = 0; t + 2 < order.size(); t += 3) std::swap(order[t + 1], order[t + 2]);
  }
  // Where each final vertex comes from in the file: itself, or each corner's vertex once flat
  // normals give every triangle its own three.
  std::vector<uint32_t> source;
  if (moves) {
    source = normals.empty() ? order : std::vector<uint32_t>();
    if (!normals.empty()) {
      source.resize(positions.size());
      for (size_t i = 0; i < source.size(); ++i) source[i] = uint32_t(i);
    }
  }
  mesh.indices = std::move(order);
  if (normals.empty()) computeFlatNormals(mesh);
  if (moves) {
    std::vector<glm::vec3> sourcePositions(source.size()), sourceNormals;
    for (size_t i = 0; i < source.size(); ++i) sourcePositions[i] = positions[source[i]];
    if (!normals.empty()) sourceNormals = normals;
    motion_->addMesh(scene_.meshes.size(), node, meshIndex, primitiveIndex,
                     std::move(sourcePositions), std::move(sourceNormals), source, mirrored);
  }
  scene_.meshes.push_back(std::move(mesh));
}

void Importer::noteCamera(int node, const glm::mat4& world) {
  const int camera = model_.nodes[size_t(node)].camera;
  if (camera < 0) return;
  if (size_t(camera) >= model_.cameras.size()) {
    fail("node " + std::to_string(node) + " names camera " + std::to_string(camera) +
         ", but the file has " + std::to_string(model_.cameras.size()));
  }
  cameras_.push_back({node, camera, world});
}

void Importer::noteLight(int node, const glm::mat4& world) {
  const auto ext = model_.nodes[size_t(node)].extensions.find("KHR_lights_punctual");
  if (ext == model_.nodes[size_t(node)].extensions.end() || lightWorld_) return;
  const tinygltf::Value& index = ext->second.Get("light");
  if (!index.IsInt() || index.Get<int>() < 0 || size_t(index.Get<int>()) >= model_.lights.size()) {
    fail("node " + std::to_string(node) + "'s KHR_lights_punctual names no light of the " +
         std::to_string(model_.lights.size()) + " in the file");
  }
  lightWorld_ = world;
  lightIndex_ = index.Get<int>();
}

Scene Importer::run(std::vector<std::string> warnings) {
  scene_.warnings = std::move(warnings);
  for (const std::string& extension : model_.extensionsRequired) {
    if (extension != "KHR_lights_punctual" && extension != "KHR_materials_unlit") {
      fail("the file requires extension " + extension +
           ", which penumbra does not read (it reads KHR_lights_punctual and "
           "KHR_materials_unlit)");
    }
  }
  parentCount_.assign(model_.nodes.size(), 0);
  if (model_.scenes.empty()) fail("the file has no scene");
  int sceneIndex = model_.defaultScene;
  if (sceneIndex < 0) sceneIndex = 0;
  if (size_t(sceneIndex) >= model_.scenes.size()) {
    fail("the default scene " + std::to_string(sceneIndex) + " does not exist (the file has " +
         std::to_string(model_.scenes.size()) + ")");
  }
  if (model_.scenes[size_t(sceneIndex)].nodes.empty()) fail("the scene has no nodes");
  const std::vector<NodeInstance> instances =
      walkHierarchy(model_.scenes[size_t(sceneIndex)].nodes);
  budgetMemory(instances);
  if (!model_.animations.empty() || !model_.skins.empty()) {
    std::vector<WalkedNode> walk;
    for (const NodeInstance& instance : instances) walk.push_back({instance.node, instance.parent});
    const ReadNumbers read = [this](int accessor, int components, AccessorNumbers numbers,
                                    const std::string& what) {
      return readNumbers(accessor, components, numbers, what);
    };
    motion_.emplace(model_, walk, name_, read, budget_,
                    [this](const std::string& what) { warn(what); });
  }
  for (const NodeInstance& instance : instances) {
    const int node = instance.node;
    const tinygltf::Node& n = model_.nodes[size_t(node)];
    if (n.mesh >= 0) {
      if (size_t(n.mesh) >= model_.meshes.size()) {
        fail("node " + std::to_string(node) + " names mesh " + std::to_string(n.mesh) +
             ", but the file has " + std::to_string(model_.meshes.size()) + " meshes");
      }
      for (size_t p = 0; p < model_.meshes[size_t(n.mesh)].primitives.size(); ++p)
        addPrimitive(node, n.mesh, int(p), instance.worldFromNode);
    }
    noteCamera(node, instance.worldFromNode);
    noteLight(node, instance.worldFromNode);
  }
  if (scene_.meshes.empty()) fail("the scene has no triangles to render");
  if (motion_ && !motion_->empty()) {
    scene_.animation = motion_->take();
    // Its reach over the clip, checked; then its pose at the start (a skinned mesh's bind pose is
    // not it).
    sweepClip(scene_, name_);
  }

  // The file's camera and light, placed once the bounds are known.
  const Bounds bounds = scene_.bounds();
  FileView fileView;
  const auto aim = [&](const glm::mat4& world) {
    const glm::vec3 position(world[3]);
    const glm::vec3 forward = glm::normalize(glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f));
    const float distance = std::max(glm::length(bounds.centre() - position), 1e-2f);
    return std::pair{position, position + distance * forward};
  };
  for (const PlacedCamera& placed : cameras_) {
    const tinygltf::Camera& c = model_.cameras[size_t(placed.camera)];
    const float fov = float(glm::degrees(c.perspective.yfov));
    // Named by the file's camera index: it is left out of the cameras --camera numbers.
    const std::string what = "the file's camera " + std::to_string(placed.camera) + " (node " +
                             std::to_string(placed.node) + ")";
    if (c.type != "perspective") {
      warn(what + " is " + c.type +
           "; only perspective cameras are used (and numbered for --camera)");
    } else if (!(fov > 0.0f && fov <= 170.0f)) {
      warn(what + "'s yfov " + std::to_string(fov) +
           " degrees is outside (0, 170]; not used (nor numbered for --camera)");
    } else {
      const auto [position, target] = aim(placed.world);
      if (std::isfinite(target.x + target.y + target.z)) {
        const std::string& name = c.name.empty() ? model_.nodes[size_t(placed.node)].name : c.name;
        fileView.cameras.push_back({name, Camera{position, target, fov}});
      }
    }
  }
  if (lightWorld_) {
    const tinygltf::Light& l = model_.lights[size_t(lightIndex_)];
    const auto [position, target] = aim(*lightWorld_);
    const bool finite = std::isfinite(target.x + target.y + target.z);
    if (l.type == "directional" && finite) {
      Light light;
      light.kind = LightKind::Directional;
      light.direction = glm::normalize(target - position);
      fileView.light = light;
    } else if (l.type == "spot" && finite) {
      const float angle = float(glm::degrees(2.0 * l.spot.outerConeAngle));
      Light light;
      light.kind = LightKind::Spot;
      light.position = position;
      light.target = target;
      light.spotAngleDegrees = std::isfinite(angle) ? std::clamp(angle, 1.0f, 170.0f) : 60.0f;
      fileView.light = light;
    } else if (l.type == "point" && std::isfinite(position.x + position.y + position.z)) {
      Light light;
      light.kind = LightKind::Point;
      light.position = position;
      fileView.light = light;
    } else {
      warn("light " + std::to_string(lightIndex_) + " is a " + l.type +
           " light; only directional, spot and point lights cast shadows here, a directional "
           "light from above is used instead");
    }
  }
  finishFileScene(scene_, name_, fileView);
  return std::move(scene_);
}

}  // namespace

Scene loadGltf(std::span<const uint8_t> bytes, const std::string& name,
               const fs::path& baseDirectory, bool readFiles, MemoryBudget& budget) {
  LoadContext context;
  context.name = name;
  context.readFiles = readFiles;
  context.budget = &budget;
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({fileExists, expandFilePath, readWholeFile, writeWholeFile, &context});
  parser.SetImageLoader(loadImage, &context);
  tinygltf::Model model;
  context.model = &model;
  std::string err, warn;
  if (bytes.size() > size_t(UINT32_MAX)) throw Error(name + ": larger than 4 GiB");
  const bool binary = isGlb(bytes);
  checkGltfJsonTypes(binary ? glbJsonChunk(bytes, name) : bytes, name);
  const bool ok = binary
                      ? parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                                    unsigned(bytes.size()), baseDirectory.string())
                      : parser.LoadASCIIFromString(&model, &err, &warn,
                                                   reinterpret_cast<const char*>(bytes.data()),
                                                   unsigned(bytes.size()), baseDirectory.string());
  const auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start < text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      if (end > start) out.push_back(text.substr(start, end - start));
      start = end + 1;
    }
    return out;
  };
  if (!context.refusal.empty()) throw Error(context.refusal);
  if (!ok) {
    std::string message;
    for (const std::string& line : lines(err)) message += (message.empty() ? "" : "; ") + line;
    throw Error(name + ": not a valid glTF 2.0 file: " +
                (message.empty() ? std::string("tinygltf gave no reason") : message));
  }
  for (const std::string& line : lines(warn)) context.warnings.push_back(name + ": " + line);
  return Importer(model, name, context.images, budget).run(std::move(context.warnings));
}

Scene loadGltfFile(const fs::path& path, MemoryBudget& budget) {
  const std::optional<std::vector<uint8_t>> bytes =
      readSceneFile(path, "the scene file", path.string(), budget);
  if (!bytes) throw Error("cannot open scene file " + path.string());
  return loadGltf(*bytes, path.string(), path.parent_path(), true, budget);
}

}  // namespace penumbra::scene
