// Posing a scene file's animated and skinned meshes at a time of its clip (glTF 2.0 §3.7.3,
// §3.11 and its Appendix C on interpolation).
#include "penumbra/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <string>

#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

glm::quat asQuat(glm::vec4 xyzw) {
  return glm::quat(xyzw.w, xyzw.x, xyzw.y, xyzw.z);
}
glm::vec4 asVec4(glm::quat q) {
  return glm::vec4(q.x, q.y, q.z, q.w);
}

// A rotation key set that interpolation left off unit length (a cubic spline's, a zero blend) is
// renormalised; a zero one is no rotation (the loader refuses zero keys, a spline can still cross
// zero).
glm::vec4 unitRotation(glm::vec4 q) {
  const float length = glm::length(q);
  return length > 0.0f && std::isfinite(length) ? q / length : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

glm::mat4 localMatrix(const NodeTransform& t) {
  return glm::scale(glm::translate(glm::mat4(1.0f), t.translation) * glm::mat4_cast(t.rotation),
                    t.scale);
}

// The matrix that takes normals as `m` takes positions: the cofactor matrix (the inverse
// transpose scaled by the determinant), signed so that a mirroring transform keeps them outward,
// and defined where a zero scale makes the inverse not exist.
glm::mat3 normalMatrix(const glm::mat3& m) {
  const glm::mat3 cofactor(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
  return glm::determinant(m) < 0.0f ? -cofactor : cofactor;
}

glm::vec3 unitOr(glm::vec3 v, glm::vec3 fallback) {
  const float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

}  // namespace

glm::vec4 sampleChannel(const AnimationChannel& channel, float seconds) {
  const std::vector<float>& times = channel.times;
  const bool cubic = channel.interpolation == KeyInterpolation::CubicSpline;
  const bool rotation = channel.property == AnimatedProperty::Rotation;
  // The value of key k (the middle of a cubic key's three).
  const auto value = [&](size_t k) { return channel.values[cubic ? 3 * k + 1 : k]; };
  if (!(seconds > times.front())) return value(0);
  if (seconds >= times.back()) return value(times.size() - 1);
  // The key interval [k, k + 1] holding `seconds`.
  const size_t k =
      size_t(std::upper_bound(times.begin(), times.end(), seconds) - times.begin()) - 1;
  const float span = times[k + 1] - times[k];
  const float s = (seconds - times[k]) / span;
  glm::vec4 result;
  switch (channel.interpolation) {
    case KeyInterpolation::Step: return value(k);
    case KeyInterpolation::Linear:
      if (rotation) return asVec4(glm::slerp(asQuat(value(k)), asQuat(value(k + 1)), s));
      return glm::mix(value(k), value(k + 1), s);
    case KeyInterpolation::CubicSpline: {
      // Appendix C: the Hermite spline through v_k and v_k+1 with the out-tangent b_k and the
      // in-tangent a_k+1, both scaled by the interval's length.
      const float s2 = s * s, s3 = s2 * s;
      const glm::vec4 outTangent = channel.values[3 * k + 2];
      const glm::vec4 inTangent = channel.values[3 * (k + 1)];
      result = (2.0f * s3 - 3.0f * s2 + 1.0f) * value(k) +
               span * (s3 - 2.0f * s2 + s) * outTangent + (-2.0f * s3 + 3.0f * s2) * value(k + 1) +
               span * (s3 - s2) * inTangent;
      break;
    }
  }
  return rotation ? unitRotation(result) : result;
}

std::vector<glm::mat4> nodeWorldTransforms(const SceneAnimation& animation, float seconds) {
  std::vector<NodeTransform> local(animation.nodes.size());
  for (size_t n = 0; n < animation.nodes.size(); ++n) local[n] = animation.nodes[n].rest;
  for (const AnimationChannel& channel : animation.channels) {
    const glm::vec4 v = sampleChannel(channel, seconds);
    NodeTransform& t = local[size_t(channel.node)];
    switch (channel.property) {
      case AnimatedProperty::Translation: t.translation = glm::vec3(v); break;
      case AnimatedProperty::Rotation: t.rotation = asQuat(unitRotation(v)); break;
      case AnimatedProperty::Scale: t.scale = glm::vec3(v); break;
    }
  }
  std::vector<glm::mat4> world(animation.nodes.size());
  for (size_t n = 0; n < animation.nodes.size(); ++n) {
    const AnimatedNode& node = animation.nodes[n];
    const glm::mat4 own = node.matrix ? *node.matrix : localMatrix(local[n]);
    world[n] = node.parent >= 0 ? world[size_t(node.parent)] * own : own;  // parents come first
  }
  return world;
}

void poseScene(Scene& scene, float seconds) {
  SceneAnimation& animation = scene.animation;
  if (animation.meshes.empty()) return;
  const std::vector<glm::mat4> world = nodeWorldTransforms(animation, seconds);
  // Each skin's joint matrices: bind space to world (the skinned node's own transform does not
  // apply, glTF 2.0 §3.7.3.1).
  std::vector<std::vector<glm::mat4>> jointMatrices(animation.skins.size());
  for (size_t s = 0; s < animation.skins.size(); ++s) {
    const Skin& skin = animation.skins[s];
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      jointMatrices[s].push_back(world[size_t(skin.joints[j])] * skin.inverseBindMatrices[j]);
    }
  }
  for (PosedMesh& posed : animation.meshes) {
    Mesh& mesh = scene.meshes[posed.mesh];
    const bool flat = posed.normals.empty();
    const glm::mat4& rigid = world[size_t(posed.node)];
    const glm::mat3 rigidNormals = normalMatrix(glm::mat3(rigid));
    // A rigid mesh whose transform mirrors it (a negative scale) has its winding turned back.
    const bool mirrored = posed.skin < 0 && glm::determinant(glm::mat3(rigid)) < 0.0f;
    if (mirrored != posed.mirrored) {
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
      posed.mirrored = mirrored;
    }
    for (size_t i = 0; i < posed.positions.size(); ++i) {
      glm::mat4 m = rigid;
      glm::mat3 n = rigidNormals;
      if (posed.skin >= 0) {
        // Linear blend skinning: the weighted sum of the joints' matrices.
        const std::vector<glm::mat4>& joints = jointMatrices[size_t(posed.skin)];
        m = glm::mat4(0.0f);
        for (int k = 0; k < 4; ++k) m += posed.weights[i][k] * joints[posed.joints[i][k]];
        n = normalMatrix(glm::mat3(m));
      }
      Vertex& v = mesh.vertices[i];
      v.position = glm::vec3(m * glm::vec4(posed.positions[i], 1.0f));
      if (!std::isfinite(v.position.x + v.position.y + v.position.z)) {
        // Named by sweepClip's caller while loading, when the scene has no name yet.
        throw Error((scene.name.empty() ? "" : scene.name + ": ") + "at " +
                    std::to_string(seconds) + " s of its animation '" + animation.clip +
                    "' a vertex of mesh " + std::to_string(posed.mesh) +
                    " is not finite in single precision");
      }
      if (!flat) v.normal = unitOr(n * posed.normals[i], v.normal);
    }
    if (flat) {  // each triangle has its own three vertices; its winding says its front
      for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        Vertex& a = mesh.vertices[mesh.indices[t]];
        Vertex& b = mesh.vertices[mesh.indices[t + 1]];
        Vertex& c = mesh.vertices[mesh.indices[t + 2]];
        const glm::vec3 normal =
            unitOr(glm::cross(b.position - a.position, c.position - a.position),
                   glm::vec3(0.0f, 1.0f, 0.0f));
        a.normal = b.normal = c.normal = normal;
      }
    }
  }
}

void sweepClip(Scene& scene, const std::string& source) {
  SceneAnimation& animation = scene.animation;
  if (animation.meshes.empty()) return;
  std::vector<float> times{0.0f, animation.duration};
  size_t keys = 0;
  for (const AnimationChannel& c : animation.channels) keys += c.times.size();
  if (keys + 2 <= size_t(kMaxSweepPoses)) {
    for (const AnimationChannel& c : animation.channels)
      times.insert(times.end(), c.times.begin(), c.times.end());
  } else {
    for (int k = 1; k + 1 < kMaxSweepPoses; ++k)
      times.push_back(animation.duration * float(k) / float(kMaxSweepPoses - 1));
  }
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
  for (float t : times) {
    try {
      poseScene(scene, t);
    } catch (const Error& e) {
      throw Error(source + ": " + e.what());
    }
    for (const PosedMesh& posed : animation.meshes) {
      for (const Vertex& v : scene.meshes[posed.mesh].vertices) {
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
      }
    }
    const glm::vec3 extent = hi - lo;
    if (!std::isfinite(extent.x + extent.y + extent.z) || !std::isfinite(glm::length(extent))) {
      throw Error(source + ": at " + std::to_string(t) + " s of its animation '" + animation.clip +
                  "' the moving meshes' extent is not finite in single precision");
    }
  }
  animation.sweepMin = lo;
  animation.sweepMax = hi;
  poseScene(scene, 0.0f);
}

float clipTime(const Scene& scene, int frame) {
  if (!scene.animation.moves()) return 0.0f;
  return std::fmod(float(frame) / kClipFramesPerSecond, scene.animation.duration);
}

}  // namespace penumbra
