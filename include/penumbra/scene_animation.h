// A scene file's own motion: glTF 2.0 node animations and skins (glTF 2.0 §3.7.3 skins, §3.11
// animations), kept beside the meshes they move so that poseScene can place the geometry at any
// time of the clip. Posing is on the CPU (linear blend skinning, glTF 2.0 §3.7.3.3): the renderer
// uploads the posed vertices, and the ray-traced truth traces the same triangles.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct Scene;

// A node's local transform as glTF writes it: translation, rotation, scale (T * R * S).
struct NodeTransform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit length
  glm::vec3 scale{1.0f};
};

// A node of the file's scene, parents before their children.
struct AnimatedNode {
  int parent = -1;                  // index into SceneAnimation::nodes; -1 for a root
  NodeTransform rest;               // where no channel moves it
  std::optional<glm::mat4> matrix;  // a node given by a matrix (glTF forbids animating it)
};

enum class AnimatedProperty { Translation, Rotation, Scale };
// glTF 2.0 §3.11: LINEAR (rotations by slerp), STEP, CUBICSPLINE (Hermite, tangents per key).
enum class KeyInterpolation { Linear, Step, CubicSpline };

// One property of one node over time.
struct AnimationChannel {
  int node = 0;  // index into SceneAnimation::nodes
  AnimatedProperty property = AnimatedProperty::Translation;
  KeyInterpolation interpolation = KeyInterpolation::Linear;
  std::vector<float> times;  // seconds, strictly increasing, at least one
  // xyz (translation, scale) or xyzw (rotation, unit length) per key; CUBICSPLINE holds three per
  // key: the in-tangent, the value, the out-tangent.
  std::vector<glm::vec4> values;
};

// A skeleton: the nodes whose transforms bend the skinned meshes, each with the matrix that takes
// the mesh from its bind pose into the joint's space.
struct Skin {
  std::vector<int> joints;  // indices into SceneAnimation::nodes
  std::vector<glm::mat4> inverseBindMatrices;
};

// How one Scene::meshes entry follows the nodes: its vertices as the file gives them (in the
// node's space, or bind space for a skinned mesh), each final vertex's own copy.
struct PosedMesh {
  size_t mesh = 0;  // index into Scene::meshes
  int node = 0;     // the node that draws it (unused for a skinned mesh)
  int skin = -1;    // index into SceneAnimation::skins, or -1: rigid
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty: flat normals, one triangle per three vertices
  std::vector<glm::uvec4> joints;  // skinned: four indices into the skin's joints per vertex
  std::vector<glm::vec4> weights;  // skinned: their weights, summing to 1
  bool mirrored = false;           // rigid: the winding is turned for a mirroring transform
};

struct SceneAnimation {
  std::string clip;       // the animation played (its name, or "animation N")
  float duration = 0.0f;  // seconds: the last key of its channels
  std::vector<AnimatedNode> nodes;
  std::vector<AnimationChannel> channels;
  std::vector<Skin> skins;
  std::vector<PosedMesh> meshes;
  // Where the moving meshes reach over the clip (sweepClip): the renderer's depth ranges and the
  // light's fit hold still over it. Empty (min > max) until swept.
  glm::vec3 sweepMin{1.0f}, sweepMax{-1.0f};

  // Whether posing at different times gives different geometry.
  bool moves() const { return !channels.empty() && duration > 0.0f; }
};

// A channel's value at `seconds` (clamped to its first and last keys): a translation or scale in
// xyz, a unit rotation quaternion in xyzw.
glm::vec4 sampleChannel(const AnimationChannel& channel, float seconds);

// Every node's world transform at `seconds` of the clip.
std::vector<glm::mat4> nodeWorldTransforms(const SceneAnimation& animation, float seconds);

// Places the scene's animated meshes as they are at `seconds` of its clip (vertex positions and
// normals, and the winding where a node's transform turns mirroring or back, glTF 2.0 §3.7.4); a
// scene without an animation is left as it is. Cameras and lights are not changed. Throws Error
// naming the time where a vertex would not be finite.
void poseScene(Scene& scene, float seconds);

// Poses the clip at its keys' times (at most kMaxSweepPoses of them, else that many spread over
// it) and keeps the union of the poses' bounds (SceneAnimation::sweepMin/Max), then poses it at
// 0 s. Throws Error "<source>: ..." naming the time of a pose whose extent is not finite in
// single precision.
inline constexpr int kMaxSweepPoses = 256;
void sweepClip(Scene& scene, const std::string& source);

// Frame sequences (render --frames, compare's frames) play a clip in real time at this rate,
// which is also the rate of render's video: frame f shows the clip at f / 30 s, looped.
inline constexpr float kClipFramesPerSecond = 30.0f;
// The clip time of frame `frame` (0 for a still scene).
float clipTime(const Scene& scene, int frame);

}  // namespace penumbra
