#include "render/technique.h"

#include <fmt/format.h>

#include "util/error.h"

namespace voxr {

namespace {

template <class Rows, class Names>
constexpr bool rows_follow_names(const Rows& rows, const Names& names) {
  if (rows.size() != names.size()) return false;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].method != names[i].value) return false;
  return true;
}
static_assert(rows_follow_names(kShadowTechniques, kShadowMethods),
              "kShadowTechniques has one row per kShadowMethods entry, in its order");
static_assert(rows_follow_names(kRefractionTechniques, kRefractionMethods),
              "kRefractionTechniques has one row per kRefractionMethods entry, in its order");

template <class Rows, class Method>
const auto& row_of(const Rows& rows, Method method) {
  for (const auto& row : rows)
    if (row.method == method) return row;
  throw InternalError("a method missing from its technique registry");
}

}  // namespace

SceneReference& FrameContext::need_reference(const char* who) const {
  if (reference == nullptr) fail("{} needs the exact reference scene (FrameRenderer::set_scene)", who);
  return *reference;
}

TechniqueDescription light_grid_description(const FrameStats& stats) {
  TechniqueDescription d;
  d.report["light_grid"] = {
      {"kind", stats.light.projective() ? "frustum" : "orthographic"},
      {"dims", {stats.light.grid.dims.x, stats.light.grid.dims.y, stats.light.grid.dims.z}},
      {"describe", stats.light.describe()},
      {"triangles", stats.light_triangles},
      {"device_bytes", stats.device_bytes}};
  d.lines.push_back(fmt::format("light grid {}, {} triangles from the light, {:.1f} MiB",
                                stats.light.describe(), stats.light_triangles,
                                double(stats.device_bytes) / (1 << 20)));
  return d;
}

HostFrame RefractionTechnique::render_on_host(const FrameContext&, const RenderOptions&) {
  throw InternalError("render_on_host of a technique that does not finish on the host");
}

std::unique_ptr<ShadowTechnique> make_shadow_technique(ClRuntime& cl, Voxelizer& voxelizer,
                                                       ShadowMethod method) {
  return row_of(kShadowTechniques, method).make(cl, voxelizer);
}

std::unique_ptr<RefractionTechnique> make_refraction_technique(ClRuntime& cl, Voxelizer& voxelizer,
                                                               RefractionMethod method) {
  return row_of(kRefractionTechniques, method).make(cl, voxelizer);
}

}  // namespace voxr
