#include "core/scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "core/subdivide.h"
#include "util/error.h"

namespace voxr {

using nlohmann::json;

// ---------------------------------------------------------------------------------------------------------
// Scene parsing

glm::mat4 make_transform(glm::vec3 scale, glm::vec3 rotate_deg, glm::vec3 translate) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
  // Column vectors: the rightmost factor acts first, so this is T * Rz * Ry * Rx * S.
  m = glm::rotate(m, glm::radians(rotate_deg.z), glm::vec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate_deg.y), glm::vec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate_deg.x), glm::vec3(1, 0, 0));
  return glm::scale(m, scale);
}

namespace {

bool box_empty(const WorldBox& b) {
  return !(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z);
}

// Centre and radius of the bounding sphere of `bounds` (the unit sphere at the origin when it is empty or a
// point), in double.
std::pair<glm::dvec3, double> framing_sphere(const WorldBox& bounds) {
  if (box_empty(bounds)) return {glm::dvec3(0.0), 1.0};
  const double radius = 0.5 * glm::length(bounds.hi - bounds.lo);
  return {0.5 * (bounds.lo + bounds.hi), radius > 0.0 ? radius : 1.0};
}

}  // namespace

Camera default_camera(const WorldBox& bounds) {
  Camera camera;
  const auto [center, radius] = framing_sphere(bounds);
  camera.look_at = center;
  // Far enough that the bounding sphere fits the vertical field of view, with a little room.
  const double distance = 1.1 * radius / std::sin(0.5 * glm::radians(double(camera.fov_deg)));
  camera.position = center + distance * glm::normalize(glm::dvec3(0.0, 0.25, 1.0));
  return camera;
}

Light default_light(const WorldBox& bounds) {
  Light light;
  const auto [center, radius] = framing_sphere(bounds);
  light.type = "point";
  const glm::dvec3 d = radius * glm::dvec3(1.0, 3.0, 2.0);
  light.position = center + d;
  light.intensity = glm::vec3(float(glm::dot(d, d)));  // irradiance 1 at the centre
  return light;
}

std::string precision_warning(const WorldBox& bounds, const std::string& label) {
  if (box_empty(bounds)) return "";
  const glm::dvec3 far = glm::max(glm::abs(bounds.lo), glm::abs(bounds.hi));
  const double magnitude = std::max({far.x, far.y, far.z});
  const glm::dvec3 size = bounds.hi - bounds.lo;
  const double extent = std::max({size.x, size.y, size.z});
  const double step = std::nextafter(magnitude, std::numeric_limits<double>::infinity()) - magnitude;
  if (!(extent < 65536.0 * step)) return "";
  return fmt::format(
      "{}: the scene spans {:.3g} units at {:.3g} from the origin, where coordinates are {:.3g} apart: {} "
      "across it, so its positions are quantised; translate it nearer the origin",
      label, extent, magnitude, step, extent < step ? "less than one step" : "fewer than 65536 steps");
}

namespace {

constexpr int kMaxSubdivide = 8;
constexpr int64_t kMaxImageSize = 16384;

std::filesystem::path mesh_dir() {
  const char* env = std::getenv("VOXR_MESH_DIR");
  return env && *env ? std::filesystem::path(env) : std::filesystem::current_path() / "data" / "meshes";
}

// A path is named in messages (and in those of the mesh readers): a control character would break the line.
void refuse_control_characters(const JsonObjectReader& in, std::string_view key, const std::string& path) {
  if (std::any_of(path.begin(), path.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
    in.fail_key(key, fmt::format("must be a path without control characters (got {})", quoted_text(path)));
}

std::filesystem::path resolve_mesh_path(const JsonObjectReader& in, const std::string& text,
                                        const std::filesystem::path& base_dir) {
  namespace fs = std::filesystem;
  static constexpr std::string_view kPrefix = "$VOXR_MESH_DIR/";
  refuse_control_characters(in, "file", text);
  std::error_code ec;
  if (std::string_view(text).substr(0, kPrefix.size()) == kPrefix) {
    const fs::path p = mesh_dir() / text.substr(kPrefix.size());
    if (!fs::exists(p, ec))
      in.fail_key("file", fmt::format("names '{}', which does not exist (VOXR_MESH_DIR={}; run "
                                      "scripts/fetch-meshes.sh to fetch the packaged meshes)",
                                      p.string(), mesh_dir().string()));
    return p;
  }
  const fs::path p(text);
  if (p.is_absolute()) return p;  // load_mesh reports a missing file
  const fs::path local = base_dir / p;
  if (fs::exists(local, ec)) return local;
  const fs::path shared = mesh_dir() / p;
  if (fs::exists(shared, ec)) return shared;
  in.fail_key("file", fmt::format("'{}' not found in {} nor in VOXR_MESH_DIR={} (scripts/fetch-meshes.sh "
                                  "fetches the packaged meshes)",
                                  text, base_dir.empty() ? "." : base_dir.string(), mesh_dir().string()));
}

MaterialKind parse_kind(const JsonObjectReader& in) {
  const std::string kind = in.string("kind");
  if (kind == "opaque") return MaterialKind::kOpaque;
  if (kind == "dielectric") return MaterialKind::kDielectric;
  if (kind == "sheet") return MaterialKind::kSheet;
  in.fail_key("kind", fmt::format("must be opaque, dielectric or sheet (got {})", quoted_text(kind)));
}

glm::vec3 unit_color(const JsonObjectReader& in, std::string_view key, std::optional<glm::vec3> fallback) {
  const glm::vec3 c = in.vec3(key, fallback);
  in.require(
      glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(c, glm::vec3(1.0f))),
      key, "must have every component in [0, 1]");
  return c;
}

glm::vec3 non_negative(const JsonObjectReader& in, std::string_view key, std::optional<glm::vec3> fallback) {
  const glm::vec3 v = in.vec3(key, fallback);
  in.require(glm::all(glm::greaterThanEqual(v, glm::vec3(0.0f))), key, "must have every component >= 0");
  return v;
}

Material parse_material(const json& value, const std::string& where, const std::string& path) {
  const JsonObjectReader in(value, where, path,
                            {"name", "kind", "color", "ior", "absorption", "transmittance"});
  Material m;
  m.name = in.string("name");
  in.require(!m.name.empty(), "name", "must not be empty");
  m.kind = parse_kind(in);
  const std::string why = fmt::format("is not used by kind '{}'", material_kind_name(m.kind));
  switch (m.kind) {
    case MaterialKind::kOpaque:
      m.color = unit_color(in, "color", m.color);
      for (const char* key : {"ior", "absorption", "transmittance"}) in.forbid(key, why);
      break;
    case MaterialKind::kDielectric:
      m.ior = in.number("ior", m.ior);
      in.require(m.ior > 0.0f, "ior", "must be positive");
      m.absorption = non_negative(in, "absorption", m.absorption);
      for (const char* key : {"color", "transmittance"}) in.forbid(key, why);
      break;
    case MaterialKind::kSheet:
      m.color = unit_color(in, "color", m.color);
      m.transmittance = unit_color(in, "transmittance", m.transmittance);
      for (const char* key : {"ior", "absorption"}) in.forbid(key, why);
      break;
  }
  return m;
}

glm::mat4 parse_transform(const json& value, const std::string& where, const std::string& path) {
  const JsonObjectReader in(value, where, path, {"scale", "rotate_deg", "translate"});
  const glm::vec3 scale = in.scale("scale", glm::vec3(1.0f));
  return make_transform(scale, in.vec3("rotate_deg", glm::vec3(0.0f)), in.vec3("translate", glm::vec3(0.0f)));
}

uint32_t find_material(const JsonObjectReader& in, const std::vector<Material>& materials, const json& name,
                       const std::string& path) {
  if (!name.is_string())
    fail_json_value(in.where(), path, fmt::format("must be a material name (got {})", shown(name)));
  const std::string s = name.get<std::string>();
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == s) return uint32_t(i);
  std::vector<std::string> names;
  for (const Material& m : materials) names.push_back(printable_key(m.name));
  const std::vector<std::string_view> known(names.begin(), names.end());
  fail_json_value(in.where(), path,
                  fmt::format("names no material: {} (materials: {})", quoted_text(s), join(known)));
}

MeshInstance parse_mesh(const json& value, const std::string& where, const std::string& path,
                        const std::vector<Material>& materials, const std::filesystem::path& base_dir) {
  const JsonObjectReader in(
      value, where, path, {"file", "generator", "params", "material", "subdivide", "transform", "animation"});
  MeshInstance mesh;
  if (in.has("file") == in.has("generator"))
    fail("{}: '{}' needs exactly one of 'file' and 'generator'", where, path);
  if (in.has("file")) {
    in.forbid("params", "is only used with 'generator'");
    const std::filesystem::path file = resolve_mesh_path(in, in.string("file"), base_dir);
    mesh.source = file.string();
    try {
      mesh.soup = load_mesh(file, &mesh.warnings);
    } catch (const Error& e) {
      in.fail_key("file", fmt::format("could not be loaded: {}", e.what()));
    }
  } else {
    const std::string name = in.string("generator");
    const auto& names = generator_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::vector<std::string_view> known(names.begin(), names.end());
      in.fail_key("generator", fmt::format("must be one of {} (got {})", join(known), quoted_text(name)));
    }
    const json* params = in.get("params");
    mesh.source = "generator:" + name;
    mesh.soup = make_generated(name, params ? *params : json(), where, in.path("params"));
  }
  const int levels = int(in.integer("subdivide", 0, 0, kMaxSubdivide));
  if (levels > 0) {
    try {
      mesh.soup = subdivide_midpoint(mesh.soup, levels);
    } catch (const Error& e) {
      in.fail_key("subdivide", e.what());
    }
  }

  const json* material = in.get("material");
  if (!material) {
    mesh.material = 0;
  } else if (material->is_array()) {
    // One scene material per material id the mesh carries.
    std::vector<uint32_t> map;
    for (size_t k = 0; k < material->size(); ++k)
      map.push_back(
          find_material(in, materials, (*material)[k], fmt::format("{}[{}]", in.path("material"), k)));
    uint32_t used = 0;
    for (const glm::uvec4& t : mesh.soup.triangles) used = std::max(used, t.w);
    in.require(used < map.size(), "material",
               fmt::format("must list a material for each of the material ids 0..{} that {} carries", used,
                           mesh.source));
    if (map.size() > used + 1)
      mesh.warnings.push_back(fmt::format(
          "{}: carries {} material id{} (0..{}) but '{}' in {} lists {} materials; the last {} {} unused",
          mesh.source, used + 1, used == 0 ? "" : "s", used, in.path("material"), where, map.size(),
          map.size() - used - 1, map.size() - used - 1 == 1 ? "is" : "are"));
    for (glm::uvec4& t : mesh.soup.triangles) t.w = map[t.w];
    mesh.material = TriangleSoup::kKeepMaterial;
  } else {
    mesh.material = find_material(in, materials, *material, in.path("material"));
  }

  if (const json* t = in.get("transform")) mesh.transform = parse_transform(*t, where, in.path("transform"));
  if (const json* a = in.get("animation"))
    mesh.animation = parse_mesh_animation(*a, where, in.path("animation"));
  return mesh;
}

Light parse_light(const json& value, const std::string& where) {
  const JsonObjectReader in(value, where, "light", {"type", "position", "direction", "intensity"});
  Light light;
  light.type = in.string("type");
  if (light.type == "point") {
    light.position = in.dvec3("position");
    in.forbid("direction", "is not used by a point light");
  } else if (light.type == "directional") {
    const glm::vec3 d = in.vec3("direction");
    in.require(glm::length(d) > 0.0f, "direction", "must not be zero");
    light.direction = glm::normalize(d);
    in.forbid("position", "is not used by a directional light");
  } else {
    in.fail_key("type", fmt::format("must be point or directional (got {})", quoted_text(light.type)));
  }
  light.intensity = non_negative(in, "intensity", light.intensity);
  return light;
}

Camera parse_camera(const json& value, const std::string& where) {
  const JsonObjectReader in(value, where, "camera",
                            {"position", "look_at", "up", "fov_deg", "width", "height"});
  Camera camera;
  camera.position = in.dvec3("position");
  camera.look_at = in.dvec3("look_at");
  in.require(camera.look_at != camera.position, "look_at", "must differ from 'position'");
  camera.up = in.vec3("up", camera.up);
  const glm::vec3 view(glm::normalize(camera.look_at - camera.position));
  in.require(
      glm::length(camera.up) > 0.0f && glm::length(glm::cross(view, glm::normalize(camera.up))) > 1e-4f, "up",
      "must be non-zero and not parallel to the view direction");
  camera.fov_deg = in.number("fov_deg", camera.fov_deg);
  in.require(camera.fov_deg > 0.0f && camera.fov_deg < 180.0f, "fov_deg", "must be in (0, 180)");
  camera.width = uint32_t(in.integer("width", camera.width, 1, kMaxImageSize));
  camera.height = uint32_t(in.integer("height", camera.height, 1, kMaxImageSize));
  return camera;
}

GridRequest parse_grid(const json& value, const std::string& where) {
  const JsonObjectReader in(value, where, "grid", {"res", "dims", "bounds", "margin_voxels"});
  GridRequest grid;
  if (in.has("res") && in.has("dims")) fail("{}: 'grid' takes 'res' or 'dims', not both", where);
  grid.resolution = uint32_t(in.integer("res", grid.resolution, 1, kMaxGridDim));
  if (const json* d = in.get("dims")) {
    if (!d->is_array() || d->size() != 3)
      in.fail_key("dims", fmt::format("must be an array of 3 integers (got {})", shown(*d)));
    glm::uvec3 dims;
    for (int a = 0; a < 3; ++a) {
      const json& e = (*d)[a];
      if (!e.is_number_integer() || e.get<int64_t>() < 1 || e.get<int64_t>() > int64_t(kMaxGridDim))
        in.fail_key("dims", fmt::format("must hold integers in [1, {}] (got {})", kMaxGridDim, shown(*d)));
      dims[a] = uint32_t(e.get<int64_t>());
    }
    grid.dims = dims;
  }
  if (in.has("bounds")) {
    const std::vector<float> b = in.numbers("bounds");
    in.require(b.size() == 6, "bounds", "must be [x0, y0, z0, x1, y1, z1]");
    Bounds bounds;
    bounds.lo = glm::vec3(b[0], b[1], b[2]);
    bounds.hi = glm::vec3(b[3], b[4], b[5]);
    in.require(glm::all(glm::lessThan(bounds.lo, bounds.hi)), "bounds",
               "must have x0 < x1, y0 < y1 and z0 < z1");
    grid.bounds = bounds;
  }
  grid.margin_voxels = in.number("margin_voxels", grid.margin_voxels);
  in.require(grid.margin_voxels >= 0.0f && grid.margin_voxels <= 1000.0f, "margin_voxels",
             "must be in [0, 1000]");
  return grid;
}

// Parses JSON text, reporting syntax errors with line and column and refusing duplicate keys (which
// nlohmann::json would silently resolve to the last one).
json parse_json(std::string_view text, const std::string& where) {
  struct Frame {
    bool array = false;
    size_t index = 0;
    std::string key;
    std::vector<std::string> keys;
  };
  std::vector<Frame> stack;
  auto where_in = [&]() {
    std::string path;
    for (size_t i = 0; i < stack.size(); ++i) {
      const Frame& f = stack[i];
      if (f.array)
        path += fmt::format("[{}]", f.index);
      else if (i + 1 < stack.size())
        path = join_path(path, f.key);
    }
    return path;
  };
  // The quoted key path of the value being parsed (with the key or index of the innermost container).
  auto value_path = [&]() {
    std::string path;
    for (const Frame& f : stack)
      path = f.array ? path + fmt::format("[{}]", f.index) : join_path(path, f.key);
    return path.empty() ? std::string("the top-level value") : "'" + path + "'";
  };
  auto finish_value = [&]() {
    if (!stack.empty() && stack.back().array) ++stack.back().index;
  };
  const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        stack.push_back({false, 0, {}, {}});
        break;
      case json::parse_event_t::array_start:
        stack.push_back({true, 0, {}, {}});
        break;
      case json::parse_event_t::key: {
        Frame& f = stack.back();
        const std::string key = parsed.get<std::string>();
        if (std::find(f.keys.begin(), f.keys.end(), key) != f.keys.end()) {
          f.key = key;
          fail("{}: duplicate key '{}'", where, join_path(where_in(), key));
        }
        f.keys.push_back(key);
        f.key = key;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack.pop_back();
        finish_value();
        break;
      case json::parse_event_t::value:
        finish_value();
        break;
    }
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), callback, /*allow_exceptions=*/true,
                       /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error while ..."
    std::string reason = e.what();
    if (const size_t bracket = reason.find("] ");
        reason.starts_with("[json.exception") && bracket != std::string::npos)
      reason = reason.substr(bracket + 2);
    fail("{}: JSON {}", where, reason);
  } catch (const json::out_of_range& e) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'": a number beyond a double's range
    // (the parser has no line or column for it, but the callback knows the key path).
    const std::string reason = e.what();
    const size_t quote = reason.find('\'');
    std::string number = quote == std::string::npos ? std::string() : reason.substr(quote);
    if (number.size() > 42) number = number.substr(0, 38) + "...'";
    fail("{}: {} holds the number {}, which is out of range (beyond 1.8e308)", where, value_path(),
         number.empty() ? "given" : number);
  }
}

// The defaults not given, framed in double from the scene's world bounds, and the precision warning.
void apply_defaults(Scene& scene, bool has_light, bool has_camera, bool has_environment) {
  const WorldBox bounds = scene_world_bounds(scene);
  if (std::string w = precision_warning(bounds, scene.source); !w.empty())
    scene.warnings.push_back(std::move(w));
  if (!has_light) scene.light = default_light(bounds);
  if (!has_camera) scene.camera = default_camera(bounds);
  if (!has_environment) scene.environment.color = kDefaultEnvironment;
}

}  // namespace

Scene parse_scene(std::string_view json_text, const std::string& label,
                  const std::filesystem::path& base_dir) {
  const json root_value = parse_json(json_text, label);
  const JsonObjectReader root(root_value, label, "",
                              {"materials", "meshes", "light", "camera", "environment", "grid", "animation"});
  Scene scene;
  scene.source = label;

  if (const json* materials = root.get("materials")) {
    if (!materials->is_array() || materials->empty())
      root.require(false, "materials", "must be a non-empty array of materials");
    for (size_t i = 0; i < materials->size(); ++i) {
      const std::string path = fmt::format("materials[{}]", i);
      Material m = parse_material((*materials)[i], label, path);
      for (const Material& other : scene.materials)
        if (other.name == m.name)
          fail("{}: '{}.name' repeats the material name {}", label, path, quoted_text(m.name));
      scene.materials.push_back(std::move(m));
    }
  } else {
    scene.materials.push_back(Material{"default", MaterialKind::kOpaque});
  }

  const json* meshes = root.get("meshes");
  if (!meshes) fail("{}: missing required key 'meshes'", label);
  if (!meshes->is_array() || meshes->empty())
    root.require(false, "meshes", "must be a non-empty array of meshes");
  for (size_t i = 0; i < meshes->size(); ++i)
    scene.meshes.push_back(
        parse_mesh((*meshes)[i], label, fmt::format("meshes[{}]", i), scene.materials, base_dir));

  if (const json* light = root.get("light")) scene.light = parse_light(*light, label);
  if (const json* camera = root.get("camera")) scene.camera = parse_camera(*camera, label);
  if (const json* env = root.get("environment")) {
    const JsonObjectReader in(*env, label, "environment", {"color", "image", "procedural"});
    if (int(in.has("color")) + int(in.has("image")) + int(in.has("procedural")) != 1)
      fail("{}: 'environment' needs exactly one of 'color', 'image' and 'procedural'", label);
    if (in.has("color")) scene.environment.color = non_negative(in, "color", std::nullopt);
    if (in.has("image")) {
      const std::string image_text = in.string("image");
      refuse_control_characters(in, "image", image_text);
      const std::filesystem::path image(image_text);
      const std::filesystem::path resolved = image.is_absolute() ? image : base_dir / image;
      std::error_code ec;
      if (!std::filesystem::exists(resolved, ec))
        in.fail_key("image", fmt::format("names '{}', which does not exist", resolved.string()));
      scene.environment.image = resolved.string();
    }
    if (in.has("procedural")) {
      scene.environment.procedural = in.string("procedural");
      if (scene.environment.procedural != "checker")
        in.fail_key("procedural",
                    fmt::format("must be \"checker\" (got {})", quoted_text(scene.environment.procedural)));
    }
  }
  if (const json* grid = root.get("grid")) {
    scene.grid = parse_grid(*grid, label);
    scene.grid_given = true;
  }
  if (const json* animation = root.get("animation")) scene.fps = parse_scene_animation(*animation, label);
  apply_defaults(scene, root.has("light"), root.has("camera"), root.has("environment"));
  return scene;
}

Scene load_scene(const std::filesystem::path& json_file) {
  const std::string label = json_file.string();
  std::error_code ec;
  if (!std::filesystem::exists(json_file, ec)) fail("{}: no such file", label);
  if (std::filesystem::is_directory(json_file, ec)) fail("{}: is a directory, not a scene file", label);
  std::ifstream in(json_file, std::ios::binary);
  if (!in) fail("{}: cannot open the file for reading", label);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) fail("{}: reading the file failed", label);
  return parse_scene(text.str(), label, json_file.parent_path());
}

Scene load_input(const std::filesystem::path& input) {
  std::string ext = input.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".json") return load_scene(input);
  std::vector<std::string> warnings;
  TriangleSoup soup = load_mesh(input, &warnings);
  return scene_from_mesh(std::move(soup), input.string(), std::move(warnings));
}

Scene scene_from_mesh(TriangleSoup soup, const std::string& source, std::vector<std::string> warnings) {
  Scene scene;
  scene.source = source;
  // The mesh keeps its own material ids (OBJ usemtl, glTF materials: the voxels' material channel), each an
  // opaque scene material of its own so that every id names one.
  uint32_t largest = 0;
  for (const glm::uvec4& t : soup.triangles) largest = std::max(largest, t.w);
  scene.materials.push_back(Material{"default", MaterialKind::kOpaque});
  for (uint32_t id = 1; id <= largest; ++id)
    scene.materials.push_back(Material{fmt::format("material{}", id), MaterialKind::kOpaque});
  MeshInstance mesh;
  mesh.source = source;
  mesh.material = TriangleSoup::kKeepMaterial;
  mesh.soup = std::move(soup);
  mesh.warnings = std::move(warnings);
  scene.meshes.push_back(std::move(mesh));
  apply_defaults(scene, false, false, false);
  return scene;
}

namespace {

// World bounds of an instance, in double: the transformed corners of its soup's bounds.
void extend_world(const MeshInstance& m, glm::dvec3& lo, glm::dvec3& hi) {
  const Bounds b = m.soup.bounds();
  if (b.empty()) return;
  const glm::dmat4 t(m.transform);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p =
        m.soup.anchor + glm::dvec3(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
    const glm::dvec4 q = t * glm::dvec4(p, 1.0);
    lo = glm::min(lo, glm::dvec3(q) / q.w);
    hi = glm::max(hi, glm::dvec3(q) / q.w);
  }
}

}  // namespace

namespace {

// One mesh placed as it is: its soup is the scene's, anchor and positions bit for bit.
bool single_mesh_as_is(const Scene& scene) {
  return scene.meshes.size() == 1 && scene.meshes[0].transform == glm::mat4(1.0f) && !is_animated(scene);
}

// The meshes' surface colours in scene order, as TriangleSoup::append combines them (pose_scene gives
// geometry only); empty, and nothing copied, when no mesh has colour.
SoupColors scene_colors(const Scene& scene) {
  if (std::all_of(scene.meshes.begin(), scene.meshes.end(),
                  [](const MeshInstance& m) { return m.soup.colors.empty(); }))
    return SoupColors();
  TriangleSoup all;
  for (const MeshInstance& m : scene.meshes) all.append(m.soup);
  return std::move(all.colors);
}

}  // namespace

TriangleSoup take_scene_triangles(Scene& scene) {
  if (!single_mesh_as_is(scene)) return scene_triangles(scene);
  MeshInstance& m = scene.meshes[0];
  TriangleSoup out = std::move(m.soup);
  m.soup = TriangleSoup();
  if (m.material != TriangleSoup::kKeepMaterial)
    for (glm::uvec4& t : out.triangles) t.w = m.material;
  return out;
}

TriangleSoup scene_triangles(const Scene& scene) {
  if (is_animated(scene)) {
    TriangleSoup posed = pose_scene(scene, 0.0, animation_anchor(scene));
    posed.colors = scene_colors(scene);
    return posed;
  }
  TriangleSoup out;
  size_t vertices = 0, triangles = 0;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  const bool as_is = single_mesh_as_is(scene);
  for (const MeshInstance& m : scene.meshes) {
    vertices += m.soup.positions.size();
    triangles += m.soup.triangles.size();
    if (!as_is) extend_world(m, lo, hi);
  }
  out.anchor = as_is ? scene.meshes[0].soup.anchor : lo.x <= hi.x ? choose_anchor(lo, hi) : glm::dvec3(0.0);
  out.positions.reserve(vertices);
  out.triangles.reserve(triangles);
  for (const MeshInstance& m : scene.meshes) {
    const size_t first = out.triangles.size();
    out.append(m.soup, m.transform, m.material);
    // A mirroring transform turns counter-clockwise into clockwise; swap two corners to keep normals outward.
    if (glm::determinant(glm::mat3(m.transform)) < 0.0f)
      for (size_t t = first; t < out.triangles.size(); ++t) std::swap(out.triangles[t].y, out.triangles[t].z);
  }
  return out;
}

WorldBox scene_world_bounds(const Scene& scene) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  if (is_animated(scene)) {
    const TriangleSoup soup = scene_triangles(scene);
    const Bounds b = soup.bounds();
    if (!b.empty()) lo = glm::dvec3(b.lo) + soup.anchor, hi = glm::dvec3(b.hi) + soup.anchor;
    return WorldBox(lo, hi);
  }
  for (const MeshInstance& m : scene.meshes) {
    std::vector<bool> used(m.soup.positions.size(), false);
    for (const glm::uvec4& t : m.soup.triangles) used[t.x] = used[t.y] = used[t.z] = true;
    const glm::dmat4 transform(m.transform);
    for (size_t i = 0; i < used.size(); ++i)
      if (used[i]) {
        const glm::dvec4 p =
            transform * glm::dvec4(m.soup.anchor + glm::dvec3(glm::vec3(m.soup.positions[i])), 1.0);
        lo = glm::min(lo, glm::dvec3(p) / p.w);
        hi = glm::max(hi, glm::dvec3(p) / p.w);
      }
  }
  return WorldBox(lo, hi);
}

Bounds scene_bounds(const Scene& scene) {
  const WorldBox b = scene_world_bounds(scene);
  Bounds bounds;
  if (!box_empty(b)) bounds.lo = glm::vec3(b.lo), bounds.hi = glm::vec3(b.hi);
  return bounds;
}

}  // namespace voxr
