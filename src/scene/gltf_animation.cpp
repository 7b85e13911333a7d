// Reading a glTF file's animation and skins (glTF 2.0 §3.7.3 skins, §3.11 animations).
#include "gltf_animation.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

#include "penumbra/error.h"

namespace penumbra::scene {
namespace {

// What a sampler's keys cost once held: one vec4 (16 bytes) per value, one float per time.
constexpr uint64_t kBytesPerKeyValue = sizeof(glm::vec4);

}  // namespace

GltfMotion::GltfMotion(const tinygltf::Model& model, std::span<const WalkedNode> walk,
                       const std::string& name, ReadNumbers read, MemoryBudget& budget,
                       const std::function<void(const std::string&)>& warn)
    : model_(model), name_(name), read_(std::move(read)), budget_(budget), warn_(warn) {
  readNodes(walk);
  readClip();
  // A node moves when a channel moves it or a node above it; the walk lists parents first.
  for (const WalkedNode& w : walk) {
    if (w.parent >= 0 && moves_[size_t(w.parent)]) moves_[size_t(w.node)] = true;
  }
}

void GltfMotion::fail(const std::string& what) const {
  throw Error(name_ + ": " + what);
}

void GltfMotion::readNodes(std::span<const WalkedNode> walk) {
  nodeIndex_.assign(model_.nodes.size(), -1);
  moves_.assign(model_.nodes.size(), false);
  skinIndex_.assign(model_.skins.size(), -1);
  // The loader's walk has checked each node's transform (sizes, single precision, a non-zero
  // rotation) before this reads it.
  for (const WalkedNode& w : walk) {
    const tinygltf::Node& n = model_.nodes[size_t(w.node)];
    AnimatedNode node;
    node.parent = w.parent >= 0 ? nodeIndex_[size_t(w.parent)] : -1;
    if (!n.matrix.empty()) {
      glm::mat4 m;
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[size_t(i)]);
      node.matrix = m;
    }
    if (!n.translation.empty()) {
      node.rest.translation =
          glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
    }
    if (!n.rotation.empty()) {
      const glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                        float(n.rotation[2]));
      node.rest.rotation = q / glm::length(q);
    }
    if (!n.scale.empty()) {
      node.rest.scale = glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2]));
    }
    nodeIndex_[size_t(w.node)] = int(animation_.nodes.size());
    animation_.nodes.push_back(node);
    if (n.skin >= 0 && n.mesh >= 0) moves_[size_t(w.node)] = true;
  }
}

void GltfMotion::readClip() {
  if (model_.animations.empty()) return;
  const tinygltf::Animation& clip = model_.animations.front();
  animation_.clip = clip.name.empty() ? "animation 0" : clip.name;
  if (model_.animations.size() > 1) {
    warn_("the file has " + std::to_string(model_.animations.size()) + " animations; the first ('" +
          animation_.clip + "') is played");
  }
  int outsideScene = 0, morphWeights = 0;
  for (size_t c = 0; c < clip.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = clip.channels[c];
    const std::string where = "animation 0 channel " + std::to_string(c);
    if (channel.target_path == "weights") {
      ++morphWeights;
      continue;
    }
    AnimationChannel out;
    if (channel.target_path == "translation") {
      out.property = AnimatedProperty::Translation;
    } else if (channel.target_path == "rotation") {
      out.property = AnimatedProperty::Rotation;
    } else if (channel.target_path == "scale") {
      out.property = AnimatedProperty::Scale;
    } else {
      fail(where + "'s target path '" + channel.target_path +
           "' is none of translation, rotation, scale, weights");
    }
    if (channel.target_node < 0 || size_t(channel.target_node) >= model_.nodes.size()) {
      fail(where + " targets node " + std::to_string(channel.target_node) + ", but the file has " +
           std::to_string(model_.nodes.size()) + " nodes");
    }
    if (channel.sampler < 0 || size_t(channel.sampler) >= clip.samplers.size()) {
      fail(where + " names sampler " + std::to_string(channel.sampler) +
           ", but the animation has " + std::to_string(clip.samplers.size()));
    }
    const int node = nodeIndex_[size_t(channel.target_node)];
    if (node < 0) {
      ++outsideScene;
      continue;
    }
    if (animation_.nodes[size_t(node)].matrix) {
      fail(where + " animates node " + std::to_string(channel.target_node) +
           ", which is given by a matrix (glTF 2.0 §3.11: animated nodes use translation, "
           "rotation and scale)");
    }
    out.node = node;
    const tinygltf::AnimationSampler& sampler = clip.samplers[size_t(channel.sampler)];
    const std::string samplerWhere = "animation 0 sampler " + std::to_string(channel.sampler);
    if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty()) {
      out.interpolation = KeyInterpolation::Linear;
    } else if (sampler.interpolation == "STEP") {
      out.interpolation = KeyInterpolation::Step;
    } else if (sampler.interpolation == "CUBICSPLINE") {
      out.interpolation = KeyInterpolation::CubicSpline;
    } else {
      fail(samplerWhere + "'s interpolation '" + sampler.interpolation +
           "' is none of LINEAR, STEP, CUBICSPLINE");
    }
    const bool rotation = out.property == AnimatedProperty::Rotation;
    const int components = rotation ? 4 : 3;
    const int perKey = out.interpolation == KeyInterpolation::CubicSpline ? 3 : 1;
    // Charged before the keys are expanded: a file's bytes can hold four times as many
    // normalized-byte rotations as vec4s.
    for (int accessor : {sampler.input, sampler.output}) {
      if (accessor >= 0 && size_t(accessor) < model_.accessors.size()) {
        budget_.addGeometry(
            0, saturatingMultiply(model_.accessors[size_t(accessor)].count, kBytesPerKeyValue));
      }
    }
    budget_.check(name_);
    out.times = read_(sampler.input, 1, AccessorNumbers::Float, samplerWhere + " input");
    if (out.times.empty()) fail(samplerWhere + " input has no keys");
    for (size_t k = 1; k < out.times.size(); ++k) {
      if (!(out.times[k] > out.times[k - 1])) {
        fail(samplerWhere + " input's times must increase strictly (key " + std::to_string(k) +
             " at " + std::to_string(out.times[k]) + " s follows " +
             std::to_string(out.times[k - 1]) + " s)");
      }
    }
    const std::vector<float> values =
        read_(sampler.output, components,
              rotation ? AccessorNumbers::FloatOrNormalized : AccessorNumbers::Float,
              samplerWhere + " output");
    const size_t expected = out.times.size() * size_t(perKey);
    if (values.size() != expected * size_t(components)) {
      fail(samplerWhere + " output has " + std::to_string(values.size() / size_t(components)) +
           " values for " + std::to_string(out.times.size()) + " keys (" + sampler.interpolation +
           " needs " + std::to_string(expected) + ")");
    }
    out.values.resize(expected, glm::vec4(0.0f));
    for (size_t v = 0; v < expected; ++v) {
      for (int k = 0; k < components; ++k) out.values[v][k] = values[v * size_t(components) + k];
      // A rotation key (not a cubic tangent) must be a rotation.
      if (rotation && (perKey == 1 || v % 3 == 1)) {
        const float length = glm::length(out.values[v]);
        if (!(length > 0.0f)) {
          fail(samplerWhere + " output's rotation key " + std::to_string(v / size_t(perKey)) +
               " is the zero quaternion");
        }
        out.values[v] /= length;
      }
    }
    animation_.duration = std::max(animation_.duration, out.times.back());
    moves_[size_t(channel.target_node)] = true;
    animation_.channels.push_back(std::move(out));
  }
  if (morphWeights > 0) {
    warn_(std::to_string(morphWeights) +
          " channel(s) animate morph-target weights, which penumbra does not read; ignored");
  }
  if (outsideScene > 0) {
    warn_(std::to_string(outsideScene) +
          " channel(s) animate nodes outside the scene drawn; ignored");
  }
}

int GltfMotion::readSkin(int gltfSkin) {
  if (gltfSkin < 0 || size_t(gltfSkin) >= model_.skins.size()) {
    fail("a node names skin " + std::to_string(gltfSkin) + ", but the file has " +
         std::to_string(model_.skins.size()) + " skins");
  }
  if (skinIndex_[size_t(gltfSkin)] >= 0) return skinIndex_[size_t(gltfSkin)];
  const tinygltf::Skin& s = model_.skins[size_t(gltfSkin)];
  const std::string where = "skin " + std::to_string(gltfSkin);
  if (s.joints.empty()) fail(where + " has no joints");
  Skin skin;
  for (int joint : s.joints) {
    if (joint < 0 || size_t(joint) >= model_.nodes.size() || nodeIndex_[size_t(joint)] < 0) {
      fail(where + "'s joint node " + std::to_string(joint) +
           " is not a node of the scene drawn (the file has " +
           std::to_string(model_.nodes.size()) + " nodes)");
    }
    skin.joints.push_back(nodeIndex_[size_t(joint)]);
  }
  if (s.inverseBindMatrices >= 0) {
    const std::vector<float> m =
        read_(s.inverseBindMatrices, 16, AccessorNumbers::Float, where + " inverseBindMatrices");
    if (m.size() != 16 * s.joints.size()) {
      fail(where + " has " + std::to_string(m.size() / 16) + " inverse bind matrices for " +
           std::to_string(s.joints.size()) + " joints");
    }
    for (size_t j = 0; j < s.joints.size(); ++j)
      skin.inverseBindMatrices.push_back(glm::make_mat4(m.data() + 16 * j));  // column-major
  } else {
    skin.inverseBindMatrices.assign(s.joints.size(), glm::mat4(1.0f));  // §3.7.3.1's default
  }
  skinIndex_[size_t(gltfSkin)] = int(animation_.skins.size());
  animation_.skins.push_back(std::move(skin));
  return skinIndex_[size_t(gltfSkin)];
}

bool GltfMotion::moves(int gltfNode) const {
  return moves_[size_t(gltfNode)];
}

void GltfMotion::addMesh(size_t sceneMesh, int gltfNode, int meshIndex, int primitiveIndex,
                         std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
                         std::span<const uint32_t> source, bool mirrored) {
  PosedMesh posed;
  posed.mesh = sceneMesh;
  posed.mirrored = mirrored;
  posed.node = nodeIndex_[size_t(gltfNode)];
  posed.positions = std::move(positions);
  posed.normals = std::move(normals);
  const int gltfSkin = model_.nodes[size_t(gltfNode)].skin;
  if (gltfSkin >= 0) {
    const tinygltf::Primitive& p =
        model_.meshes[size_t(meshIndex)].primitives[size_t(primitiveIndex)];
    const std::string where =
        "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex);
    const auto joints = p.attributes.find("JOINTS_0");
    const auto weights = p.attributes.find("WEIGHTS_0");
    if (joints == p.attributes.end() || weights == p.attributes.end()) {
      warn_(where + " is drawn by skinned node " + std::to_string(gltfNode) +
            " but has no JOINTS_0 and WEIGHTS_0; it follows its node unskinned");
    } else {
      posed.skin = readSkin(gltfSkin);
      const size_t jointCount = animation_.skins[size_t(posed.skin)].joints.size();
      if (p.attributes.count("JOINTS_1") != 0) {
        warn_(where +
              " has more than four joints per vertex; the four of JOINTS_0 are used, "
              "their weights renormalised");
      }
      const std::vector<float> j =
          read_(joints->second, 4, AccessorNumbers::SmallUnsigned, where + " JOINTS_0");
      const std::vector<float> w =
          read_(weights->second, 4, AccessorNumbers::FloatOrNormalized, where + " WEIGHTS_0");
      size_t fileVertices = 0;
      for (uint32_t s : source) fileVertices = std::max<size_t>(fileVertices, s + 1);
      if (j.size() / 4 < fileVertices || w.size() / 4 < fileVertices) {
        fail(where + " has " + std::to_string(std::min(j.size(), w.size()) / 4) +
             " joint and weight sets for " + std::to_string(fileVertices) + " vertices");
      }
      for (size_t i = 0; i < source.size(); ++i) {
        const size_t s = source[i];
        glm::uvec4 index;
        glm::vec4 weight;
        for (int k = 0; k < 4; ++k) {
          index[k] = unsigned(j[4 * s + size_t(k)]);
          weight[k] = std::max(w[4 * s + size_t(k)], 0.0f);
          if (weight[k] > 0.0f && index[k] >= jointCount) {
            fail(where + " vertex " + std::to_string(s) + " names joint " +
                 std::to_string(index[k]) + " of skin " + std::to_string(gltfSkin) +
                 ", which has " + std::to_string(jointCount));
          }
          if (index[k] >= jointCount) index[k] = 0;  // weight 0: any joint will do
        }
        const float sum = weight.x + weight.y + weight.z + weight.w;
        if (!(sum > 0.0f)) {
          fail(where + " vertex " + std::to_string(s) + "'s joint weights sum to 0");
        }
        posed.joints.push_back(index);
        posed.weights.push_back(weight / sum);
      }
    }
  }
  animation_.meshes.push_back(std::move(posed));
}

}  // namespace penumbra::scene
