#include "scene_inputs.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <vector>

namespace voxr::test {

namespace {

const float kFloor[4][3] = {{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}};
const uint32_t kFloorIndices[6] = {0, 2, 1, 0, 3, 2};
const float kBox[8][3] = {{-0.5f, 0, -0.5f}, {0.5f, 0, -0.5f}, {0.5f, 1, -0.5f}, {-0.5f, 1, -0.5f},
                          {-0.5f, 0, 0.5f},  {0.5f, 0, 0.5f},  {0.5f, 1, 0.5f},  {-0.5f, 1, 0.5f}};
const uint32_t kBoxIndices[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                  0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5, 3, 7, 6, 3, 6, 2};

template <typename T, size_t N>
void append(std::string& bytes, const T (&data)[N]) {
  bytes.append(reinterpret_cast<const char*>(data), sizeof data);
}

}  // namespace

std::filesystem::path write_floor_and_box_gltf(const std::filesystem::path& dir, const std::string& name) {
  std::string bin;
  append(bin, kFloor);         // 48 bytes at 0
  append(bin, kFloorIndices);  // 24 at 48
  append(bin, kBox);           // 96 at 72
  append(bin, kBoxIndices);    // 144 at 168
  const std::string bin_name = name + ".bin";
  std::ofstream(dir / bin_name, std::ios::binary) << bin;
  const std::filesystem::path path = dir / name;
  std::ofstream(path, std::ios::binary) << fmt::format(R"({{
  "asset": {{"version": "2.0"}},
  "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "materials": [{{"name": "matA"}}, {{"name": "matB"}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1, "material": 0}},
                              {{"attributes": {{"POSITION": 2}}, "indices": 3, "material": 1}}]}}],
  "buffers": [{{"byteLength": {}, "uri": "{}"}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
                  {{"buffer": 0, "byteOffset": 48, "byteLength": 24}},
                  {{"buffer": 0, "byteOffset": 72, "byteLength": 96}},
                  {{"buffer": 0, "byteOffset": 168, "byteLength": 144}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                  "min": [-3, 0, -3], "max": [3, 0, 3]}},
                {{"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}},
                {{"bufferView": 2, "componentType": 5126, "count": 8, "type": "VEC3",
                  "min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5]}},
                {{"bufferView": 3, "componentType": 5125, "count": 36, "type": "SCALAR"}}]
}}
)",
                                                       bin.size(), bin_name);
  return path;
}

std::string floor_and_box_obj(const glm::dvec3& shift) {
  std::string s;
  for (const auto& p : kFloor)
    s += fmt::format("v {} {} {}\n", p[0] + shift.x, p[1] + shift.y, p[2] + shift.z);
  for (const auto& p : kBox) s += fmt::format("v {} {} {}\n", p[0] + shift.x, p[1] + shift.y, p[2] + shift.z);
  for (int t = 0; t < 2; ++t)
    s += fmt::format("f {} {} {}\n", kFloorIndices[3 * t] + 1, kFloorIndices[3 * t + 1] + 1,
                     kFloorIndices[3 * t + 2] + 1);
  s += "usemtl box\n";
  for (int t = 0; t < 12; ++t)
    s += fmt::format("f {} {} {}\n", kBoxIndices[3 * t] + 5, kBoxIndices[3 * t + 1] + 5,
                     kBoxIndices[3 * t + 2] + 5);
  return s;
}

std::string floor_and_box_scene(const std::string& mesh_file) {
  const std::string meshes =
      mesh_file.empty() ? R"([{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"},
               {"generator": "box", "params": {"lo": [-0.5, 0, -0.5], "hi": [0.5, 1, 0.5]}, "material": "red"}])"
                        : fmt::format(R"([{{"file": "{}", "material": ["floor", "red"]}}])", mesh_file);
  return fmt::format(R"({{
  "materials": [{{"name": "floor", "kind": "opaque", "color": [0.7, 0.7, 0.65]}},
                {{"name": "red", "kind": "opaque", "color": [0.8, 0.2, 0.2]}}],
  "meshes": {},
  "light": {{"type": "directional", "direction": [-0.2, -1, -0.1]}},
  "camera": {{"position": [0, 3, 3.5], "look_at": [0, 0.3, 0], "fov_deg": 45, "width": 80, "height": 60}},
  "environment": {{"color": [0.2, 0.2, 0.2]}}
}})",
                     meshes);
}

std::string far_scene_json(const glm::dvec3& shift, bool directional_light) {
  return fmt::format(R"({{
  "materials": [{{"name": "floor", "kind": "opaque", "color": [0.8, 0.8, 0.8]}},
                {{"name": "red", "kind": "opaque", "color": [0.8, 0.2, 0.2]}}],
  "meshes": [{{"generator": "plane", "params": {{"size": [6, 6]}}, "material": "floor",
               "transform": {{"translate": [{}, {}, {}]}}}},
             {{"generator": "sphere", "params": {{"radius": 0.5}}, "material": "red",
               "transform": {{"translate": [{}, {}, {}]}}}}],
  {}"environment": {{"color": [0.3, 0.3, 0.3]}}
}})",
                     shift.x, shift.y, shift.z, shift.x, shift.y + 0.6, shift.z,
                     directional_light ? R"("light": {"type": "directional", "direction": [-0.3, -1, -0.2]},
  )"
                                       : "");
}

}  // namespace voxr::test
