// A glTF file's motion read into SceneAnimation: its first animation's channels and the skins of
// the nodes its scene draws (glTF 2.0 §3.7.3, §3.11), every index, accessor and key checked
// before use. The loader expands the meshes and asks which must be posed.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "memory_budget.h"
#include "penumbra/scene_animation.h"

namespace tinygltf {
class Model;
}

namespace penumbra::scene {

// The accessor element types a reader accepts (glTF 2.0 §3.7.2.1, §3.11).
enum class AccessorNumbers {
  Float,              // FLOAT
  FloatOrNormalized,  // FLOAT, or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT
  SmallUnsigned,      // UNSIGNED_BYTE or UNSIGNED_SHORT, not normalized (joint indices)
};
// An accessor's elements of `components` numbers each, flattened, as floats (normalized integers
// mapped to [-1, 1] or [0, 1]); throws Error naming `what` for another type, a count of
// components that differs, an element outside its buffer or a number that is not finite.
using ReadNumbers = std::function<std::vector<float>(
    int accessor, int components, AccessorNumbers numbers, const std::string& what)>;

// A node of the scene's trees as the loader walked them: parents before their children.
struct WalkedNode {
  int node;    // glTF index
  int parent;  // glTF index, -1 for a root
};

class GltfMotion {
 public:
  // Reads the nodes' rest transforms, the first animation's channels on the walked nodes and the
  // skins of walked nodes that draw a mesh. Throws Error "<name>: ..." for anything malformed;
  // `warn` hears what is read with a caveat (more animations than the one played, morph-target
  // weights, channels on nodes outside the scene).
  GltfMotion(const tinygltf::Model& model, std::span<const WalkedNode> walk,
             const std::string& name, ReadNumbers read, MemoryBudget& budget,
             const std::function<void(const std::string&)>& warn);

  // Whether a mesh drawn by this glTF node must be posed: it is skinned, or an animated node is
  // it or above it.
  bool moves(int gltfNode) const;

  // Records how a Scene::meshes entry follows its node: `positions` and `normals` as the file
  // gives them (normals empty for flat shading), one per final vertex, with `source[i]` the
  // file's vertex behind final vertex i (for the skinning attributes, read here from the
  // primitive's JOINTS_0 and WEIGHTS_0); `mirrored`: its winding was turned for a mirroring
  // transform (PosedMesh::mirrored).
  void addMesh(size_t sceneMesh, int gltfNode, int meshIndex, int primitiveIndex,
               std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
               std::span<const uint32_t> source, bool mirrored);

  // Whether anything was recorded to pose.
  bool empty() const { return animation_.meshes.empty(); }
  SceneAnimation take() { return std::move(animation_); }

 private:
  [[noreturn]] void fail(const std::string& what) const;
  void readNodes(std::span<const WalkedNode> walk);
  void readClip();
  int readSkin(int gltfSkin);

  const tinygltf::Model& model_;
  std::string name_;
  ReadNumbers read_;
  MemoryBudget& budget_;
  std::function<void(const std::string&)> warn_;
  SceneAnimation animation_;
  std::vector<int> nodeIndex_;  // by glTF node: its index in animation_.nodes, or -1
  std::vector<bool> moves_;     // by glTF node
  std::vector<int> skinIndex_;  // by glTF skin: its index in animation_.skins, or -1
};

}  // namespace penumbra::scene
