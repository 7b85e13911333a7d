// A scene in GL objects, uploaded once: one vertex and one index buffer for all meshes, each
// base-colour texture as sRGB with mipmaps, and a copy of each mesh's material; drawn mesh by
// mesh.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "penumbra/gl/program.h"
#include "penumbra/scene.h"

namespace penumbra::gl {

class GpuScene {
 public:
  // What the passes need of a mesh's material (a copy: the Scene need not outlive the upload).
  struct Material {
    glm::vec3 albedo{0.8f};     // base-colour factor, linear
    float opacity = 1.0f;       // its alpha
    float alphaCutoff = -1.0f;  // < 0: opaque, no test (shared/alpha_mask.h)
    unsigned texture = 0;       // the base-colour texture, 0 for none
    bool doubleSided = true;    // false: the camera pass culls back faces
    bool castsShadow = true;    // false: the light pass skips it (Mesh::castsShadow)
    bool translucent = false;   // BLEND: the light pass may dither its coverage (LightPass)

    // Masked or translucent: its passes may discard (MaterialPrograms' ALPHA_TEST variant).
    bool alphaTested() const { return alphaCutoff >= 0.0f; }
  };

  explicit GpuScene(const Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Draws every mesh; `beforeMesh` runs first for each (to set its material, setMaterialUniforms)
  // with the mesh's base-colour texture, if any, bound to PENUMBRA_BASE_COLOR_TEXTURE_UNIT.
  // Which meshes a pass draws: the camera sees every mesh, the light only the shadow casters.
  enum class Meshes { All, Casters };
  void draw(const std::function<void(const Material&)>& beforeMesh,
            Meshes meshes = Meshes::All) const;

  // Whether any of these meshes has an alpha-tested material.
  bool hasAlphaTested(Meshes meshes) const;

  // Replaces the vertices with `scene`'s, which must have this scene's layout (its meshes'
  // vertex and index counts: sceneLayoutFingerprint equal): an animated scene's next pose.
  void updateVertices(const Scene& scene);

  // Bytes of the vertex, index and texture storage (textures with their full mip chains).
  uint64_t bytes() const { return bytes_; }

 private:
  struct Range {
    size_t firstIndex;
    size_t indexCount;
    int baseVertex;
  };
  unsigned vertexArray_ = 0;
  unsigned vertexBuffer_ = 0;
  unsigned indexBuffer_ = 0;
  std::vector<unsigned> textures_;
  std::vector<Range> ranges_;
  std::vector<Material> materials_;
  uint64_t bytes_ = 0;
};

// The material's uniforms of lib/material.glsl (albedo, alpha and texture switch).
void setMaterialUniforms(const Program& program, const GpuScene::Material& material);

// Seen from the camera, glTF's doubleSided: false culls back faces (shadows are cast by both).
void setCameraFaceCulling(const GpuScene::Material& material);

// A 64-bit FNV-1a hash of what GpuScene uploads (geometry, materials and mesh roles): equal scenes
// hash equal, so a renderer re-uploads only a scene whose content changed.
uint64_t sceneFingerprint(const Scene& scene);
// The same of everything but the vertices (counts, indices, materials, textures): equal for two
// poses of an animated scene, whose next pose then replaces only the vertices.
uint64_t sceneLayoutFingerprint(const Scene& scene);
// sceneFingerprint from the scene's layout fingerprint, computed once (the textures hashed once).
uint64_t sceneFingerprint(const Scene& scene, uint64_t layout);

}  // namespace penumbra::gl
