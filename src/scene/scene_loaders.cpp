// loadScene: a built-in scene by name, or a scene file chosen by its extension.
#include <algorithm>
#include <filesystem>

#include "gltf_loader.h"
#include "obj_loader.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

enum class FileKind { None, Gltf, Obj };

FileKind fileKind(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension == ".gltf" || extension == ".glb") return FileKind::Gltf;
  if (extension == ".obj") return FileKind::Obj;
  return FileKind::None;
}

bool isBuiltin(std::string_view name) {
  const auto names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

void checkSceneSource(std::string_view nameOrPath) {
  if (isBuiltin(nameOrPath)) return;
  const fs::path path{std::string(nameOrPath)};
  if (fileKind(path) == FileKind::None) {
    throw Error("unknown scene '" + std::string(nameOrPath) +
                "'; valid scenes: " + builtinSceneNameList() + ", or a .gltf, .glb or .obj file");
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw Error("scene file " + path.string() + " " +
                (fs::exists(path, ec) ? "is not a regular file" : "does not exist"));
  }
}

Scene loadScene(std::string_view nameOrPath) {
  if (isBuiltin(nameOrPath)) return makeBuiltinScene(nameOrPath);
  checkSceneSource(nameOrPath);
  const fs::path path{std::string(nameOrPath)};
  const FileKind kind = fileKind(path);
  Scene scene = kind == FileKind::Gltf ? scene::loadGltfFile(path) : scene::loadObjFile(path);
  scene.name = path.stem().string();
  scene.description = (kind == FileKind::Gltf ? "glTF 2.0 file " : "OBJ file ") + path.string() +
                      ", " + std::to_string(scene.triangleCount()) + " triangles";
  return scene;
}

}  // namespace penumbra
