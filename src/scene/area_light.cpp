// Point samples of a disk or sphere area light (penumbra/area_light.h).
#include "penumbra/area_light.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <string>

#include "penumbra/error.h"

namespace penumbra {
namespace {

// Shirley and Chiu's concentric map of [-1,1]^2 onto the unit disk.
glm::vec2 concentricDisk(glm::vec2 square) {
  if (square.x == 0.0f && square.y == 0.0f) return glm::vec2(0.0f);
  const float quarter = 0.25f * glm::pi<float>();
  float radius = 0.0f, angle = 0.0f;
  if (std::abs(square.x) > std::abs(square.y)) {
    radius = square.x;
    angle = quarter * (square.y / square.x);
  } else {
    radius = square.y;
    angle = 2.0f * quarter - quarter * (square.x / square.y);
  }
  return radius * glm::vec2(std::cos(angle), std::sin(angle));
}

}  // namespace

void perpendicularBasis(glm::vec3 axis, glm::vec3& a, glm::vec3& b) {
  const glm::vec3 helper =
      std::abs(axis.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  a = glm::normalize(glm::cross(axis, helper));
  b = glm::cross(axis, a);
}

LightDisk lightDisk(const Light& light) {
  const float radius = 0.5f * light.size;
  glm::vec3 a, b;
  if (light.kind == LightKind::Spot) {
    perpendicularBasis(glm::normalize(light.target - light.position), a, b);
    return {light.position, radius * a, radius * b};
  }
  const glm::vec3 travel = glm::normalize(light.direction);
  perpendicularBasis(travel, a, b);
  return {-travel, radius * a, radius * b};
}

void checkSquareCount(int count, int minSide, int maxSide, std::string_view what) {
  const int side = int(std::lround(std::sqrt(double(std::max(count, 0)))));
  if (side < minSide || side > maxSide || side * side != count) {
    auto square = [](int k) { return std::to_string(k * k); };
    throw Error(std::string(what) + " " + std::to_string(count) +
                " must be a square side^2 with side in [" + std::to_string(minSide) + ", " +
                std::to_string(maxSide) + "] (" + square(minSide) + ", " + square(minSide + 1) +
                ", " + square(minSide + 2) + ", ..., " + square(maxSide) + ")");
  }
}

void checkAreaLightSamples(int count) {
  checkSquareCount(count, 8, 32, "area-light samples");
}

std::vector<glm::vec2> stratifiedDiskSamples(int count) {
  checkAreaLightSamples(count);
  const int side = int(std::lround(std::sqrt(double(count))));
  std::vector<glm::vec2> points;
  points.reserve(size_t(count));
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const glm::vec2 square((float(i) + 0.5f) / float(side), (float(j) + 0.5f) / float(side));
      points.push_back(concentricDisk(2.0f * square - 1.0f));
    }
  }
  return points;
}

Light areaLightSample(const Light& light, glm::vec2 diskPoint) {
  Light sample = light;
  sample.size = 0.0f;
  const LightDisk disk = lightDisk(light);
  const glm::vec3 offset = diskPoint.x * disk.axisA + diskPoint.y * disk.axisB;
  if (light.kind == LightKind::Spot) {
    // The sample keeps the axis: its target moves with it.
    sample.position += offset;
    sample.target += offset;
  } else {
    sample.direction = -glm::normalize(disk.centre + offset);
  }
  return sample;
}

std::vector<glm::vec3> stratifiedSphereSamples(int count) {
  checkAreaLightSamples(count);
  const int side = int(std::lround(std::sqrt(double(count))));
  std::vector<glm::vec3> points;
  points.reserve(size_t(count));
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const double u = (double(i) + 0.5) / double(side);
      const double v = (double(j) + 0.5) / double(side);
      const double z = 1.0 - 2.0 * u;
      const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = 2.0 * glm::pi<double>() * v;
      points.emplace_back(float(ring * std::cos(phi)), float(ring * std::sin(phi)), float(z));
    }
  }
  return points;
}

Light sphereLightSample(const Light& light, glm::vec3 spherePoint) {
  Light sample = light;
  sample.size = 0.0f;
  sample.position += 0.5f * light.size * spherePoint;
  return sample;
}

float sphereLightSampleWeight(const Light& light, glm::vec3 spherePoint, glm::vec3 receiver) {
  const glm::vec3 toReceiver = receiver - (light.position + 0.5f * light.size * spherePoint);
  const float squared = glm::dot(toReceiver, toReceiver);
  if (!(squared > 0.0f)) return 0.0f;
  const float facing = glm::dot(spherePoint, toReceiver) / std::sqrt(squared);
  return std::max(facing, 0.0f) / squared;
}

}  // namespace penumbra
