// OBJ import: tinyobjloader parses (polygons triangulated by ear clipping), this file checks every
// number and index and groups the faces by material into meshes, one vertex per distinct
// position/normal/texcoord.
#include "obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "file_scene.h"
#include "image_decoding.h"
#include "penumbra/error.h"
#include "scene_file_reading.h"

namespace penumbra::scene {
namespace {

namespace fs = std::filesystem;

// Calls visit(lineNumber, keyword, tokens) for each line of an OBJ or MTL text as
// tinyobjloader reads it: lines end at \n, \r or \r\n, and at a NUL (it reads each line as a C
// string); the keyword is the first token, the tokens those after it, split at spaces and tabs.
template <typename Visit>
void forEachStatement(const std::string& text, Visit&& visit) {
  size_t lineNumber = 0;
  std::vector<std::string_view> tokens;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find_first_of("\r\n", start), text.size());
    ++lineNumber;
    std::string_view line(text.data() + start, end - start);
    start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    line = line.substr(0, line.find('\0'));
    tokens.clear();
    for (size_t at = 0;;) {
      at = line.find_first_not_of(" \t", at);
      if (at == std::string_view::npos) break;
      const size_t tokenEnd = std::min(line.find_first_of(" \t", at), line.size());
      tokens.push_back(line.substr(at, tokenEnd - at));
      at = tokenEnd;
    }
    if (!tokens.empty()) {
      visit(lineNumber, tokens.front(), std::span<const std::string_view>(tokens).subspan(1));
    }
  }
}

// tinyobjloader (Debian's 2.0.0~rc) converts a skin-weight line's joint ids (`vw VERTEX JOINT
// WEIGHT ...`, its extension) to int unchecked (tiny_obj_loader.h:2669): a joint beyond int's
// range is undefined behaviour (the fuzzer's "vw 0 6000000000"). Penumbra reads no skin weights;
// such a line is refused here, before tinyobjloader sees it (a number is the longest numeric
// prefix of its token, which strtod reads the same or larger).
void refuseSkinJoint(size_t lineNumber, std::span<const std::string_view> tokens,
                     const std::string& name) {
  // The vertex, then joint and weight pairs.
  for (size_t i = 1; i < tokens.size(); i += 2) {
    const std::string token(tokens[i]);
    const double joint = std::strtod(token.c_str(), nullptr);
    if (!(joint >= -2147483648.0 && joint < 2147483648.0)) {
      throw Error(name + ": line " + std::to_string(lineNumber) + ": skin weight (vw) joint '" +
                  token + "' is outside int's range [-2147483648, 2147483647]");
    }
  }
}

// The statements whose arguments are all numbers, as tinyobjloader reads them: OBJ's positions
// (with an optional w or colour), texture coordinates and normals; MTL's colours and factors.
bool isObjNumberStatement(std::string_view keyword) {
  return keyword == "v" || keyword == "vt" || keyword == "vn";
}
bool isMtlNumberStatement(std::string_view keyword) {
  for (std::string_view k : {"Ka", "Kd", "Ks", "Kt", "Tf", "Ke", "Ni", "Ns", "d", "Tr", "Pr", "Pm",
                             "Ps", "Pc", "Pcr", "aniso", "anisor"}) {
    if (keyword == k) return true;
  }
  return false;
}

// Doubles from here up (FLT_MAX plus half its last place) round to infinity as float.
constexpr double kFloatOverflow = 0x1.ffffffp+127;

// tinyobjloader reads numbers with a parser of its own that takes no "nan" or "inf" and stores 0
// for a token it cannot read: `v nan 0 0` became a vertex at 0 and `d nan` a material that
// vanished, while 1e39 became infinity (as float) and was refused. So the statements' tokens are
// read here with strtod, which reads "nan", "inf" and "infinity" as what they say, before
// tinyobjloader sees them; a token strtod reads as a non-finite number, or as one beyond float, is
// refused with its line. (A token that is no number at all, "#" starting a comment, stays
// tinyobjloader's to read.)
void refuseNonFiniteNumbers(size_t lineNumber, std::string_view keyword,
                            std::span<const std::string_view> tokens, const std::string& where) {
  for (std::string_view t : tokens) {
    if (t.starts_with('#')) return;
    const std::string token(t);
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || std::abs(value) < kFloatOverflow) continue;
    throw Error(where + ": line " + std::to_string(lineNumber) + ": " + std::string(keyword) +
                " value '" + token + "' is " +
                (std::isfinite(value) ? "beyond single precision (at most 3.4e38 in magnitude)"
                                      : "not a finite number"));
  }
}

// The line of each v, vt and vn statement, in order: tinyobjloader stores one element per
// statement, so a value it reads as non-finite is named by its line.
struct ObjNumberLines {
  std::vector<size_t> v, vt, vn;
};

// tinyobjloader triangulates a polygon of more than four corners by ear clipping, quadratic in
// its corners: one face of 20,000 corners (0.57 MB) took 1.1 s, 60,000 took 16 s, a million would
// take hours. Real polygons (caps, outlines) have at most a few hundred corners; at this many,
// ear clipping takes about 50 ms.
constexpr size_t kMaxFaceCorners = 4096;

void refuseHugePolygon(size_t lineNumber, std::span<const std::string_view> tokens,
                       const std::string& name) {
  size_t corners = 0;
  for (std::string_view t : tokens) {
    if (t.starts_with('#')) break;
    ++corners;
  }
  if (corners > kMaxFaceCorners) {
    throw Error(name + ": line " + std::to_string(lineNumber) + ": a face of " +
                std::to_string(corners) + " corners; penumbra takes polygons of at most " +
                std::to_string(kMaxFaceCorners) + " (triangulating it would take quadratic time)");
  }
}

// What is refused before tinyobjloader parses the OBJ text (above).
ObjNumberLines checkObjStatements(const std::string& objText, const std::string& name) {
  ObjNumberLines lines;
  forEachStatement(objText, [&](size_t lineNumber, std::string_view keyword,
                                std::span<const std::string_view> tokens) {
    if (keyword == "vw") refuseSkinJoint(lineNumber, tokens, name);
    if (keyword == "f") refuseHugePolygon(lineNumber, tokens, name);
    if (!isObjNumberStatement(keyword)) return;
    refuseNonFiniteNumbers(lineNumber, keyword, tokens, name);
    // tinyobjloader takes a statement only where a space or tab follows its keyword (a bare "v"
    // is no vertex, "v " one at 0); std::string's text ends in a NUL, so the read is in bounds.
    const char after = keyword.data()[keyword.size()];
    if (after != ' ' && after != '\t') return;
    (keyword == "v" ? lines.v : keyword == "vt" ? lines.vt : lines.vn).push_back(lineNumber);
  });
  return lines;
}

// tinyobjloader's own arithmetic can still make a non-finite value of a number strtod reads as
// finite ("0e500": 0 × 5^500, an infinity, is NaN): what it stored is checked too.
void refuseNonFiniteValues(const std::vector<tinyobj::real_t>& values, size_t perStatement,
                           const std::vector<size_t>& lines, const char* keyword,
                           const std::string& name) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i])) continue;
    const size_t statement = i / perStatement;
    throw Error(name + ": " +
                (statement < lines.size() ? "line " + std::to_string(lines[statement])
                                          : "statement " + std::to_string(statement + 1)) +
                ": " + keyword + " value " + std::to_string(i % perStatement + 1) +
                " is not finite as tinyobjloader reads it (" +
                (std::isnan(values[i]) ? "nan" : std::to_string(values[i])) + ")");
  }
}

// Material libraries through the caller's file reader (tinyobjloader's own reads the disk). A
// refusal (not a regular file, over the budget) is kept and thrown once tinyobjloader returns:
// nothing is thrown through its code.
class LibraryReader : public tinyobj::MaterialReader {
 public:
  LibraryReader(const ObjFileReader& read, const std::string& objName)
      : read_(read), objName_(objName) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warn, std::string*) override {
    std::optional<std::vector<uint8_t>> bytes;
    try {
      bytes = read_(name, "material library '" + name + "'");
    } catch (const Error& e) {
      if (refusal.empty()) refusal = e.what();
      return false;
    }
    if (!bytes) {
      if (warn) *warn += "material library '" + name + "' cannot be read\n";
      return false;
    }
    const std::string text(bytes->begin(), bytes->end());
    const std::string where = objName_ + ": material library '" + name + "'";
    const size_t first = materials->size();
    try {
      forEachStatement(text, [&](size_t lineNumber, std::string_view keyword,
                                 std::span<const std::string_view> tokens) {
        if (isMtlNumberStatement(keyword))
          refuseNonFiniteNumbers(lineNumber, keyword, tokens, where);
      });
    } catch (const Error& e) {
      if (refusal.empty()) refusal = e.what();
      return false;
    }
    std::istringstream in(text);
    tinyobj::LoadMtl(names, materials, &in, warn, nullptr);
    // What penumbra reads of a material, as tinyobjloader's arithmetic made it (see
    // refuseNonFiniteValues).
    for (size_t m = first; m < materials->size() && refusal.empty(); ++m) {
      const tinyobj::material_t& material = (*materials)[m];
      const auto refuse = [&](const char* what, double value) {
        if (!refusal.empty()) return;
        refusal = where + ": material '" + material.name + "': " + what +
                  " is not finite as tinyobjloader reads it (" +
                  (std::isnan(value) ? "nan" : std::to_string(value)) + ")";
      };
      for (double c : material.diffuse) {
        if (!std::isfinite(c)) refuse("Kd", c);
      }
      if (!std::isfinite(material.dissolve)) refuse("d (or Tr)", material.dissolve);
    }
    return refusal.empty();
  }

  std::string refusal;

 private:
  const ObjFileReader& read_;
  const std::string& objName_;
};

// map_Kd's colour with map_d's luminance as alpha (the .mtl convention for cut-outs), map_d
// sampled at map_Kd's texel centres where their sizes differ; white where there is no colour.
TextureImage withAlphaMask(const TextureImage* colour, const TextureImage& alpha,
                           const std::string& name) {
  TextureImage out = colour ? *colour : alpha;
  if (!colour) {
    for (size_t i = 0; i < out.rgba.size(); i += 4)
      out.rgba[i] = out.rgba[i + 1] = out.rgba[i + 2] = 255;
  }
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const int ax =
          std::min(alpha.width - 1, int((float(x) + 0.5f) * float(alpha.width) / float(out.width)));
      const int ay = std::min(alpha.height - 1,
                              int((float(y) + 0.5f) * float(alpha.height) / float(out.height)));
      const uint8_t* a = &alpha.rgba[(size_t(ay) * size_t(alpha.width) + size_t(ax)) * 4];
      // Rec. 709 luma of the (sRGB-encoded) mask: masks are black and white in practice.
      const float luma = 0.2126f * float(a[0]) + 0.7152f * float(a[1]) + 0.0722f * float(a[2]);
      out.rgba[(size_t(y) * size_t(out.width) + size_t(x)) * 4 + 3] = uint8_t(std::lround(luma));
    }
  }
  out.name = name;
  return out;
}

// The textures of the materials the faces use. Each file is read once and decoded once however
// many materials name it, and each (map_Kd, map_d) pair becomes one scene texture shared by its
// materials. Every file is read, and what decoding will take is budgeted from the images'
// headers, before any is decoded.
class ObjTextures {
 public:
  ObjTextures(const ObjFileReader& read, const std::string& source,
              std::vector<std::string>& warnings)
      : read_(read), source_(source), warnings_(warnings) {}

  // A material faces use (before budget()).
  void use(const tinyobj::material_t& m) {
    if (m.diffuse_texname.empty() && m.alpha_texname.empty()) return;
    const Pair pair{m.diffuse_texname, m.alpha_texname};
    if (!textureOfPair_.try_emplace(pair, kNotBuilt).second) return;
    for (const std::string& file : {pair.first, pair.second}) {
      if (!file.empty()) ++usesLeft_[file];
    }
  }

  // Reads every file the used materials name and adds what decoding them will take.
  void budget(MemoryBudget& budget) {
    for (const auto& [file, uses] : usesLeft_) {
      std::optional<std::vector<uint8_t>>& bytes = encoded_[file];
      bytes = read_(file, "texture '" + file + "'");
      if (bytes) {
        if (const std::optional<ImageSize> size = readImageSize(*bytes)) {
          sizes_[file] = *size;
          budget.addTexture(size->rgbaBytes());
        }
      }
    }
    for (const auto& [pair, texture] : textureOfPair_) {
      const auto colour = sizes_.find(pair.first);
      const auto alpha = sizes_.find(pair.second);
      if (!pair.second.empty()) {  // a new image, the colour's size (or the mask's)
        if (colour != sizes_.end()) {
          budget.addTexture(colour->second.rgbaBytes());
        } else if (alpha != sizes_.end()) {
          budget.addTexture(alpha->second.rgbaBytes());
        }
      } else if (colour != sizes_.end() && usesLeft_[pair.first] > 1) {
        budget.addTexture(colour->second.rgbaBytes());  // a copy: other pairs use the image too
      }
    }
  }

  // The scene texture of a used material, made on first use; -1 where it has none usable.
  int textureOf(const tinyobj::material_t& m, std::vector<TextureImage>& textures) {
    if (m.diffuse_texname.empty() && m.alpha_texname.empty()) return -1;
    int& texture = textureOfPair_.at({m.diffuse_texname, m.alpha_texname});
    if (texture != kNotBuilt) return texture;
    const TextureImage* colour = m.diffuse_texname.empty() ? nullptr : decoded(m.diffuse_texname);
    const TextureImage* alpha = m.alpha_texname.empty() ? nullptr : decoded(m.alpha_texname);
    texture = -1;
    if (alpha) {
      texture = int(textures.size());
      textures.push_back(withAlphaMask(colour, *alpha, m.alpha_texname));
    } else if (colour) {
      texture = int(textures.size());
      // The last pair to use an image takes it; earlier ones copy it.
      textures.push_back(
          usesLeft_.at(m.diffuse_texname) == 1 ? std::move(*decoded_[m.diffuse_texname]) : *colour);
    }
    release(m.diffuse_texname);
    release(m.alpha_texname);
    return texture;
  }

 private:
  using Pair = std::pair<std::string, std::string>;  // map_Kd, map_d ("" where none)
  static constexpr int kNotBuilt = -2;

  // The file's image, decoded on first use (a warning, once, where it cannot be).
  const TextureImage* decoded(const std::string& file) {
    auto [it, first] = decoded_.try_emplace(file);
    if (first) {
      std::string why = "it cannot be read";
      if (const std::optional<std::vector<uint8_t>>& bytes = encoded_[file]) {
        it->second = decodeImage(*bytes, file, why);
      }
      encoded_.erase(file);
      if (!it->second)
        warnings_.push_back(source_ + ": texture '" + file + "' cannot be used: " + why);
    }
    return it->second ? &*it->second : nullptr;
  }

  // One pair fewer needs the file's image: the last frees it.
  void release(const std::string& file) {
    if (file.empty()) return;
    if (--usesLeft_.at(file) == 0) decoded_.erase(file);
  }

  const ObjFileReader& read_;
  const std::string& source_;
  std::vector<std::string>& warnings_;
  std::map<Pair, int> textureOfPair_;    // scene texture, -1 (none usable) or kNotBuilt
  std::map<std::string, int> usesLeft_;  // pairs that still need the file's image
  std::map<std::string, std::optional<std::vector<uint8_t>>> encoded_;
  std::map<std::string, ImageSize> sizes_;
  std::map<std::string, std::optional<TextureImage>> decoded_;
};

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

// A face's material as the meshes are grouped: -1 for none or one the file does not define.
int faceMaterial(const tinyobj::shape_t& shape, size_t face, size_t materials) {
  const int material = face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1;
  return material >= 0 && size_t(material) < materials ? material : -1;
}

// The triangles, vertices and meshes loadObj will make, at most: three vertices per triangle (a
// face without normals has its own three; shared corners only make fewer), a mesh per material.
// Adds them and the used materials' textures to the budget and checks it.
void budgetObj(const std::vector<tinyobj::shape_t>& shapes,
               const std::vector<tinyobj::material_t>& materials, ObjTextures& textures,
               MemoryBudget& budget, const std::string& name) {
  uint64_t triangles = 0;
  std::set<int> used;
  for (const tinyobj::shape_t& shape : shapes) {
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      if (shape.mesh.num_face_vertices[f] != 3) continue;
      ++triangles;
      used.insert(faceMaterial(shape, f, materials.size()));
    }
  }
  budget.addGeometry(
      triangles, used.size() * sizeof(Mesh) + 3 * triangles * (sizeof(Vertex) + sizeof(uint32_t)));
  for (int material : used) {
    if (material >= 0) textures.use(materials[size_t(material)]);
  }
  textures.budget(budget);
  budget.check(name);
}

}  // namespace

Scene loadObj(const std::string& objText, const std::string& name, const ObjFileReader& readFile,
              MemoryBudget& budget) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const ObjNumberLines numberLines = checkObjStatements(objText, name);
  std::istringstream in(objText);
  LibraryReader libraries(readFile, name);
  const bool parsed =
      tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &libraries, true, false);
  if (!libraries.refusal.empty()) throw Error(libraries.refusal);
  if (!parsed) {
    throw Error(name +
                ": not a valid OBJ file: " + (err.empty() ? "tinyobjloader gave no reason" : err));
  }
  refuseNonFiniteValues(attrib.vertices, 3, numberLines.v, "v", name);
  refuseNonFiniteValues(attrib.texcoords, 2, numberLines.vt, "vt", name);
  refuseNonFiniteValues(attrib.normals, 3, numberLines.vn, "vn", name);
  Scene scene;
  std::istringstream warnings(warn);
  for (std::string line; std::getline(warnings, line);) {
    if (!line.empty()) scene.warnings.push_back(name + ": " + line);
  }

  ObjTextures textures(readFile, name, scene.warnings);
  budgetObj(shapes, materials, textures, budget, name);

  // One mesh per material (-1: none).
  std::map<int, size_t> meshOfMaterial;
  std::vector<std::unordered_map<VertexKey, uint32_t, VertexKeyHash>> vertexMaps;
  const auto meshFor = [&](int material) -> size_t {
    if (auto found = meshOfMaterial.find(material); found != meshOfMaterial.end())
      return found->second;
    Mesh mesh;
    if (material >= 0) {
      const tinyobj::material_t& m = materials[size_t(material)];
      // Finite: LibraryReader refuses a material otherwise.
      mesh.albedo = glm::clamp(
          glm::vec3(float(m.diffuse[0]), float(m.diffuse[1]), float(m.diffuse[2])), 0.0f, 1.0f);
      mesh.opacity = std::clamp(float(m.dissolve), 0.0f, 1.0f);
      mesh.baseColorTexture = textures.textureOf(m, scene.textures);
      if (!m.alpha_texname.empty()) {
        mesh.alphaMode = AlphaMode::Mask;
      } else if (mesh.opacity < 1.0f) {
        mesh.alphaMode = AlphaMode::Blend;
        scene.warnings.push_back(name + ": material '" + m.name + "' is partly transparent (d " +
                                 std::to_string(mesh.opacity) + "): " + kTranslucentMaterialRule);
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
      const int material = faceMaterial(shape, f, materials.size());
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

Scene loadObjFile(const fs::path& path, MemoryBudget& budget) {
  const std::string source = path.string();
  const std::optional<std::vector<uint8_t>> text =
      readSceneFile(path, "the scene file", source, budget);
  if (!text) throw Error("cannot open scene file " + source);
  const fs::path folder = path.parent_path();
  const ObjFileReader read = [&](const std::string& name, const std::string& what) {
    // Files written on Windows name textures with backslashes (".\\bark.jpg").
    std::string portable = name;
    std::replace(portable.begin(), portable.end(), '\\', '/');
    return readSceneFile(folder / portable, what, source, budget);
  };
  return loadObj(std::string(text->begin(), text->end()), source, read, budget);
}

}  // namespace penumbra::scene
