#include "mesh/assimp_reader.h"

#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "mesh/corner_welder.h"
#include "mesh/file_bytes.h"
#include "mesh/texture_reader.h"
#include "util/error.h"
#include "util/file_extension.h"
#include "util/text_scan.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

// Assimp's messages may span lines (validation lists every problem); a voxr error is one line.
std::string one_line(std::string text) {
  std::string out;
  bool space = false;
  for (char c : text) {
    if (c == '\n' || c == '\r' || c == '\t' || c == ' ') {
      space = !out.empty();
      continue;
    }
    if (space) out += ' ';
    space = false;
    out += c;
  }
  return out.empty() ? std::string("Assimp gave no reason") : out;
}

// aiMatrix4x4 is row-major with the translation in column 4; glm is column-major (m[column][row]).
glm::dmat4 to_dmat4(const aiMatrix4x4& m) {
  glm::dmat4 d;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) d[col][row] = double(m[row][col]);
  return d;
}

struct Skipped {
  size_t points = 0;
  size_t lines = 0;
};

// Appends one instance of `mesh` under the world transform `world`. Like voxr's own readers, it refuses
// positions that are not finite or beyond text::kMaxCoordinate (the triangulation and the soup need them
// finite).
// With `colours`, each corner also carries its COLOR_0 (white without) and, with `uvs`, its TEXCOORD_0
// ((0, 0) without); both must be finite and colours in [0, 1].
void append_instance(const std::string& name, const aiMesh& mesh, const glm::dmat4& world, PolygonMesh& out,
                     CornerWelder& welder, Skipped& skipped, bool colours, bool uvs) {
  bool any_face = false;
  for (unsigned f = 0; f < mesh.mNumFaces && !any_face; ++f) any_face = mesh.mFaces[f].mNumIndices >= 3;
  if (!any_face) {  // a points- or lines-only mesh adds no vertices
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      skipped.points += mesh.mFaces[f].mNumIndices == 1;
      skipped.lines += mesh.mFaces[f].mNumIndices == 2;
    }
    return;
  }
  std::vector<uint32_t> id(mesh.mNumVertices);
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D& p = mesh.mVertices[v];
    const glm::dvec3 w(world * glm::dvec4(double(p.x), double(p.y), double(p.z), 1.0));
    if (!(std::abs(w.x) <= text::kMaxCoordinate && std::abs(w.y) <= text::kMaxCoordinate &&
          std::abs(w.z) <= text::kMaxCoordinate))
      fail("{}: mesh '{}' vertex {} is not finite or too large ({}, {}, {}) after its node transforms", name,
           text::printable(mesh.mName.C_Str()), v, w.x, w.y, w.z);
    uint32_t rgba = kWhiteRgba;
    glm::vec2 uv(0.0f);
    if (colours && mesh.HasVertexColors(0)) {
      const aiColor4D& c = mesh.mColors[0][v];
      const float k[4] = {c.r, c.g, c.b, c.a};
      uint32_t b[4];
      for (int i = 0; i < 4; ++i) {
        if (!(k[i] >= 0.0f && k[i] <= 1.0f))
          fail("{}: mesh '{}' vertex {} colour ({}, {}, {}, {}) is not in [0, 1]", name,
               text::printable(mesh.mName.C_Str()), v, c.r, c.g, c.b, c.a);
        b[i] = unit_to_byte(k[i]);
      }
      rgba = pack_rgba(b[0], b[1], b[2], b[3]);
    }
    if (uvs && mesh.HasTextureCoords(0)) {
      const aiVector3D& t = mesh.mTextureCoords[0][v];
      if (!std::isfinite(t.x) || !std::isfinite(t.y))
        fail("{}: mesh '{}' vertex {} texture coordinate ({}, {}) is not finite", name,
             text::printable(mesh.mName.C_Str()), v, t.x, t.y);
      uv = glm::vec2(t.x, t.y);
    }
    id[v] = welder.add(w, rgba, uv);
  }
  const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
  std::vector<uint32_t> corners;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices == 1) ++skipped.points;
    if (face.mNumIndices == 2) ++skipped.lines;
    if (face.mNumIndices < 3) continue;
    corners.resize(face.mNumIndices);
    for (unsigned c = 0; c < face.mNumIndices; ++c) corners[c] = id[face.mIndices[c]];
    if (mirrored) std::reverse(corners.begin(), corners.end());
    out.add_face(corners.data(), uint32_t(corners.size()));
    out.materials.push_back(mesh.mMaterialIndex);
  }
}

// The base-colour texture `path` of a material: embedded ("*0", or a name the file embeds) or a file
// relative to the mesh. Raw embedded texels (aiTexel, BGRA) are taken as they are.
SoupTexture material_texture(const std::string& name, const aiScene& scene, const std::string& path) {
  if (const aiTexture* t = scene.GetEmbeddedTexture(path.c_str())) {
    const std::string source = fmt::format("{} (embedded texture '{}')", name, text::printable(path));
    if (t->pcData == nullptr) fail("{}: no data", source);
    if (t->mHeight == 0)  // compressed: mWidth bytes of an image file
      return decode_texture(source, std::string_view(reinterpret_cast<const char*>(t->pcData), t->mWidth));
    if (uint64_t(t->mWidth) * t->mHeight > kMaxTextureTexels)
      fail("{}: {}x{} texels are more than voxr reads", source, t->mWidth, t->mHeight);
    SoupTexture out;
    out.width = t->mWidth;
    out.height = t->mHeight;
    out.source = source;
    out.texels.resize(size_t(t->mWidth) * t->mHeight);
    for (size_t i = 0; i < out.texels.size(); ++i)
      out.texels[i] = pack_rgba(t->pcData[i].r, t->pcData[i].g, t->pcData[i].b, t->pcData[i].a);
    return out;
  }
  std::string relative = path;
  std::replace(relative.begin(), relative.end(), '\\', '/');
  const fs::path folder = fs::path(name).parent_path();
  fs::path file = folder / relative;
  // FBX and Collada files often keep the absolute path of the machine that wrote them: the file name
  // beside the mesh is tried next.
  std::error_code ec;
  if (!fs::is_regular_file(file, ec) && fs::is_regular_file(folder / fs::path(relative).filename(), ec))
    file = folder / fs::path(relative).filename();
  return read_texture(file, name);
}

// Each material's look: the base colour factor (AI_MATKEY_BASE_COLOR, else COLOR_DIFFUSE with OPACITY as
// alpha) and base-colour texture (aiTextureType_BASE_COLOR, else DIFFUSE), textures read once per path.
void read_looks(const std::string& name, const aiScene& scene, PolygonMesh& out) {
  std::vector<std::string> paths;
  for (unsigned m = 0; m < scene.mNumMaterials; ++m) {
    const aiMaterial& material = *scene.mMaterials[m];
    SurfaceLook look;
    aiColor4D c(1.0f, 1.0f, 1.0f, 1.0f);
    if (material.Get(AI_MATKEY_BASE_COLOR, c) != AI_SUCCESS &&
        material.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
      float opacity = 1.0f;
      if (material.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS) c.a = opacity;
    }
    const float k[4] = {c.r, c.g, c.b, c.a};
    uint32_t b[4];
    for (int i = 0; i < 4; ++i) {
      if (!(k[i] >= 0.0f && k[i] <= 1.0f))
        fail("{}: material '{}' base colour ({}, {}, {}, {}) is not in [0, 1]", name,
             text::printable(material.GetName().C_Str()), c.r, c.g, c.b, c.a);
      b[i] = unit_to_byte(k[i]);
    }
    look.factor_rgba = pack_rgba(b[0], b[1], b[2], b[3]);
    aiString path;
    if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &path) == AI_SUCCESS ||
        material.GetTexture(aiTextureType_DIFFUSE, 0, &path) == AI_SUCCESS) {
      const std::string p = path.C_Str();
      const auto known = std::find(paths.begin(), paths.end(), p);
      look.texture = int32_t(known - paths.begin());
      if (known == paths.end()) {
        out.textures.push_back(material_texture(name, scene, p));
        paths.push_back(p);
      }
    }
    out.looks.push_back(look);
  }
}

// glTF JSON: an object with an "asset" whose version is 2.x.
bool gltf_json(std::string_view text) {
  const nlohmann::json j = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("asset") || !j["asset"].is_object()) return false;
  const auto version = j["asset"].find("version");
  return version != j["asset"].end() && version->is_string() &&
         version->get<std::string>().rfind("2", 0) == 0;
}

uint32_t le32(std::string_view b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(b[at + i]);
  return v;
}

// Assimp falls back to sniffing every importer when the one for the extension declines a file, and some of
// them hang or allocate gigabytes on garbage (found by fuzzing: a 23-byte .gltf, an 83-byte .glb). So a file
// must look like what its extension says before Assimp sees it: glTF JSON with asset.version 2; a GLB
// header whose length is the file's and whose first chunk is that JSON; FBX's binary magic or an FBX
// text header; a COLLADA document; a 3MF zip.
void check_signature(const std::string& name, const std::string& ext, std::string_view b) {
  std::string_view text = b.substr(b.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0);
  while (!text.empty() && (text::is_space(text[0]) || text[0] == '\n')) text.remove_prefix(1);
  auto refuse = [&](const char* what) { fail("{}: not {}", name, what); };
  if (ext == ".gltf") {
    if (!gltf_json(text)) refuse("glTF 2.0 JSON (an object with asset.version \"2.x\")");
  } else if (ext == ".glb") {
    if (b.size() < 20 || b.substr(0, 4) != "glTF" || le32(b, 4) != 2)
      refuse("binary glTF 2.0 (no 'glTF' version 2 header)");
    if (le32(b, 8) != b.size())
      fail("{}: the binary glTF header gives a length of {} bytes but the file has {}", name, le32(b, 8),
           b.size());
    const uint32_t json_length = le32(b, 12);
    if (b.substr(16, 4) != "JSON" || json_length > b.size() - 20 || !gltf_json(b.substr(20, json_length)))
      refuse("binary glTF 2.0 (its first chunk is not glTF JSON)");
  } else if (ext == ".fbx") {
    if (b.rfind("Kaydara FBX Binary", 0) != 0 && text.substr(0, 4096).find("FBX") == std::string_view::npos)
      refuse("FBX (neither the binary magic nor an FBX text header)");
  } else if (ext == ".dae") {
    if (text.empty() || text[0] != '<' || text.substr(0, 4096).find("<COLLADA") == std::string_view::npos)
      refuse("COLLADA (no <COLLADA> element)");
  } else if (ext == ".3mf") {
    if (b.substr(0, 4) != std::string_view("PK\x03\x04", 4)) refuse("3MF (not a zip archive)");
  }
}

}  // namespace

bool is_assimp_extension(const fs::path& file) {
  const std::string ext = lower_extension(file);
  return std::any_of(std::begin(kAssimpExtensions), std::end(kAssimpExtensions),
                     [&](const char* known) { return ext == known; });
}

PolygonMesh read_with_assimp(const fs::path& file) {
  const std::string name = file.string();
  if (!is_assimp_extension(file))
    fail("{}: unknown mesh extension '{}' (Assimp reads .gltf, .glb, .fbx, .dae, .3mf)", name,
         file.extension().string());
  std::error_code ec;
  if (!fs::exists(file, ec)) fail("{}: no such file", name);
  if (!fs::is_regular_file(file, ec)) fail("{}: not a regular file", name);
  if (fs::file_size(file, ec) == 0) fail("{}: empty file", name);
  check_signature(name, lower_extension(file), FileBytes(file).view());

  // One importer per call: Assimp::Importer is not shared between threads. No DefaultLogger is created,
  // so Assimp logs to its NullLogger and prints nothing.
  Assimp::Importer importer;
  // A file with bones and no meshes must not turn into a mesh of its skeleton.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  // Corners are merged by position here (CornerWelder), in double after the node transforms: per-face
  // normals or UVs do not open a closed mesh, and Assimp's JoinIdenticalVertices (80-90 % of a large
  // read) is not needed.
  const unsigned flags = aiProcess_ValidateDataStructure;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(name, flags);
  } catch (const std::exception& e) {
    fail("{}: cannot read: {}", name, one_line(e.what()));
  }
  if (scene == nullptr) fail("{}: cannot read: {}", name, one_line(importer.GetErrorString()));

  PolygonMesh out;
  size_t vertices = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) vertices += scene->mMeshes[m]->mNumVertices;
  // Surface colour: looks from the materials; corners carry COLOR_0 when a mesh has it, TEXCOORD_0 when a
  // material has a texture. A file whose materials are all plain white and that has no vertex colours has
  // no colour at all.
  read_looks(name, *scene, out);
  const bool textured = !out.textures.empty();
  bool colours = false;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) colours |= scene->mMeshes[m]->HasVertexColors(0);
  const bool plain = !colours && !textured &&
                     std::all_of(out.looks.begin(), out.looks.end(),
                                 [](const SurfaceLook& l) { return l.factor_rgba == kWhiteRgba; });
  if (plain) out.looks.clear();
  CornerWelder welder(out, vertices, colours || textured);
  Skipped skipped;
  if (scene->mRootNode != nullptr) {
    std::vector<std::pair<const aiNode*, glm::dmat4>> stack{{scene->mRootNode, glm::dmat4(1.0)}};
    while (!stack.empty()) {
      const auto [node, parent] = stack.back();
      stack.pop_back();
      const glm::dmat4 world = parent * to_dmat4(node->mTransformation);
      for (unsigned i = 0; i < node->mNumMeshes; ++i)
        append_instance(name, *scene->mMeshes[node->mMeshes[i]], world, out, welder, skipped,
                        colours || textured, textured);
      // Children pushed in reverse so instances come out in the file's order.
      for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], world);
    }
  }
  if (out.face_count() == 0)
    fail("{}: no polygon faces ({} meshes; skipped {} points and {} lines)", name, scene->mNumMeshes,
         skipped.points, skipped.lines);
  if (!textured) out.vertex_uv.clear();
  if (!colours) out.vertex_rgba.clear();
  // Only the looks that faces use, in order of first use (Assimp adds a default material that a file's
  // faces may not use); one look for every face needs no per-face list.
  if (!out.looks.empty()) {
    std::vector<int32_t> look_of(out.looks.size(), -1);
    std::vector<SurfaceLook> used;
    out.face_looks.resize(out.materials.size());
    for (size_t f = 0; f < out.materials.size(); ++f) {
      int32_t& look = look_of[out.materials[f]];
      if (look < 0) {
        look = int32_t(used.size());
        used.push_back(out.looks[out.materials[f]]);
      }
      out.face_looks[f] = uint32_t(look);
    }
    out.looks = std::move(used);
    if (out.looks.size() <= 1) out.face_looks.clear();
    if (!colours && !textured && out.looks.size() == 1 && out.looks[0].factor_rgba == kWhiteRgba)
      out.looks.clear();
  }
  // Every face on material 0 says no more than no materials at all (PolygonMesh: empty when the file has
  // none).
  if (std::all_of(out.materials.begin(), out.materials.end(), [](uint32_t m) { return m == 0; }))
    out.materials.clear();
  return out;
}

}  // namespace voxr
