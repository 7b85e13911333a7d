// A ground plane and four boxes (one floating: a caster far above its receiver, where the
// filtered techniques' bleeding and the ESM fallback show).
#include "host_scene.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace {

void addQuad(HostScene& s, const float corners[4][3], const float normal[3]) {
  const auto base = uint32_t(s.vertices.size());
  for (int i = 0; i < 4; ++i) {
    s.vertices.push_back(
        {{corners[i][0], corners[i][1], corners[i][2]}, {normal[0], normal[1], normal[2]}});
  }
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(base + i);
}

// An axis-aligned box: six faces with their own normals, each quad counter-clockwise from
// outside.
void addBox(HostScene& s, float cx, float cy, float cz, float hx, float hy, float hz) {
  const float x0 = cx - hx, x1 = cx + hx, y0 = cy - hy, y1 = cy + hy, z0 = cz - hz, z1 = cz + hz;
  const float faces[6][4][3] = {
      {{x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}},  // +x
      {{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}},  // -x
      {{x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}},  // +y
      {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}},  // -y
      {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}},  // +z
      {{x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}},  // -z
  };
  const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) addQuad(s, faces[f], normals[f]);
}

}  // namespace

HostScene makeHostScene() {
  HostScene s;
  const float ground[4][3] = {{-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}};
  const float up[3] = {0, 1, 0};
  addQuad(s, ground, up);
  addBox(s, -1.5f, 0.75f, 0.5f, 0.75f, 0.75f, 0.75f);
  addBox(s, 1.0f, 1.0f, -1.0f, 0.25f, 1.0f, 0.5f);
  addBox(s, 0.5f, 1.75f, 1.25f, 1.0f, 0.125f, 0.75f);  // floating
  addBox(s, 2.0f, 0.25f, 1.5f, 0.25f, 0.25f, 0.25f);
  std::copy_n(s.vertices[0].position, 3, s.boundsMin);
  std::copy_n(s.vertices[0].position, 3, s.boundsMax);
  for (const HostVertex& v : s.vertices) {
    for (int a = 0; a < 3; ++a) {
      s.boundsMin[a] = std::min(s.boundsMin[a], v.position[a]);
      s.boundsMax[a] = std::max(s.boundsMax[a], v.position[a]);
    }
  }
  return s;
}

void writeObj(const HostScene& scene, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "# penumbra examples/embed: the host's scene\n";
  // Multiples of 1/8 print exactly in the default notation.
  for (const HostVertex& v : scene.vertices) {
    out << "v " << v.position[0] << ' ' << v.position[1] << ' ' << v.position[2] << '\n';
  }
  for (const HostVertex& v : scene.vertices) {
    out << "vn " << v.normal[0] << ' ' << v.normal[1] << ' ' << v.normal[2] << '\n';
  }
  for (size_t i = 0; i + 2 < scene.indices.size(); i += 3) {
    out << 'f';
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t n = scene.indices[i + k] + 1;
      out << ' ' << n << "//" << n;
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
}
