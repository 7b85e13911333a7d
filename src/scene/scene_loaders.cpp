// loadScene: a built-in scene by name, or a scene file chosen by its extension.
#include <algorithm>
#include <filesystem>
#include <new>
#include <stdexcept>

#include "gltf_loader.h"
#include "memory_budget.h"
#include "obj_loader.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scene_shaping.h"

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

Scene loadScene(std::string_view nameOrPath, const SceneLoadOptions& options) {
  if (isBuiltin(nameOrPath)) {
    if (options.camera) {
      throw Error("scene '" + std::string(nameOrPath) +
                  "' is built in and defines no cameras of its own; --camera picks one of a "
                  "scene file's cameras");
    }
    return makeBuiltinScene(nameOrPath);
  }
  checkSceneSource(nameOrPath);
  if (options.maxMemoryBytes < kMinSceneMemoryBytes ||
      options.maxMemoryBytes > kMaxSceneMemoryBytes) {
    throw Error("the scene memory limit " + memorySizeText(options.maxMemoryBytes) +
                " is out of range [" + memorySizeText(kMinSceneMemoryBytes) + ", " +
                memorySizeText(kMaxSceneMemoryBytes) + "]");
  }
  const fs::path path{std::string(nameOrPath)};
  const FileKind kind = fileKind(path);
  scene::MemoryBudget budget(options.maxMemoryBytes);
  // The one place a failure the loaders did not foresee becomes a line naming the file: the
  // budget is an estimate, and the machine may hold less than it allows.
  try {
    Scene scene = kind == FileKind::Gltf ? scene::loadGltfFile(path, budget)
                                         : scene::loadObjFile(path, budget);
    scene::shapeFileScene(scene, options, path.string());
    scene.name = path.stem().string();
    scene.description = (kind == FileKind::Gltf ? "glTF 2.0 file " : "OBJ file ") + path.string() +
                        ", " + std::to_string(scene.triangleCount()) + " triangles";
    return scene;
  } catch (const Error&) {
    throw;
  } catch (const std::length_error& e) {
    throw Error(path.string() + ": out of memory while loading the scene: an allocation beyond " +
                "what can be addressed (" + e.what() + ")");
  } catch (const std::bad_alloc&) {
    throw Error(path.string() + ": out of memory while loading the scene (within the " +
                memorySizeText(options.maxMemoryBytes) +
                " limit, --max-memory, but more than this machine could give)");
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot be loaded: " + e.what());
  }
}

}  // namespace penumbra
