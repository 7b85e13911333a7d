// The area light behind soft shadows (Light::size): a disk (directional, spot) or a sphere
// (point), stood in for by N point lights spread evenly over it. The area-light reference
// (docs/reference.md) averages the hard shadow tests of one shadow map per sample point
// (gl::Renderer::renderAreaLightReference).
#pragma once

#include <glm/glm.hpp>
#include <string_view>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra {

// Sample counts of the reference: perfect squares side^2, side in [8, 32].
inline constexpr int kMinAreaLightSamples = 64;
inline constexpr int kMaxAreaLightSamples = 1024;

// Throws Error naming `what` and the valid counts unless `count` is side^2 with side in
// [minSide, maxSide]: stratified grids of side x side cells.
void checkSquareCount(int count, int minSide, int maxSide, std::string_view what);
// Throws Error naming the valid counts unless `count` is side^2 with side in [8, 32].
void checkAreaLightSamples(int count);

// `count` (= side^2) points on the unit disk, stratified: the centres of a side x side grid over
// the unit square mapped by Shirley and Chiu's concentric map ("A Low Distortion Map Between Disk
// and Square", 1997), which preserves area, so each point stands for 1/count of the disk.
std::vector<glm::vec2> stratifiedDiskSamples(int count);
// A disk light (spot, or directional with a size) as a centre and two perpendicular axes of the
// disk's radius: the point of unit-disk coordinates (x, y) is centre + x axisA + y axisB. Spot:
// in world units around the light's position. Directional: at unit distance from the receiver,
// towards the light (centre = -direction), so the way a sample's light travels is
// -normalize(point). areaLightSample builds its samples from it.
// Two unit vectors perpendicular to the unit `axis` and to each other (a, b, axis right-handed).
void perpendicularBasis(glm::vec3 axis, glm::vec3& a, glm::vec3& b);

struct LightDisk {
  glm::vec3 centre;
  glm::vec3 axisA;
  glm::vec3 axisB;
};
LightDisk lightDisk(const Light& light);

// The point light at `diskPoint` (unit disk coordinates) of an area light, with size 0.
// Spot: the disk of diameter size centred on the light, perpendicular to its axis; the sample
// keeps the axis (its target moves with it). Directional: the direction towards the sample point
// of a disk of diameter size at unit distance, so the directions fill a cone whose angular
// diameter has tangent size.
Light areaLightSample(const Light& light, glm::vec2 diskPoint);

// `count` (= side^2) points on the unit sphere, stratified: the centres of a side x side grid
// over the unit square (u, v) mapped by Archimedes' map z = 1 - 2u, phi = 2 pi v, which
// preserves area, so each point stands for 1/count of the sphere's surface.
std::vector<glm::vec3> stratifiedSphereSamples(int count);

// The point light at `spherePoint` (unit sphere coordinates) of a point light's sphere of
// diameter size, with size 0.
Light sphereLightSample(const Light& light, glm::vec3 spherePoint);

// The share of the sphere light's radiance that its sample at `spherePoint` sends to `receiver`,
// up to a factor common to all samples: a uniformly radiant (Lambertian) sphere's surface element
// at y, normal n, is seen from x under the solid angle max(0, n . (x - y) / |x - y|) / |x - y|^2
// per unit area, so uniform samples of the surface weighted so sample the silhouette disk by
// solid angle (docs/reference.md). 0 for the samples x cannot see.
float sphereLightSampleWeight(const Light& light, glm::vec3 spherePoint, glm::vec3 receiver);

}  // namespace penumbra
