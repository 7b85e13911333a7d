// Scene upload and drawing.
#include "gpu_scene.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>

#include "penumbra/error.h"
#include "penumbra/gl/context.h"
#include "penumbra/gl/scene_buffers.h"
#include "penumbra/shared/alpha_mask.h"

namespace penumbra::gl {
namespace {

// sRGB8_ALPHA8 with a full mip chain: alpha-tested cards seen from far read the averaged alpha
// of their footprint instead of aliasing.
unsigned uploadTexture(const TextureImage& image, uint64_t& bytes) {
  const int levels = std::bit_width(unsigned(std::max(image.width, image.height)));
  unsigned texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, levels, GL_SRGB8_ALPHA8, image.width, image.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      image.rgba.data());
  glGenerateTextureMipmap(texture);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_REPEAT);
  for (int level = 0; level < levels; ++level) {
    bytes += uint64_t(std::max(image.width >> level, 1)) *
             uint64_t(std::max(image.height >> level, 1)) * 4;
  }
  return texture;
}

}  // namespace

void setMaterialUniforms(const Program& program, const GpuScene::Material& material) {
  program.set("albedo", material.albedo);
  program.set("baseColorAlpha", material.opacity);
  program.set("alphaCutoff", material.alphaCutoff);
  program.set("hasBaseColorTexture", material.texture != 0 ? 1 : 0);
}

void setCameraFaceCulling(const GpuScene::Material& material) {
  if (material.doubleSided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
  }
}

GpuScene::GpuScene(const Scene& scene) {
  size_t vertexCount = 0, indexCount = 0;
  for (const Mesh& m : scene.meshes) {
    vertexCount += m.vertices.size();
    indexCount += m.indices.size();
  }
  if (vertexCount > size_t(INT32_MAX)) {
    throw Error("scene '" + scene.name + "' has " + std::to_string(vertexCount) +
                " vertices; the renderer draws at most 2^31 - 1");
  }
  // Before anything is copied or uploaded.
  const auto* device = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (const std::string why = sceneBufferShortfall(vertexCount, indexCount, device ? device : "");
      !why.empty()) {
    throw Error("scene '" + scene.name + "' cannot be drawn on this GL: " + why +
                "; use a smaller scene or a GPU");
  }
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  vertices.reserve(vertexCount);
  indices.reserve(indexCount);
  for (const Mesh& m : scene.meshes) {
    ranges_.push_back({indices.size(), m.indices.size(), int(vertices.size())});
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  const auto vertexBytes = GLsizeiptr(vertices.size() * sizeof(Vertex));
  const auto indexBytes = GLsizeiptr(indices.size() * sizeof(uint32_t));
  glCreateBuffers(1, &vertexBuffer_);
  // Dynamic: an animated scene's next pose replaces the vertices in place (updateVertices).
  glNamedBufferStorage(vertexBuffer_, vertexBytes, vertices.data(), GL_DYNAMIC_STORAGE_BIT);
  glCreateBuffers(1, &indexBuffer_);
  glNamedBufferStorage(indexBuffer_, indexBytes, indices.data(), 0);
  bytes_ = uint64_t(vertexBytes) + uint64_t(indexBytes);
  glCreateVertexArrays(1, &vertexArray_);
  glVertexArrayVertexBuffer(vertexArray_, 0, vertexBuffer_, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vertexArray_, indexBuffer_);
  const struct {
    int components;
    size_t offset;
  } attributes[] = {{3, offsetof(Vertex, position)},
                    {3, offsetof(Vertex, normal)},
                    {2, offsetof(Vertex, texcoord)}};
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vertexArray_, a);
    glVertexArrayAttribFormat(vertexArray_, a, attributes[a].components, GL_FLOAT, GL_FALSE,
                              GLuint(attributes[a].offset));
    glVertexArrayAttribBinding(vertexArray_, a, 0);
  }
  for (const TextureImage& image : scene.textures)
    textures_.push_back(uploadTexture(image, bytes_));
  for (const Mesh& m : scene.meshes) {
    const bool textured = m.baseColorTexture >= 0 && size_t(m.baseColorTexture) < textures_.size();
    materials_.push_back({m.albedo, m.opacity, m.alphaTested() ? m.effectiveAlphaCutoff() : -1.0f,
                          textured ? textures_[size_t(m.baseColorTexture)] : 0u, m.doubleSided,
                          m.castsShadow, m.alphaMode == AlphaMode::Blend});
  }
  checkErrors("uploading the scene");
}

void GpuScene::updateVertices(const Scene& scene) {
  GLintptr offset = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const std::vector<Vertex>& vertices = scene.meshes[i].vertices;
    const auto bytes = GLsizeiptr(vertices.size() * sizeof(Vertex));
    glNamedBufferSubData(vertexBuffer_, offset, bytes, vertices.data());
    offset += bytes;
  }
  checkErrors("updating the scene's vertices");
}

GpuScene::~GpuScene() {
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteBuffers(1, &vertexBuffer_);
  glDeleteBuffers(1, &indexBuffer_);
  if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
}

void GpuScene::draw(const std::function<void(const Material&)>& beforeMesh, Meshes meshes) const {
  glBindVertexArray(vertexArray_);
  for (size_t i = 0; i < ranges_.size(); ++i) {
    const Material& material = materials_[i];
    if (meshes == Meshes::Casters && !material.castsShadow) continue;
    if (beforeMesh) beforeMesh(material);
    if (material.texture != 0)
      glBindTextureUnit(PENUMBRA_BASE_COLOR_TEXTURE_UNIT, material.texture);
    glDrawElementsBaseVertex(
        GL_TRIANGLES, GLsizei(ranges_[i].indexCount), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(ranges_[i].firstIndex * sizeof(uint32_t)),
        ranges_[i].baseVertex);
  }
  glBindVertexArray(0);
}

bool GpuScene::hasAlphaTested(Meshes meshes) const {
  return std::any_of(materials_.begin(), materials_.end(), [&](const Material& m) {
    return m.alphaTested() && (meshes == Meshes::All || m.castsShadow);
  });
}

namespace {

uint64_t hashBytes(uint64_t hash, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 0x100000001b3ull;
  return hash;
}

}  // namespace

uint64_t sceneLayoutFingerprint(const Scene& scene) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (const Mesh& m : scene.meshes) {
    const uint64_t counts[2] = {m.vertices.size(), m.indices.size()};
    hash = hashBytes(hash, counts, sizeof counts);
    hash = hashBytes(hash, m.indices.data(), m.indices.size() * sizeof(uint32_t));
    const float material[5] = {m.albedo.r, m.albedo.g, m.albedo.b, m.opacity,
                               m.alphaTested() ? m.effectiveAlphaCutoff() : -1.0f};
    // The role with castsShadow decides the frame's depth ranges (Scene::shadowBounds).
    const int flags[5] = {m.baseColorTexture, m.doubleSided ? 1 : 0, m.castsShadow ? 1 : 0,
                          int(m.role), int(m.alphaMode)};
    hash = hashBytes(hash, material, sizeof material);
    hash = hashBytes(hash, flags, sizeof flags);
  }
  for (const TextureImage& t : scene.textures) {
    const int size[2] = {t.width, t.height};
    hash = hashBytes(hash, size, sizeof size);
    hash = hashBytes(hash, t.rgba.data(), t.rgba.size());
  }
  return hash;
}

uint64_t sceneFingerprint(const Scene& scene) {
  return sceneFingerprint(scene, sceneLayoutFingerprint(scene));
}

uint64_t sceneFingerprint(const Scene& scene, uint64_t layout) {
  uint64_t hash = layout;
  for (const Mesh& m : scene.meshes)
    hash = hashBytes(hash, m.vertices.data(), m.vertices.size() * sizeof(Vertex));
  return hash;
}

}  // namespace penumbra::gl
