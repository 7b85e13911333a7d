// What loading one scene file has committed to hold, checked against SceneLoadOptions'
// maxMemoryBytes before the memory is taken (docs/untrusted-input.md).
#pragma once

#include <cstdint>
#include <string>

namespace penumbra::scene {

// The loaders add what they are about to hold: files as they are read, then the geometry and
// textures a scene expands to, estimated from the file's counts and image headers; check()
// refuses before anything is expanded or decoded.
class MemoryBudget {
 public:
  explicit MemoryBudget(uint64_t limitBytes) : limit_(limitBytes) {}

  uint64_t limit() const { return limit_; }

  // A file about to be read whole (`bytes` from its size; `file` says which, "image 'a.png'").
  // Throws Error "<source>: <file> is ..." when it and the files read before it exceed the limit.
  void addFile(const std::string& source, const std::string& file, uint64_t bytes);
  // Expanded geometry: `triangles` of them taking `bytes` (vertices, indices, meshes).
  void addGeometry(uint64_t triangles, uint64_t bytes);
  // One decoded texture (or an image decoded to make one) of `bytes`.
  void addTexture(uint64_t bytes);

  // Throws Error "<source>: needs ... of host memory for ..., above the ... limit" when the files,
  // geometry and textures added so far exceed the limit.
  void check(const std::string& source) const;

 private:
  uint64_t limit_;
  uint64_t fileBytes_ = 0;
  uint64_t geometryBytes_ = 0;
  uint64_t triangles_ = 0;
  uint64_t textureBytes_ = 0;
  uint64_t textures_ = 0;
};

// a + b, or UINT64_MAX where that overflows (counts from a file can be anything).
uint64_t saturatingAdd(uint64_t a, uint64_t b);
// a * b, or UINT64_MAX where that overflows.
uint64_t saturatingMultiply(uint64_t a, uint64_t b);

}  // namespace penumbra::scene
