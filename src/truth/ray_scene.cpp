// The scene's BVH for the ray-traced truth (penumbra/truth/true_shadow.h): one Embree triangle
// geometry per mesh, alpha masks and single-sided culling in filter functions.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "penumbra/error.h"
#include "penumbra/shared/alpha_mask.h"
#include "penumbra/srgb.h"
#include "ray_scene_impl.h"

namespace penumbra::truth {
namespace {

// Embree reports failures through a callback; the last message is kept for the Error thrown.
void keepDeviceError(void* message, RTCError, const char* text) {
  *static_cast<std::string*>(message) = text ? text : "unknown error";
}

std::string deviceErrorText(RTCDevice device, const std::string& message) {
  const RTCError code = rtcGetDeviceError(device);
  if (code == RTC_ERROR_NONE && message.empty()) return {};
  return message.empty() ? "Embree error " + std::to_string(int(code)) : message;
}

RayTexture decodeTexture(const TextureImage& image) {
  RayTexture t;
  t.width = image.width;
  t.height = image.height;
  float linear[256];
  for (int i = 0; i < 256; ++i) linear[i] = linearFromSrgb(float(i) / 255.0f);
  t.texels.resize(size_t(image.width) * size_t(image.height));
  for (size_t i = 0; i < t.texels.size(); ++i) {
    const uint8_t* texel = &image.rgba[4 * i];
    t.texels[i] =
        glm::vec4(linear[texel[0]], linear[texel[1]], linear[texel[2]], float(texel[3]) / 255.0f);
  }
  return t;
}

// Filter for camera rays: the camera pass culls single-sided meshes from behind and discards
// what the alpha mask cuts out.
void filterCameraHit(const RTCFilterFunctionNArguments* args) {
  const RayMesh& mesh = *static_cast<const RayMesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
    if (!mesh.doubleSided) {
      const glm::vec3 front = mesh.frontNormal(primitive);
      const glm::vec3 direction(RTCRayN_dir_x(args->ray, args->N, i),
                                RTCRayN_dir_y(args->ray, args->N, i),
                                RTCRayN_dir_z(args->ray, args->N, i));
      if (glm::dot(front, direction) >= 0.0f) {
        args->valid[i] = 0;
        continue;
      }
    }
    if (!mesh.covers(primitive, RTCHitN_u(args->hit, args->N, i),
                     RTCHitN_v(args->hit, args->N, i))) {
      args->valid[i] = 0;
    }
  }
}

// Filter for shadow rays: every caster casts from both sides (the light pass draws without
// culling); the alpha mask cuts out what it cuts out in the light pass; a mesh that casts no
// shadow (the light pass skips it) lets every ray through; a translucent (BLEND) one lets the ray
// on with 1 - alpha of its light (each triangle the ray crosses once: the BVH's medium quality
// makes no spatial splits, so Embree meets each triangle once; a ray exactly through an edge
// shared by two may be dimmed by both).
void filterShadowHit(const RTCFilterFunctionNArguments* args) {
  const RayMesh& mesh = *static_cast<const RayMesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (mesh.translucent && mesh.castsShadow) {
      // rtcOccluded1 in true_shadow.cpp: one ray (N == 1) with a ShadowRayContext.
      auto* context = reinterpret_cast<ShadowRayContext*>(args->context);
      context->transmittance *= 1.0f - std::clamp(mesh.baseColor(primitive, u, v).a, 0.0f, 1.0f);
      args->valid[i] = 0;
    } else if (!mesh.castsShadow || !mesh.covers(primitive, u, v)) {
      args->valid[i] = 0;
    }
  }
}

}  // namespace

glm::vec4 RayTexture::sample(glm::vec2 texcoord) const {
  // Texel centres at (i + 0.5) / width; GL_REPEAT wraps each of the four taps.
  const float x = texcoord.x * float(width) - 0.5f;
  const float y = texcoord.y * float(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float wx = x - fx, wy = y - fy;
  auto wrap = [](float i, int n) {
    const double m = std::fmod(double(i), double(n));
    return int(m < 0.0 ? m + n : m);
  };
  const int x0 = wrap(fx, width), x1 = wrap(fx + 1.0f, width);
  const int y0 = wrap(fy, height), y1 = wrap(fy + 1.0f, height);
  auto at = [&](int tx, int ty) { return texels[size_t(ty) * size_t(width) + size_t(tx)]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), wx), glm::mix(at(x0, y1), at(x1, y1), wx), wy);
}

glm::vec4 RayMesh::baseColor(uint32_t primitive, float u, float v) const {
  glm::vec4 color(albedo, opacity);
  if (texture != nullptr) {
    const auto [a, b, c] = triangle(primitive);
    color *= texture->sample((1.0f - u - v) * texcoords[a] + u * texcoords[b] + v * texcoords[c]);
  }
  return color;
}

bool RayMesh::covers(uint32_t primitive, float u, float v) const {
  if (alphaCutoff < 0.0f) return true;
  return shaders::alphaCovers(baseColor(primitive, u, v).a, alphaCutoff);
}

RayScene::RayScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  std::string& message = s.deviceError;
  s.device = rtcNewDevice(nullptr);
  if (s.device == nullptr) {
    throw Error("Embree could not create a device (error " +
                std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  }
  rtcSetDeviceErrorFunction(s.device, keepDeviceError, &message);
  s.textures.reserve(scene.textures.size());
  for (const TextureImage& t : scene.textures) s.textures.push_back(decodeTexture(t));
  s.scene = rtcNewScene(s.device);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_MEDIUM);
  // Watertight triangle tests: a ray through a shared edge or vertex hits one of the triangles
  // (the default, faster test may let it slip between them).
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
  s.meshes.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) {
    RayMesh& m = s.meshes.emplace_back();
    m.positions.reserve(mesh.vertices.size());
    for (const Vertex& v : mesh.vertices) {
      m.positions.push_back(v.position);
      m.normals.push_back(v.normal);
      m.texcoords.push_back(v.texcoord);
    }
    m.indices = mesh.indices;
    m.albedo = mesh.albedo;
    m.opacity = mesh.opacity;
    if (mesh.baseColorTexture >= 0 && size_t(mesh.baseColorTexture) < s.textures.size()) {
      m.texture = &s.textures[size_t(mesh.baseColorTexture)];
    }
    m.alphaCutoff = mesh.alphaTested() ? mesh.effectiveAlphaCutoff() : -1.0f;
    m.doubleSided = mesh.doubleSided;
    m.castsShadow = mesh.castsShadow;
    m.translucent = mesh.alphaMode == AlphaMode::Blend;
    s.triangles += m.indices.size() / 3;
  }
  for (size_t id = 0; id < s.meshes.size(); ++id) {
    RayMesh& m = s.meshes[id];
    const RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads vertices as 16 bytes: its own buffers carry the padding it needs.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), std::max<size_t>(m.positions.size(), 1)));
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), std::max<size_t>(m.indices.size() / 3, 1)));
    if (vertices == nullptr || indices == nullptr) {
      rtcReleaseGeometry(geometry);
      throw Error("Embree could not allocate mesh " + std::to_string(id) +
                  "'s buffers: " + deviceErrorText(s.device, message));
    }
    for (size_t i = 0; i < m.positions.size(); ++i) {
      vertices[3 * i] = m.positions[i].x;
      vertices[3 * i + 1] = m.positions[i].y;
      vertices[3 * i + 2] = m.positions[i].z;
    }
    std::copy(m.indices.begin(), m.indices.end(), indices);
    if (m.indices.empty()) indices[0] = indices[1] = indices[2] = 0;  // degenerate: never hit
    rtcSetGeometryUserData(geometry, &m);
    if (!m.doubleSided || m.alphaCutoff >= 0.0f) {
      rtcSetGeometryIntersectFilterFunction(geometry, filterCameraHit);
    }
    if (m.alphaCutoff >= 0.0f || !m.castsShadow || m.translucent) {
      rtcSetGeometryOccludedFilterFunction(geometry, filterShadowHit);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(s.scene, geometry, unsigned(id));
    rtcReleaseGeometry(geometry);
  }
  const auto start = std::chrono::steady_clock::now();
  rtcCommitScene(s.scene);
  s.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string failure = deviceErrorText(s.device, message);
  if (!failure.empty()) {
    throw Error("Embree could not build the scene's BVH (" + std::to_string(s.triangles) +
                " triangles): " + failure);
  }
}

RayScene::~RayScene() = default;

size_t RayScene::triangleCount() const {
  return impl_->triangles;
}
double RayScene::buildSeconds() const {
  return impl_->buildSeconds;
}

std::string embreeDescription() {
  return "Intel Embree " RTC_VERSION_STRING;
}

}  // namespace penumbra::truth
