// Real models look right the first time: enclosures cast no shadow, a lone model stands on a
// ground, the camera sees the model (docs/scenes.md, "Real models").
#include "scene_shaping.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr std::string_view kGroundModeNames[] = {"auto", "on", "off"};
constexpr std::string_view kCasterModeNames[] = {"auto", "all"};

std::string nameList(std::span<const std::string_view> names) {
  std::string list;
  for (std::string_view n : names) list += (list.empty() ? "" : ", ") + std::string(n);
  return list;
}

std::string percent(float share) {
  std::ostringstream text;
  text.precision(3);
  text << 100.0f * share << "%";
  return text.str();
}

}  // namespace

std::string_view groundModeName(GroundMode mode) {
  return kGroundModeNames[int(mode)];
}

GroundMode parseGroundMode(std::string_view name) {
  for (size_t i = 0; i < std::size(kGroundModeNames); ++i) {
    if (kGroundModeNames[i] == name) return GroundMode(i);
  }
  throw Error("unknown ground mode '" + std::string(name) +
              "'; valid modes: " + nameList(kGroundModeNames));
}

std::string_view casterModeName(CasterMode mode) {
  return kCasterModeNames[int(mode)];
}

CasterMode parseCasterMode(std::string_view name) {
  for (size_t i = 0; i < std::size(kCasterModeNames); ++i) {
    if (kCasterModeNames[i] == name) return CasterMode(i);
  }
  throw Error("unknown casters mode '" + std::string(name) +
              "'; valid modes: " + nameList(kCasterModeNames));
}

std::optional<int> parseCameraIndex(std::string_view text) {
  int index = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return {};
  return index;
}

Camera framingCamera(const Scene& scene, float aspect) {
  Camera camera;
  camera.verticalFovDegrees = 45.0f;
  const Bounds model = scene.modelBounds();
  const glm::vec3 centre = model.centre();
  const glm::vec3 back = glm::normalize(kFramingDirection);  // from the model to the camera
  const glm::vec3 forward = -back;
  // The camera's axes as viewFromWorld builds them (glm::lookAt with +y up).
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(right, forward);
  const float tanHalfHeight = std::tan(glm::radians(0.5f * camera.verticalFovDegrees));
  const float tanHalfWidth = tanHalfHeight * aspect;
  // A vertex at offset o from the centre, seen from centre + D back, lies at depth D - o.back,
  // across at o.right and up at o.up; it is inside fill of the frame when
  // |o.right| <= fill tanHalfWidth (D - o.back), alike vertically. The least D meeting every
  // vertex's conditions puts the binding vertex exactly on the fill line.
  const float radius = std::max(model.radius(), 1e-6f);
  float distance = 0.0f;
  const bool hasModel = std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) {
    return m.role == MeshRole::Model && !m.vertices.empty();
  });
  for (const Mesh& mesh : scene.meshes) {
    if (hasModel && mesh.role != MeshRole::Model) continue;
    for (const Vertex& v : mesh.vertices) {
      const glm::vec3 o = v.position - centre;
      const float depthOffset = glm::dot(o, back);
      distance = std::max(distance, depthOffset + 1e-3f * radius);  // every vertex in front
      distance = std::max(
          distance, std::abs(glm::dot(o, right)) / (kFramingFill * tanHalfWidth) + depthOffset);
      distance = std::max(distance,
                          std::abs(glm::dot(o, up)) / (kFramingFill * tanHalfHeight) + depthOffset);
    }
  }
  camera.position = centre + distance * back;
  camera.target = centre;
  return camera;
}

CameraSight cameraSight(const Scene& scene, const Camera& camera, float aspect) {
  const glm::mat4 clipFromWorld =
      clipFromView(camera, aspect, scene.viewBounds()) * viewFromWorld(camera);
  double totalArea = 0.0, seenArea = 0.0;
  glm::vec2 low(1.0f), high(-1.0f);
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.role != MeshRole::Model) continue;
    for (const Vertex& v : mesh.vertices) {
      const glm::vec4 clip = clipFromWorld * glm::vec4(v.position, 1.0f);
      if (!(clip.w > 0.0f)) continue;
      const glm::vec2 ndc = glm::clamp(glm::vec2(clip) / clip.w, glm::vec2(-1.0f), glm::vec2(1.0f));
      low = glm::min(low, ndc);
      high = glm::max(high, ndc);
    }
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
      const glm::vec3 b = mesh.vertices[mesh.indices[t + 1]].position;
      const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
      const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
      if (!std::isfinite(area)) continue;
      totalArea += area;
      const auto inView = [&](glm::vec3 p) {
        const glm::vec4 clip = clipFromWorld * glm::vec4(p, 1.0f);
        return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w &&
               std::abs(clip.z) <= clip.w;
      };
      if (inView(a) && inView(b) && inView(c)) {
        seenArea += area;
      }
    }
  }
  CameraSight sight;
  if (totalArea > 0.0) sight.surfaceShare = float(seenArea / totalArea);
  if (high.x > low.x && high.y > low.y)
    sight.frameShare = (high.x - low.x) * (high.y - low.y) / 4.0f;
  return sight;
}

namespace scene {
namespace {

// Within this share of the bounds' largest extent from one of their faces, a vertex hugs them.
constexpr float kHugShare = 0.05f;

// Whether the ray from `origin` along `direction` meets the triangle (Moller and Trumbore).
bool rayMeetsTriangle(glm::vec3 origin, glm::vec3 direction, glm::vec3 a, glm::vec3 b,
                      glm::vec3 c) {
  const glm::vec3 ab = b - a, ac = c - a;
  const glm::vec3 p = glm::cross(direction, ac);
  const float det = glm::dot(ab, p);
  if (!(std::abs(det) > 0.0f)) return false;
  const glm::vec3 t = origin - a;
  const float u = glm::dot(t, p) / det;
  if (u < 0.0f || u > 1.0f) return false;
  const glm::vec3 q = glm::cross(t, ab);
  const float v = glm::dot(direction, q) / det;
  if (v < 0.0f || u + v > 1.0f) return false;
  return glm::dot(ac, q) / det > 0.0f;
}

// Whether the shell meshes close the sky over `origin`: every ray of the upper hemisphere (the
// horizon and 30 and 60 degrees up, every 45 degrees round, and straight up) meets one. Legs
// round a body reach as far as a dome but leave gaps between them.
bool closesTheSky(const Scene& scene, const std::vector<bool>& shell, glm::vec3 origin) {
  std::vector<glm::vec3> directions{{0.0f, 1.0f, 0.0f}};
  for (float elevation : {0.0f, 30.0f, 60.0f}) {
    for (int k = 0; k < 8; ++k) {
      const float azimuth = glm::radians(45.0f * float(k) + 22.5f);
      const float e = glm::radians(elevation);
      directions.emplace_back(std::cos(e) * std::cos(azimuth), std::sin(e),
                              std::cos(e) * std::sin(azimuth));
    }
  }
  for (const glm::vec3& direction : directions) {
    bool met = false;
    for (size_t m = 0; m < scene.meshes.size() && !met; ++m) {
      if (!shell[m]) continue;
      const Mesh& mesh = scene.meshes[m];
      for (size_t t = 0; t + 2 < mesh.indices.size() && !met; t += 3) {
        met = rayMeetsTriangle(origin, direction, mesh.vertices[mesh.indices[t]].position,
                               mesh.vertices[mesh.indices[t + 1]].position,
                               mesh.vertices[mesh.indices[t + 2]].position);
      }
    }
    if (!met) return false;
  }
  return true;
}

// The area-weighted mean of |cos| between the shell triangles' normals and the directions from
// `origin` to them: about 1 for a dome round it, 0.7 or more for a box, near 0 for legs or
// columns radiating from it, whose sides face sideways.
float facingShare(const Scene& scene, const std::vector<bool>& shell, glm::vec3 origin) {
  double facing = 0.0, area = 0.0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (!shell[m]) continue;
    const Mesh& mesh = scene.meshes[m];
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
      const glm::vec3 b = mesh.vertices[mesh.indices[t + 1]].position;
      const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
      const glm::vec3 n = glm::cross(b - a, c - a);
      const glm::vec3 towards = (a + b + c) / 3.0f - origin;
      const float lengths = glm::length(n) * glm::length(towards);
      if (!(lengths > 0.0f) || !std::isfinite(lengths)) continue;
      facing += double(std::abs(glm::dot(n, towards)) / lengths) * double(glm::length(n));
      area += double(glm::length(n));
    }
  }
  return area > 0.0 ? float(facing / area) : 0.0f;
}

float distanceToFaces(glm::vec3 p, const Bounds& b) {
  const glm::vec3 low = p - b.min, high = b.max - p;
  return std::min({low.x, low.y, low.z, high.x, high.y, high.z});
}

Mesh groundUnder(const Bounds& model) {
  // A square 1.5 model radii from the model's centre each way: the default light's shadow of
  // the model's top reaches 0.57 of its height sideways, well inside it.
  const float radius = std::max(model.radius(), 1e-6f);
  const float half = 1.5f * radius;
  const float y = model.min.y - 1e-3f * radius;  // below the model's lowest point, not in it
  const glm::vec3 c = model.centre();
  Mesh ground;
  ground.role = MeshRole::Ground;
  ground.albedo = glm::vec3(0.8f);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  ground.vertices = {{{c.x - half, y, c.z + half}, up, {0.0f, 1.0f}},
                     {{c.x + half, y, c.z + half}, up, {1.0f, 1.0f}},
                     {{c.x + half, y, c.z - half}, up, {1.0f, 0.0f}},
                     {{c.x - half, y, c.z - half}, up, {0.0f, 0.0f}}};
  ground.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from above
  return ground;
}

// A file camera as --camera names it: its index in Scene::fileCameras (the file's perspective
// cameras in the order its scene reaches them), not its index in a glTF file's cameras.
std::string cameraName(const Scene& scene, size_t index) {
  const std::string& name = scene.fileCameras[index].name;
  return "--camera " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')");
}

void chooseCamera(Scene& scene, const SceneLoadOptions& options, const std::string& source) {
  const size_t count = scene.fileCameras.size();
  if (options.camera) {
    const int index = *options.camera;
    if (count == 0) {
      throw Error(source +
                  " defines no cameras; --camera takes the index of one of a file's "
                  "cameras ('--camera list' names them)");
    }
    if (index < 0 || size_t(index) >= count) {
      throw Error("--camera " + std::to_string(index) + " is out of range [0, " +
                  std::to_string(count - 1) + "]: " + source + " defines " + std::to_string(count) +
                  " cameras ('--camera list' names them)");
    }
    scene.camera = scene.fileCameras[size_t(index)].camera;
    return;
  }
  float bestShare = -1.0f;
  size_t best = 0;
  // Each sight costs a pass over the model: a file with thousands of cameras is judged by its
  // first kMaxFileCamerasJudged.
  const size_t judged = std::min(count, kMaxFileCamerasJudged);
  for (size_t i = 0; i < judged; ++i) {
    const CameraSight sight = cameraSight(scene, scene.fileCameras[i].camera, options.aspect);
    if (sight.surfaceShare >= kFileCameraMinSurfaceShare) {
      scene.camera = scene.fileCameras[i].camera;
      return;
    }
    if (sight.surfaceShare > bestShare) {
      bestShare = sight.surfaceShare;
      best = i;
    }
  }
  scene.camera = framingCamera(scene, options.aspect);
  if (count > 0) {
    scene.warnings.push_back(
        source + ": " +
        (count == 1 ? std::string("its camera does not see")
                    : "none of the " + std::to_string(judged) + " cameras judged" +
                          (judged < count ? " (its first, of " + std::to_string(count) + ")" : "") +
                          " sees") +
        " the whole model at the frame's aspect (" + cameraName(scene, best) + " sees " +
        percent(bestShare) +
        "); a camera framing the model is used instead (--camera N picks one, --camera list "
        "names them)");
  }
}

}  // namespace

std::vector<bool> findEnclosures(const Scene& scene) {
  const Bounds b = scene.bounds();
  const glm::vec3 extent = b.max - b.min;
  const float hug = kHugShare * std::max({extent.x, extent.y, extent.z});
  const size_t count = scene.meshes.size();
  std::vector<bool> rises(count, false), hugs(count, false), flat(count, true);
  // A mesh the animation moves is the model's (an animated shell's poses would undo the inward
  // turn, and a shell that moves is not a backdrop).
  std::vector<bool> moving(count, false);
  for (const PosedMesh& posed : scene.animation.meshes) moving[posed.mesh] = true;
  for (size_t m = 0; m < count; ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (mesh.vertices.empty()) continue;
    float top = b.min.y, bottom = b.max.y;
    size_t hugging = 0;
    for (const Vertex& v : mesh.vertices) {
      if (distanceToFaces(v.position, b) <= hug) ++hugging;
      top = std::max(top, v.position.y);
      bottom = std::min(bottom, v.position.y);
    }
    // A floor lies at the bottom; a dome's or a box's pieces reach the top or span half the
    // height.
    rises[m] = !moving[m] && (top >= b.max.y - hug || top - bottom >= 0.5f * extent.y);
    hugs[m] = double(hugging) >= 0.95 * double(mesh.vertices.size());
    flat[m] = top - bottom < hug;
  }
  // What stands in the scene: meshes that neither rise nor are flat (a floor may reach the
  // shell). A shell piece keeps 95 % of its vertices outside it, or hugs the bounds (a skybox).
  Bounds standing{glm::vec3(std::numeric_limits<float>::max()),
                  glm::vec3(std::numeric_limits<float>::lowest())};
  for (size_t m = 0; m < count; ++m) {
    if (rises[m] || flat[m]) continue;
    for (const Vertex& v : scene.meshes[m].vertices) {
      standing.min = glm::min(standing.min, v.position);
      standing.max = glm::max(standing.max, v.position);
    }
  }
  std::vector<bool> shell(count, false);
  size_t shells = 0;
  for (size_t m = 0; m < count; ++m) {
    if (!rises[m]) continue;
    size_t outside = 0;
    for (const Vertex& v : scene.meshes[m].vertices) {
      const bool within = glm::all(glm::greaterThan(v.position, standing.min)) &&
                          glm::all(glm::lessThan(v.position, standing.max));
      outside += within ? 0 : 1;
    }
    shell[m] = hugs[m] || double(outside) >= 0.95 * double(scene.meshes[m].vertices.size());
    shells += shell[m] ? 1 : 0;
  }
  const std::vector<bool> none(count, false);
  if (shells == 0 || shells == count) return none;
  // The shells surround the rest: together they reach the four sides and the top of the
  // bounds, and the rest stays clear of the top by the hugging distance.
  bool reaches[5] = {false, false, false, false, false};
  Bounds rest{glm::vec3(std::numeric_limits<float>::max()),
              glm::vec3(std::numeric_limits<float>::lowest())};
  for (size_t m = 0; m < count; ++m) {
    for (const Vertex& v : scene.meshes[m].vertices) {
      const glm::vec3 p = v.position;
      if (!shell[m]) {
        rest.min = glm::min(rest.min, p);
        rest.max = glm::max(rest.max, p);
        continue;
      }
      reaches[0] |= p.x <= b.min.x + hug;
      reaches[1] |= p.x >= b.max.x - hug;
      reaches[2] |= p.z <= b.min.z + hug;
      reaches[3] |= p.z >= b.max.z - hug;
      reaches[4] |= p.y >= b.max.y - hug;
    }
  }
  const bool surrounds =
      std::all_of(std::begin(reaches), std::end(reaches), [](bool r) { return r; });
  // Something stands inside: a mesh of the rest that is no plate, rising by the hugging share
  // of its own largest extent. Where nothing stands in the scene's terms (a small model under a
  // dome a thousand times its size) every rising mesh keeps outside it; but a floor plate alone
  // under walls and a roof is a house, not what a sky encloses.
  bool somethingStands = false;
  for (size_t m = 0; m < count && !somethingStands; ++m) {
    if (shell[m] || scene.meshes[m].vertices.empty()) continue;
    Bounds own{glm::vec3(std::numeric_limits<float>::max()),
               glm::vec3(std::numeric_limits<float>::lowest())};
    for (const Vertex& v : scene.meshes[m].vertices) {
      own.min = glm::min(own.min, v.position);
      own.max = glm::max(own.max, v.position);
    }
    const glm::vec3 size = own.max - own.min;
    somethingStands = size.y > kHugShare * std::max({size.x, size.y, size.z});
  }
  if (!surrounds || !somethingStands || !(rest.max.y < b.max.y - hug) ||
      !closesTheSky(scene, shell, rest.centre()) ||
      facingShare(scene, shell, rest.centre()) < 0.6f) {
    return none;
  }
  return shell;
}

bool hasFloor(const Scene& scene) {
  const Bounds b = scene.modelBounds();
  const glm::vec3 extent = b.max - b.min;
  const double footprint = double(extent.x) * double(extent.z);
  const float level = b.min.y + kHugShare * std::max({extent.x, extent.y, extent.z});
  double floorArea = 0.0;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.role != MeshRole::Model) continue;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
      const glm::vec3 p = mesh.vertices[mesh.indices[t + 1]].position;
      const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
      if (std::max({a.y, p.y, c.y}) > level) continue;
      const glm::vec3 n = glm::cross(p - a, c - a);  // length: twice the area
      const float length = glm::length(n);
      if (length > 0.0f && n.y >= 0.9f * length) floorArea += 0.5 * double(length);
    }
  }
  return footprint > 0.0 && floorArea >= 0.25 * footprint;
}

namespace {

// An enclosure's faces turned towards the model and culled from behind: a camera outside it
// (the framing camera of a city under its dome) sees the model through it, one inside sees the
// sky.
void faceInwards(Mesh& mesh, glm::vec3 modelCentre) {
  double outwards = 0.0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
    const glm::vec3 b = mesh.vertices[mesh.indices[t + 1]].position;
    const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
    outwards += double(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - modelCentre));
  }
  if (outwards > 0.0) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    }
    for (Vertex& v : mesh.vertices) v.normal = -v.normal;
  }
  mesh.doubleSided = false;
}

}  // namespace

void shapeFileScene(Scene& scene, const SceneLoadOptions& options, const std::string& source) {
  if (!(options.aspect > 0.0f && options.aspect <= 100.0f)) {
    throw Error("the frame's aspect " + std::to_string(options.aspect) + " is outside (0, 100]");
  }
  // --casters all keeps every mesh the model, as the file has it: a misjudged enclosure (a house
  // taken for a skybox) is then drawn, framed and casting as written.
  const std::vector<bool> encloses = findEnclosures(scene);
  const size_t enclosures = size_t(std::count(encloses.begin(), encloses.end(), true));
  if (options.casters == CasterMode::Auto) {
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
      if (encloses[m]) scene.meshes[m].role = MeshRole::Enclosure;
    }
    const glm::vec3 modelCentre = scene.modelBounds().centre();
    for (Mesh& mesh : scene.meshes) {
      if (mesh.role == MeshRole::Enclosure) faceInwards(mesh, modelCentre);
    }
  } else if (enclosures > 0) {
    scene.notes.push_back(source + ": " + std::to_string(enclosures) +
                          (enclosures == 1 ? " mesh seems" : " meshes seem") +
                          " to enclose the rest of the scene (a sky dome or box); with --casters "
                          "all they stay part of the model, cast shadows and are framed and "
                          "drawn as the file has them");
  }
  size_t unlit = 0;
  for (Mesh& mesh : scene.meshes) {
    unlit += mesh.unlit ? 1 : 0;
    mesh.castsShadow =
        options.casters == CasterMode::All || (mesh.role != MeshRole::Enclosure && !mesh.unlit);
  }
  if (options.casters == CasterMode::Auto && (enclosures > 0 || unlit > 0)) {
    std::string what;
    if (enclosures > 0) {
      what = std::to_string(enclosures) + (enclosures == 1 ? " mesh encloses" : " meshes enclose") +
             " the rest of the scene (a sky dome or box)";
    }
    if (unlit > 0) {
      what += (what.empty() ? "" : " and ") + std::to_string(unlit) +
              (unlit == 1 ? " mesh is" : " meshes are") + " unlit (KHR_materials_unlit)";
    }
    scene.notes.push_back(source + ": " + what +
                          "; they cast no shadows (--casters all keeps "
                          "them)");
  }
  const bool ground =
      options.ground == GroundMode::On || (options.ground == GroundMode::Auto && !hasFloor(scene));
  if (ground) {
    scene.meshes.push_back(groundUnder(scene.modelBounds()));
    if (options.ground == GroundMode::Auto) {
      scene.notes.push_back(source +
                            ": no floor under the model; a ground plane is added to "
                            "receive its shadow (--ground off leaves it out)");
    }
  }
  chooseCamera(scene, options, source);
}

}  // namespace scene
}  // namespace penumbra
