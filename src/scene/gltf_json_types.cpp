// The schema's types by property name: glTF 2.0 reuses each core property name with one type,
// except "indices" (an index in a primitive, an object in a sparse accessor), "nodes" (objects at
// the top level, indices in a scene) and "target" (an index in a buffer view, an object in an
// animation channel), and "scale" (a vector in a node, a number in a texture reference).
// Properties outside the core schema (glTF 1.0 leftovers, application keys) are not descended
// into.
#include "gltf_json_types.h"

#include <nlohmann/json.hpp>
#include <string_view>
#include <unordered_map>

#include "penumbra/error.h"

namespace penumbra::scene {
namespace {

using nlohmann::json;

enum class Kind {
  String,
  Index,  // a non-negative integer
  Number,
  Boolean,
  Object,
  Numbers,         // an array of numbers
  Indices,         // an array of non-negative integers
  Strings,         // an array of strings
  Objects,         // an array of objects
  ObjectOfIndices  // an object whose values are non-negative integers (attributes)
};

const std::unordered_map<std::string_view, Kind>& schema() {
  static const std::unordered_map<std::string_view, Kind> kinds = {
      {"name", Kind::String},
      {"uri", Kind::String},
      {"mimeType", Kind::String},
      {"alphaMode", Kind::String},
      {"type", Kind::String},
      {"version", Kind::String},
      {"minVersion", Kind::String},
      {"generator", Kind::String},
      {"copyright", Kind::String},
      {"interpolation", Kind::String},
      {"path", Kind::String},
      {"scene", Kind::Index},
      {"buffer", Kind::Index},
      {"bufferView", Kind::Index},
      {"byteOffset", Kind::Index},
      {"byteLength", Kind::Index},
      {"byteStride", Kind::Index},
      {"componentType", Kind::Index},
      {"count", Kind::Index},
      {"material", Kind::Index},
      {"mode", Kind::Index},
      {"mesh", Kind::Index},
      {"camera", Kind::Index},
      {"skin", Kind::Index},
      {"source", Kind::Index},
      {"sampler", Kind::Index},
      {"index", Kind::Index},
      {"texCoord", Kind::Index},
      {"input", Kind::Index},
      {"output", Kind::Index},
      {"node", Kind::Index},
      {"magFilter", Kind::Index},
      {"minFilter", Kind::Index},
      {"wrapS", Kind::Index},
      {"wrapT", Kind::Index},
      {"skeleton", Kind::Index},
      {"inverseBindMatrices", Kind::Index},
      {"strength", Kind::Number},
      {"alphaCutoff", Kind::Number},
      {"metallicFactor", Kind::Number},
      {"roughnessFactor", Kind::Number},
      {"yfov", Kind::Number},
      {"znear", Kind::Number},
      {"zfar", Kind::Number},
      {"aspectRatio", Kind::Number},
      {"xmag", Kind::Number},
      {"ymag", Kind::Number},
      {"doubleSided", Kind::Boolean},
      {"normalized", Kind::Boolean},
      {"asset", Kind::Object},
      {"pbrMetallicRoughness", Kind::Object},
      {"baseColorTexture", Kind::Object},
      {"metallicRoughnessTexture", Kind::Object},
      {"normalTexture", Kind::Object},
      {"occlusionTexture", Kind::Object},
      {"emissiveTexture", Kind::Object},
      {"sparse", Kind::Object},
      {"values", Kind::Object},
      {"perspective", Kind::Object},
      {"orthographic", Kind::Object},
      {"target", Kind::Object},
      {"matrix", Kind::Numbers},
      {"translation", Kind::Numbers},
      {"rotation", Kind::Numbers},
      {"baseColorFactor", Kind::Numbers},
      {"emissiveFactor", Kind::Numbers},
      {"weights", Kind::Numbers},
      {"min", Kind::Numbers},
      {"max", Kind::Numbers},
      {"children", Kind::Indices},
      {"nodes", Kind::Indices},
      {"joints", Kind::Indices},
      {"extensionsUsed", Kind::Strings},
      {"extensionsRequired", Kind::Strings},
      {"accessors", Kind::Objects},
      {"animations", Kind::Objects},
      {"buffers", Kind::Objects},
      {"bufferViews", Kind::Objects},
      {"cameras", Kind::Objects},
      {"images", Kind::Objects},
      {"materials", Kind::Objects},
      {"meshes", Kind::Objects},
      {"samplers", Kind::Objects},
      {"scenes", Kind::Objects},
      {"skins", Kind::Objects},
      {"textures", Kind::Objects},
      {"primitives", Kind::Objects},
      {"channels", Kind::Objects},
      {"targets", Kind::Objects},
      {"attributes", Kind::ObjectOfIndices},
  };
  return kinds;
}

const char* typeName(const json& v) {
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number_integer() && v.get<int64_t>() < 0) return "negative";
  if (v.is_number_integer()) return "an integer";
  if (v.is_number()) return "a number with a fraction or exponent";
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  return "null";
}

// Indices must also fit the int that tinygltf stores them in.
bool isIndex(const json& v) {
  return v.is_number_unsigned() && v.get<uint64_t>() <= uint64_t(INT32_MAX);
}

class Checker {
 public:
  explicit Checker(std::string name) : name_(std::move(name)) {}

  void object(const json& o, const std::string& path, int depth) {
    if (depth > kMaxDepth) fail(path, "nested no deeper than " + std::to_string(kMaxDepth), o);
    for (const auto& [key, value] : o.items()) {
      const std::string at = path.empty() ? key : path + "." + key;
      if (key == "extras") continue;  // application data, any type
      if (key == "extensions") {
        if (!value.is_object()) fail(at, "an object", value);
        for (const auto& [extension, content] : value.items()) {
          if (!content.is_object()) fail(at + "." + extension, "an object", content);
        }
        continue;
      }
      const bool sparseIndices = key == "indices" && path.ends_with(".sparse");
      if (key == "indices") {
        if (sparseIndices ? !value.is_object() : !isIndex(value)) {
          fail(at, sparseIndices ? "an object" : "a non-negative integer", value);
        }
      } else if (key == "nodes") {
        check(value, path.empty() ? Kind::Objects : Kind::Indices, at);
      } else if (key == "target") {
        check(value, path.find("channels[") != std::string::npos ? Kind::Object : Kind::Index, at);
      } else if (key == "scale") {
        const bool node = path.starts_with("nodes[") && path.find('.') == std::string::npos;
        check(value, node ? Kind::Numbers : Kind::Number, at);
      } else if (auto rule = schema().find(key); rule != schema().end()) {
        check(value, rule->second, at);
      } else {
        continue;
      }
      if (value.is_object()) object(value, at, depth + 1);
      if (value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i) {
          if (value[i].is_object()) object(value[i], at + "[" + std::to_string(i) + "]", depth + 1);
        }
      }
    }
  }

 private:
  static constexpr int kMaxDepth = 32;

  [[noreturn]] void fail(const std::string& path, const std::string& expected, const json& v) {
    throw Error(name_ + ": " + path + " must be " + expected + " (it is " + typeName(v) + ")");
  }

  void check(const json& v, Kind kind, const std::string& at) {
    const auto each = [&](auto ok, const char* what) {
      if (!v.is_array()) fail(at, std::string("an array of ") + what, v);
      for (size_t i = 0; i < v.size(); ++i) {
        if (!ok(v[i])) fail(at + "[" + std::to_string(i) + "]", what, v[i]);
      }
    };
    switch (kind) {
      case Kind::String:
        if (!v.is_string()) fail(at, "a string", v);
        break;
      case Kind::Index:
        if (!isIndex(v)) fail(at, "a non-negative integer", v);
        break;
      case Kind::Number:
        if (!v.is_number()) fail(at, "a number", v);
        break;
      case Kind::Boolean:
        if (!v.is_boolean()) fail(at, "a boolean", v);
        break;
      case Kind::Object:
        if (!v.is_object()) fail(at, "an object", v);
        break;
      case Kind::Numbers: each([](const json& e) { return e.is_number(); }, "numbers"); break;
      case Kind::Indices: each(isIndex, "non-negative integers"); break;
      case Kind::Strings: each([](const json& e) { return e.is_string(); }, "strings"); break;
      case Kind::Objects: each([](const json& e) { return e.is_object(); }, "objects"); break;
      case Kind::ObjectOfIndices:
        if (!v.is_object()) fail(at, "an object", v);
        for (const auto& [key, value] : v.items()) {
          if (!isIndex(value)) fail(at + "." + key, "a non-negative integer", value);
        }
        break;
    }
  }

  std::string name_;
};

// Arrays and objects nested deeper than this are refused before anything parses the JSON:
// tinygltf converts "extras" and extension objects to its own values recursively, with half a
// KiB of stack a level (a 200 KB file of brackets overflowed the thread's stack). glTF's own
// structure nests fewer than 10 levels.
constexpr int kMaxJsonNesting = 128;

void refuseDeepNesting(std::span<const uint8_t> text, const std::string& name) {
  int depth = 0;
  bool inString = false, escaped = false;
  for (size_t at = 0; at < text.size(); ++at) {
    const uint8_t c = text[at];
    if (inString) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting) {
        throw Error(name + ": its JSON nests arrays and objects deeper than " +
                    std::to_string(kMaxJsonNesting) + " levels (at byte " + std::to_string(at) +
                    " of the JSON); penumbra reads at most " + std::to_string(kMaxJsonNesting));
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

}  // namespace

void checkGltfJsonTypes(std::span<const uint8_t> text, const std::string& name) {
  refuseDeepNesting(text, name);
  json document = json::parse(text.begin(), text.end(), nullptr, false);
  if (document.is_discarded()) return;  // not JSON: tinygltf's message says where
  if (!document.is_object()) throw Error(name + ": the glTF JSON must be an object");
  Checker(name).object(document, "", 0);
}

}  // namespace penumbra::scene
