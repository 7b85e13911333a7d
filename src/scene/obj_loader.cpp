// OBJ import: tinyobjloader parses (polygons triangulated as fans), this file checks every index
// and groups the faces by material into meshes, one vertex per distinct position/normal/texcoord.
#include "obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "file_scene.h"
#include "image_decoding.h"
#include "penumbra/error.h"

namespace penumbra::scene {
namespace {

namespace fs = std::filesystem;

// Material libraries through the caller's file reader (tinyobjloader's own reads the disk).
class LibraryReader : public tinyobj::MaterialReader {
 public:
  explicit LibraryReader(const ObjFileReader& read) : read_(read) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warn, std::string*) override {
    const std::optional<std::vector<uint8_t>> bytes = read_(name);
    if (!bytes) {
      if (warn) *warn += "material library '" + name + "' cannot be read\n";
      return false;
    }
    std::istringstream in(std::string(bytes->begin(), bytes->end()));
    tinyobj::LoadMtl(names, materials, &in, warn, nullptr);
    return true;
  }

 private:
  const ObjFileReader& read_;
};

std::optional<TextureImage> readTexture(const std::string& file, const ObjFileReader& read,
                                        const std::string& source,
                                        std::vector<std::string>& warnings) {
  const std::optional<std::vector<uint8_t>> bytes = read(file);
  std::string why = "it cannot be read";
  std::optional<TextureImage> image;
  if (bytes) image = decodeImage(*bytes, file, why);
  if (!image) warnings.push_back(source + ": texture '" + file + "' cannot be used: " + why);
  return image;
}

// The material's texture: map_Kd's colour with map_d's luminance as alpha (the .mtl convention
// for cut-outs), map_d sampled at map_Kd's texel centres where their sizes differ.
std::optional<TextureImage> materialTexture(const tinyobj::material_t& m, const ObjFileReader& read,
                                            const std::string& source,
                                            std::vector<std::string>& warnings) {
  std::optional<TextureImage> colour, alpha;
  if (!m.diffuse_texname.empty()) colour = readTexture(m.diffuse_texname, read, source, warnings);
  if (!m.alpha_texname.empty()) alpha = readTexture(m.alpha_texname, read, source, warnings);
  if (!alpha) return colour;
  TextureImage out = colour ? *colour : *alpha;
  if (!colour) {
    for (size_t i = 0; i < out.rgba.size(); i += 4)
      out.rgba[i] = out.rgba[i + 1] = out.rgba[i + 2] = 255;
  }
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const int ax = std::min(alpha->width - 1,
                              int((float(x) + 0.5f) * float(alpha->width) / float(out.width)));
      const int ay = std::min(alpha->height - 1,
                              int((float(y) + 0.5f) * float(alpha->height) / float(out.height)));
      const uint8_t* a = &alpha->rgba[(size_t(ay) * size_t(alpha->width) + size_t(ax)) * 4];
      // Rec. 709 luma of the (sRGB-encoded) mask: masks are black and white in practice.
      const float luma = 0.2126f * float(a[0]) + 0.7152f * float(a[1]) + 0.0722f * float(a[2]);
      out.rgba[(size_t(y) * size_t(out.width) + size_t(x)) * 4 + 3] = uint8_t(std::lround(luma));
    }
  }
  out.name = m.alpha_texname;
  return out;
}

// tinyobjloader (Debian's 2.0.0~rc) converts a skin-weight line's joint ids (`vw VERTEX JOINT
// WEIGHT ...`, its extension) to int unchecked (tiny_obj_loader.h:2669): a joint beyond int's
// range is undefined behaviour (the fuzzer's "vw 0 6000000000"). Penumbra reads no skin weights;
// such a line is refused here, before tinyobjloader sees it, tokenised as tinyobjloader does
// (lines end at \n, \r or \r\n; tokens at spaces, tabs and \r; a number is the longest
// numeric prefix of its token, which strtod reads the same or larger).
void refuseSkinJointsBeyondInt(const std::string& objText, const std::string& name) {
  size_t lineNumber = 0;
  for (size_t start = 0; start < objText.size();) {
    const size_t end = std::min(objText.find_first_of("\r\n", start), objText.size());
    ++lineNumber;
    const std::string_view line(objText.data() + start, end - start);
    start = end + (objText.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line.size() < first + 3 ||
        line.compare(first, 2, "vw") != 0 || (line[first + 2] != ' ' && line[first + 2] != '\t'))
      continue;
    // Tokens after "vw": the vertex, then joint and weight pairs.
    int index = 0;
    for (size_t at = first + 2;;) {
      at = line.find_first_not_of(" \t", at);
      if (at == std::string_view::npos) break;
      const size_t tokenEnd = std::min(line.find_first_of(" \t", at), line.size());
      const std::string token(line.substr(at, tokenEnd - at));
      at = tokenEnd;
      if (index++ % 2 != 1) continue;  // the vertex and the weights
      const double joint = std::strtod(token.c_str(), nullptr);
      if (!(joint >= -2147483648.0 && joint < 2147483648.0)) {
        throw Error(name + ": line " + std::to_string(lineNumber) + ": skin weight (vw) joint '" +
                    token + "' is outside int's range [-2147483648, 2147483647]");
      }
    }
  }
}

struct VertexKey {
  int position, normal, texcoord, face;  // face: -1, or the face of a flat-normal vertex
  bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    size_t h = std::hash<int>()(k.position);
    for (int v : {k.normal, k.texcoord, k.face}) h = h * 1000003u ^ std::hash<int>()(v);
    return h;
  }
};

}  // namespace

Scene loadObj(const std::string& objText, const std::string& name, const ObjFileReader& readFile) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  refuseSkinJointsBeyondInt(objText, name);
  std::istringstream in(objText);
  LibraryReader libraries(readFile);
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &libraries, true, false)) {
    throw Error(name +
                ": not a valid OBJ file: " + (err.empty() ? "tinyobjloader gave no reason" : err));
  }
  Scene scene;
  std::istringstream warnings(warn);
  for (std::string line; std::getline(warnings, line);) {
    if (!line.empty()) scene.warnings.push_back(name + ": " + line);
  }

  // One mesh per material (-1: none), its texture loaded once.
  std::map<int, size_t> meshOfMaterial;
  std::vector<std::unordered_map<VertexKey, uint32_t, VertexKeyHash>> vertexMaps;
  const auto meshFor = [&](int material) -> size_t {
    if (auto found = meshOfMaterial.find(material); found != meshOfMaterial.end())
      return found->second;
    Mesh mesh;
    if (material >= 0) {
      const tinyobj::material_t& m = materials[size_t(material)];
      mesh.albedo = glm::clamp(
          glm::vec3(float(m.diffuse[0]), float(m.diffuse[1]), float(m.diffuse[2])), 0.0f, 1.0f);
      if (!std::isfinite(mesh.albedo.x + mesh.albedo.y + mesh.albedo.z)) {
        throw Error(name + ": material '" + m.name +
                    "' has a diffuse colour Kd that is not finite");
      }
      mesh.opacity = std::isfinite(m.dissolve) ? std::clamp(float(m.dissolve), 0.0f, 1.0f) : 1.0f;
      if (std::optional<TextureImage> t = materialTexture(m, readFile, name, scene.warnings)) {
        mesh.baseColorTexture = int(scene.textures.size());
        scene.textures.push_back(std::move(*t));
      }
      if (!m.alpha_texname.empty()) {
        mesh.alphaMode = AlphaMode::Mask;
      } else if (mesh.opacity < 1.0f) {
        mesh.alphaMode = AlphaMode::Blend;
        scene.warnings.push_back(name + ": material '" + m.name + "' is partly transparent (d " +
                                 std::to_string(mesh.opacity) + "): drawn as a mask at 0.5");
      }
    }
    meshOfMaterial[material] = scene.meshes.size();
    scene.meshes.push_back(std::move(mesh));
    vertexMaps.emplace_back();
    return scene.meshes.size() - 1;
  };

  const size_t positions = attrib.vertices.size() / 3;
  const size_t normals = attrib.normals.size() / 3;
  const size_t texcoords = attrib.texcoords.size() / 2;
  int faceNumber = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++faceNumber) {
      const size_t corners = shape.mesh.num_face_vertices[f];
      if (offset + corners > shape.mesh.indices.size()) {
        throw Error(name + ": shape '" + shape.name + "' face " + std::to_string(f) +
                    " has more corners than indices");
      }
      const tinyobj::index_t* face = &shape.mesh.indices[offset];
      offset += corners;
      if (corners != 3) continue;  // fewer than three corners: nothing to draw
      int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      if (material >= int(materials.size())) material = -1;
      bool hasNormals = true;
      for (size_t k = 0; k < 3; ++k) {
        const tinyobj::index_t& i = face[k];
        const auto bad = [&](const char* what, int index, size_t count) {
          throw Error(name + ": shape '" + shape.name + "' face " + std::to_string(f) + " names " +
                      what + " " + std::to_string(index + 1) + ", but the file has " +
                      std::to_string(count));
        };
        if (i.vertex_index < 0 || size_t(i.vertex_index) >= positions)
          bad("vertex", i.vertex_index, positions);
        if (i.normal_index >= 0 && size_t(i.normal_index) >= normals)
          bad("normal", i.normal_index, normals);
        if (i.texcoord_index >= 0 && size_t(i.texcoord_index) >= texcoords)
          bad("texture coordinate", i.texcoord_index, texcoords);
        if (i.normal_index < -1 || i.texcoord_index < -1)
          bad("an index", std::min(i.normal_index, i.texcoord_index), 0);
        hasNormals &= i.normal_index >= 0;
      }
      const size_t m = meshFor(material);
      Mesh& mesh = scene.meshes[m];
      const size_t first = mesh.indices.size();
      for (size_t k = 0; k < 3; ++k) {
        const tinyobj::index_t& i = face[k];
        // Faces without normals get their own vertices, to take the face's flat normal.
        const VertexKey key{i.vertex_index, hasNormals ? i.normal_index : -1, i.texcoord_index,
                            hasNormals ? -1 : faceNumber};
        auto [it, inserted] = vertexMaps[m].try_emplace(key, uint32_t(mesh.vertices.size()));
        if (inserted) {
          Vertex v;
          const size_t p = 3 * size_t(i.vertex_index);
          v.position =
              glm::vec3(attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]);
          if (hasNormals) {
            const size_t n = 3 * size_t(i.normal_index);
            v.normal = glm::vec3(attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]);
          }
          if (i.texcoord_index >= 0) {
            const size_t t = 2 * size_t(i.texcoord_index);
            // OBJ's v runs up from the image's bottom row; penumbra's from its top row.
            v.texcoord = glm::vec2(attrib.texcoords[t], 1.0f - attrib.texcoords[t + 1]);
          }
          mesh.vertices.push_back(v);
        }
        mesh.indices.push_back(it->second);
      }
      if (!hasNormals) {
        const glm::vec3 a = mesh.vertices[mesh.indices[first]].position;
        const glm::vec3 b = mesh.vertices[mesh.indices[first + 1]].position;
        const glm::vec3 c = mesh.vertices[mesh.indices[first + 2]].position;
        const glm::vec3 n = glm::cross(b - a, c - a);
        // Zero or non-finite normals are replaced by finishFileScene.
        for (size_t k = 0; k < 3; ++k) mesh.vertices[mesh.indices[first + k]].normal = n;
      }
    }
  }
  std::erase_if(scene.meshes, [](const Mesh& m) { return m.indices.empty(); });
  if (scene.meshes.empty()) throw Error(name + ": the file has no triangles to render");
  finishFileScene(scene, name, {});
  return scene;
}

Scene loadObjFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open scene file " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error("cannot read scene file " + path.string());
  const fs::path folder = path.parent_path();
  const ObjFileReader read = [&](const std::string& name) -> std::optional<std::vector<uint8_t>> {
    // Files written on Windows name textures with backslashes (".\\bark.jpg").
    std::string portable = name;
    std::replace(portable.begin(), portable.end(), '\\', '/');
    std::ifstream file(folder / portable, std::ios::binary);
    if (!file) return std::nullopt;
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(file)),
                                std::istreambuf_iterator<char>());
  };
  return loadObj(text.str(), path.string(), read);
}

}  // namespace penumbra::scene
