// Scene upload and drawing.
#include "gpu_scene.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>

#include "penumbra/error.h"
#include "penumbra/gl/context.h"

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

GpuScene::GpuScene(const Scene& scene) : scene_(scene) {
  size_t vertexCount = 0, indexCount = 0;
  for (const Mesh& m : scene.meshes) {
    vertexCount += m.vertices.size();
    indexCount += m.indices.size();
  }
  if (vertexCount > size_t(INT32_MAX)) {
    throw Error("scene '" + scene.name + "' has " + std::to_string(vertexCount) +
                " vertices; the renderer draws at most 2^31 - 1");
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
  glNamedBufferStorage(vertexBuffer_, vertexBytes, vertices.data(), 0);
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
  checkErrors("uploading the scene");
}

GpuScene::~GpuScene() {
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteBuffers(1, &vertexBuffer_);
  glDeleteBuffers(1, &indexBuffer_);
  if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
}

void GpuScene::draw(const std::function<void(const Mesh&)>& beforeMesh,
                    unsigned textureUnit) const {
  glBindVertexArray(vertexArray_);
  for (size_t i = 0; i < ranges_.size(); ++i) {
    const Mesh& mesh = scene_.meshes[i];
    if (beforeMesh) beforeMesh(mesh);
    if (mesh.baseColorTexture >= 0 && size_t(mesh.baseColorTexture) < textures_.size()) {
      glBindTextureUnit(textureUnit, textures_[size_t(mesh.baseColorTexture)]);
    }
    glDrawElementsBaseVertex(
        GL_TRIANGLES, GLsizei(ranges_[i].indexCount), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(ranges_[i].firstIndex * sizeof(uint32_t)),
        ranges_[i].baseVertex);
  }
  glBindVertexArray(0);
}

}  // namespace penumbra::gl
