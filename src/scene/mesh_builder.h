// Procedural primitives with normals, appended to a mesh.
#pragma once

#include "penumbra/scene.h"

namespace penumbra::scene {

// An axis-aligned box, optionally rotated about y by `yawRadians`.
void addBox(Mesh& mesh, glm::vec3 centre, glm::vec3 halfExtents, float yawRadians = 0.0f);
// A box with an arbitrary orientation: the columns of `axes` are its local x, y, z.
void addOrientedBox(Mesh& mesh, glm::vec3 centre, glm::vec3 halfExtents, const glm::mat3& axes);
// A horizontal square facing +y.
void addGround(Mesh& mesh, glm::vec3 centre, float halfSize);
void addSphere(Mesh& mesh, glm::vec3 centre, float radius, int segments = 24);
void addCylinder(Mesh& mesh, glm::vec3 baseCentre, float radius, float height, int segments = 16);

Mesh makeMesh(glm::vec3 albedo);

}  // namespace penumbra::scene
