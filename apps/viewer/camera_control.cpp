// Camera and light motion.
#include "camera_control.h"

#include <algorithm>
#include <cmath>

namespace penumbra::viewer {
namespace {

constexpr float kMaxPitch = 1.55f;  // just short of straight up or down, where yaw degenerates

glm::vec3 rotated(const glm::vec3& v, float yaw, float pitch) {
  const float length = glm::length(v);
  if (length == 0.0f) return v;
  float currentYaw = std::atan2(v.x, v.z);
  float currentPitch = std::asin(std::clamp(v.y / length, -1.0f, 1.0f));
  currentYaw += yaw;
  currentPitch = std::clamp(currentPitch + pitch, -kMaxPitch, kMaxPitch);
  return length * glm::vec3(std::cos(currentPitch) * std::sin(currentYaw), std::sin(currentPitch),
                            std::cos(currentPitch) * std::cos(currentYaw));
}

}  // namespace

void orbitCamera(Camera& camera, float yaw, float pitch) {
  camera.position = camera.target + rotated(camera.position - camera.target, -yaw, pitch);
}

void dollyCamera(Camera& camera, float factor) {
  const glm::vec3 offset = camera.position - camera.target;
  // Never onto the target: the view direction would vanish.
  if (glm::length(offset) * factor < 1e-3f) return;
  camera.position = camera.target + offset * factor;
}

void panCamera(Camera& camera, float right, float up) {
  const glm::vec3 view = camera.target - camera.position;
  const float distance = glm::length(view);
  const glm::vec3 forward = view / distance;
  glm::vec3 side = glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f));
  if (glm::length(side) < 1e-6f) side = glm::vec3(1.0f, 0.0f, 0.0f);
  side = glm::normalize(side);
  const glm::vec3 upward = glm::cross(side, forward);
  const glm::vec3 move = distance * (right * side + up * upward);
  camera.position += move;
  camera.target += move;
}

void lookAround(Camera& camera, float yaw, float pitch) {
  camera.target = camera.position + rotated(camera.target - camera.position, -yaw, -pitch);
}

void flyCamera(Camera& camera, const glm::vec3& move) {
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 side = glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f));
  side = glm::length(side) < 1e-6f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::normalize(side);
  const glm::vec3 delta = move.x * forward + move.y * side + move.z * glm::vec3(0.0f, 1.0f, 0.0f);
  camera.position += delta;
  camera.target += delta;
}

glm::vec3 lightDirectionFrom(float azimuthDegrees, float elevationDegrees) {
  const float a = glm::radians(azimuthDegrees), e = glm::radians(elevationDegrees);
  // Travelling downwards from a point at this azimuth and elevation on the sky.
  return -glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
}

void lightAnglesOf(const glm::vec3& direction, float& azimuthDegrees, float& elevationDegrees) {
  const glm::vec3 towardsLight = -glm::normalize(direction);
  azimuthDegrees = glm::degrees(std::atan2(towardsLight.x, towardsLight.z));
  elevationDegrees = glm::degrees(std::asin(std::clamp(towardsLight.y, -1.0f, 1.0f)));
}

}  // namespace penumbra::viewer
