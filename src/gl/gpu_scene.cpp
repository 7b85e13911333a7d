// Scene upload and drawing.
#include "gpu_scene.h"

#include <epoxy/gl.h>

#include "penumbra/gl/context.h"

namespace penumbra::gl {

GpuScene::GpuScene(const Scene& scene) {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  for (const Mesh& m : scene.meshes) {
    ranges_.push_back({indices.size(), m.indices.size(), int(vertices.size())});
    materials_.push_back({m.albedo});
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
  }
  glCreateBuffers(1, &vertexBuffer_);
  glNamedBufferStorage(vertexBuffer_, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(),
                       0);
  glCreateBuffers(1, &indexBuffer_);
  glNamedBufferStorage(indexBuffer_, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(),
                       0);
  bytes_ = vertices.size() * sizeof(Vertex) + indices.size() * sizeof(uint32_t);
  glCreateVertexArrays(1, &vertexArray_);
  glVertexArrayVertexBuffer(vertexArray_, 0, vertexBuffer_, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vertexArray_, indexBuffer_);
  glEnableVertexArrayAttrib(vertexArray_, 0);
  glVertexArrayAttribFormat(vertexArray_, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, position));
  glVertexArrayAttribBinding(vertexArray_, 0, 0);
  glEnableVertexArrayAttrib(vertexArray_, 1);
  glVertexArrayAttribFormat(vertexArray_, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, normal));
  glVertexArrayAttribBinding(vertexArray_, 1, 0);
  checkErrors("uploading the scene");
}

GpuScene::~GpuScene() {
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteBuffers(1, &vertexBuffer_);
  glDeleteBuffers(1, &indexBuffer_);
}

void GpuScene::draw(const std::function<void(const Material&)>& beforeMesh) const {
  glBindVertexArray(vertexArray_);
  for (size_t i = 0; i < ranges_.size(); ++i) {
    if (beforeMesh) beforeMesh(materials_[i]);
    glDrawElementsBaseVertex(
        GL_TRIANGLES, GLsizei(ranges_[i].indexCount), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(ranges_[i].firstIndex * sizeof(uint32_t)),
        ranges_[i].baseVertex);
  }
  glBindVertexArray(0);
}

namespace {

uint64_t hashBytes(uint64_t hash, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 0x100000001b3ull;
  return hash;
}

}  // namespace

uint64_t sceneFingerprint(const Scene& scene) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (const Mesh& m : scene.meshes) {
    const uint64_t counts[2] = {m.vertices.size(), m.indices.size()};
    hash = hashBytes(hash, counts, sizeof counts);
    hash = hashBytes(hash, m.vertices.data(), m.vertices.size() * sizeof(Vertex));
    hash = hashBytes(hash, m.indices.data(), m.indices.size() * sizeof(uint32_t));
    hash = hashBytes(hash, &m.albedo, sizeof m.albedo);
  }
  return hash;
}

}  // namespace penumbra::gl
