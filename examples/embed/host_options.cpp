// Options by table: each option's name and what its value sets.
#include "host_options.h"

#include <cstdio>
#include <functional>
#include <map>
#include <stdexcept>

namespace {

constexpr const char* kUsage =
    "usage: penumbra-embed [--technique ID] [--param NAME=VALUE]... [--size N] [--width N]\n"
    "  [--height N] [--blur TAPS] [--filter NAME] [--depth window|linear] [--light-dir X,Y,Z]\n"
    "  [--camera-pos X,Y,Z] [--camera-target X,Y,Z] [--camera-fov DEG] [--glsl-dir DIR]\n"
    "  [--write-obj PATH] [--out VISIBILITY.pfm] [--check-state]\n";

glm::vec3 parseVec3(const std::string& text) {
  glm::vec3 v;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v.x, &v.y, &v.z, &tail) != 3) {
    throw std::runtime_error("'" + text + "' is not X,Y,Z");
  }
  return v;
}

}  // namespace

const char* optionsUsage() {
  return kUsage;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  using Value = const std::string&;
  const std::map<std::string, std::function<void(Value)>> setters{
      {"--technique", [&](Value v) { o.technique = v; }},
      {"--param", [&](Value v) { o.params.push_back(v); }},
      {"--size", [&](Value v) { o.size = std::stoi(v); }},
      {"--width", [&](Value v) { o.width = std::stoi(v); }},
      {"--height", [&](Value v) { o.height = std::stoi(v); }},
      {"--blur", [&](Value v) { o.blurTaps = std::stoi(v); }},
      {"--filter", [&](Value v) { o.filter = v; }},
      {"--depth", [&](Value v) { o.depth = v; }},
      {"--light-dir", [&](Value v) { o.lightDir = parseVec3(v); }},
      {"--camera-pos", [&](Value v) { o.cameraPos = parseVec3(v); }},
      {"--camera-target", [&](Value v) { o.cameraTarget = parseVec3(v); }},
      {"--camera-fov", [&](Value v) { o.cameraFov = std::stof(v); }},
      {"--glsl-dir", [&](Value v) { o.glslDir = v; }},
      {"--write-obj", [&](Value v) { o.writeObj = v; }},
      {"--out", [&](Value v) { o.out = v; }},
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--check-state") {
      o.checkState = true;
      continue;
    }
    const auto setter = setters.find(a);
    if (setter == setters.end()) throw std::runtime_error("unknown option " + a);
    if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
    const std::string value = argv[++i];
    try {
      setter->second(value);
    } catch (const std::logic_error&) {  // std::stoi's and std::stof's
      throw std::runtime_error(a + ": '" + value + "' is not a number");
    }
  }
  if (o.blurTaps < 1 || o.blurTaps % 2 == 0) throw std::runtime_error("--blur takes odd taps");
  if (o.depth != "window" && o.depth != "linear") throw std::runtime_error("--depth window|linear");
  return o;
}
