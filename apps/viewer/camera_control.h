// Orbit and fly cameras over penumbra::Camera (position, target, field of view), and the
// directional light's direction as azimuth and elevation: the mouse and keyboard move them.
#pragma once

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra::viewer {

enum class CameraMode { Orbit, Fly };

// Orbit: turns the camera around its target (yaw about +y, pitch clamped short of the poles).
void orbitCamera(Camera& camera, float yawRadians, float pitchRadians);
// Orbit: moves the camera towards (factor < 1) or away from its target.
void dollyCamera(Camera& camera, float factor);
// Orbit: moves camera and target together in the view plane, by a share of the target distance.
void panCamera(Camera& camera, float right, float up);
// Fly: turns the view direction about the camera's position.
void lookAround(Camera& camera, float yawRadians, float pitchRadians);
// Fly: moves camera and target along the view (forward), its right and world up, in world units.
void flyCamera(Camera& camera, const glm::vec3& forwardRightUp);

// A light direction (the way the light travels) from azimuth and elevation above the horizon in
// degrees, and back.
glm::vec3 lightDirectionFrom(float azimuthDegrees, float elevationDegrees);
void lightAnglesOf(const glm::vec3& direction, float& azimuthDegrees, float& elevationDegrees);

}  // namespace penumbra::viewer
