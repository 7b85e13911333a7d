// The mostly-shadowed frame and its likely cause.
#include "penumbra/compare/shadowed_frame.h"

#include <cmath>
#include <sstream>

#include "penumbra/error.h"

namespace penumbra::compare {
namespace {

bool inside(const Bounds& b, glm::vec3 p) {
  return p.x >= b.min.x && p.y >= b.min.y && p.z >= b.min.z && p.x <= b.max.x &&
         p.y <= b.max.y && p.z <= b.max.z;
}

std::string text(glm::vec3 v) {
  std::ostringstream out;
  out.precision(4);
  out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

}  // namespace

double shadowedShare(const Image& visibility, const Image& coverage) {
  if (coverage.width() != visibility.width() || coverage.height() != visibility.height()) {
    throw Error("the shadowed share's coverage is not the visibility's size");
  }
  size_t drawn = 0, shadowed = 0;
  for (int y = 0; y < visibility.height(); ++y) {
    for (int x = 0; x < visibility.width(); ++x) {
      if (!(coverage.at(x, y) > 0.5f)) continue;
      ++drawn;
      shadowed += visibility.at(x, y) < 0.5f;
    }
  }
  return drawn == 0 ? 0.0 : double(shadowed) / double(drawn);
}

std::optional<std::string> mostlyShadowedWarning(const Scene& scene, double share) {
  if (!(share > kMostlyShadowedShare)) return std::nullopt;
  std::ostringstream out;
  out.precision(3);
  out << 100.0 * share
      << "% of the lit surfaces are in shadow for every technique: the frame shows the view more "
         "than the techniques. ";
  // What casts shadows and receives them: a sky dome that casts none blocks no light.
  const Bounds bounds = scene.shadowBounds();
  const Light& light = scene.light;
  if (light.kind != LightKind::Directional && !inside(bounds, light.position)) {
    out << "The " << lightKindName(light.kind) << " light at " << text(light.position)
        << " is outside the bounds of what casts shadows " << text(bounds.min) << " - "
        << text(bounds.max)
        << ": geometry that encloses the scene (a sky dome, walls) stands between it and "
           "everything; place it inside with --light-pos.";
  } else if (inside(bounds, scene.camera.position)) {
    out << "The camera at " << text(scene.camera.position)
        << " is inside the bounds of what casts shadows: geometry enclosing it (a room, a sky "
           "dome that casts) may block the light; try --light point --light-pos inside it, or a "
           "camera outside.";
  } else {
    out << "Most of what the camera sees faces away from the light or lies under other geometry; "
           "try another --light-dir or --camera-pos.";
  }
  return out.str();
}

}  // namespace penumbra::compare
