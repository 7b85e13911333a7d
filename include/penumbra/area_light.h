// The area light behind soft shadows (Light::size): a disk, stood in for by N point lights spread
// evenly over it. The area-light reference (docs/reference.md) averages the hard shadow tests of
// one shadow map per sample point (gl::Renderer::renderAreaLightReference).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra {

// Sample counts of the reference: perfect squares side^2, side in [8, 32].
inline constexpr int kMinAreaLightSamples = 64;
inline constexpr int kMaxAreaLightSamples = 1024;

// Throws Error naming the valid counts unless `count` is side^2 with side in [8, 32].
void checkAreaLightSamples(int count);

// `count` (= side^2) points on the unit disk, stratified: the centres of a side x side grid over
// the unit square mapped by Shirley and Chiu's concentric map ("A Low Distortion Map Between Disk
// and Square", 1997), which preserves area, so each point stands for 1/count of the disk.
std::vector<glm::vec2> stratifiedDiskSamples(int count);

// The point light at `diskPoint` (unit disk coordinates) of an area light, with size 0.
// Spot: the disk of diameter size centred on the light, perpendicular to its axis; the sample
// keeps the axis (its target moves with it). Directional: the direction towards the sample point
// of a disk of diameter size at unit distance, so the directions fill a cone whose angular
// diameter has tangent size.
Light areaLightSample(const Light& light, glm::vec2 diskPoint);

}  // namespace penumbra
