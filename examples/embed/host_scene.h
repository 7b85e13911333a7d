// The example host's own scene: a ground plane and a few boxes, defined in code, and the OBJ
// writer that lets `penumbra render --scene` draw the very same triangles.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

struct HostVertex {
  float position[3];
  float normal[3];
};

struct HostScene {
  std::vector<HostVertex> vertices;
  std::vector<uint32_t> indices;  // triangles, counter-clockwise seen from outside
  float boundsMin[3];
  float boundsMax[3];
};

// Every coordinate is a multiple of 1/8, so OBJ text carries it exactly both ways.
HostScene makeHostScene();

// Positions, normals and faces (1-based v//vn), one triangle per `f` line in index order.
void writeObj(const HostScene& scene, const std::filesystem::path& path);
