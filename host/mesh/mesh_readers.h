// One reader per mesh format, each from the file's bytes to a PolygonMesh. They check everything the
// geometry depends on and throw voxr::Error with a one-line message that starts with `name` (the file) and
// names the place (line, element and property, triangle): unparseable or non-finite numbers, truncated
// files, counts a header promises but the body does not hold, indices out of range. Polygons stay polygons
// (polygon_triangulation.h triangulates them); faces of fewer than 3 corners are kept for the caller to
// count. Formats: ASCII OFF (Princeton shape benchmark; colour and normal columns, comments), Wavefront
// OBJ (v, f with v/vt/vn forms and negative indices; `usemtl` names give material ids in the order faces
// first use them, none when there is only one; other statements ignored), PLY 1.0 (ASCII and both
// binary byte orders, every scalar type, any property order), STL (ASCII and binary; identical corners are
// merged so closed meshes stay closed by index).
// Surface colour (PolygonMesh's vertex_rgba, vertex_uv, face_looks, looks, textures; docs/mesh-files.md):
// OFF vertex colours (COFF) and face colours; OBJ `v x y z r g b`, `vt` and the `mtllib` libraries' Kd,
// d/Tr and map_Kd; PLY vertex and face red, green, blue (and alpha). STL has none. Colour values out of
// range, texture coordinates that are not finite numbers and textures that cannot be read fail like any
// other fault.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "mesh/polygon_mesh.h"

namespace voxr {

PolygonMesh read_off(const std::string& name, std::string_view bytes);
// `name` is also the path that `mtllib` libraries are found relative to; a library that is missing adds a
// line to `notes` (when given) and leaves its materials white.
PolygonMesh read_obj(const std::string& name, std::string_view bytes,
                     std::vector<std::string>* notes = nullptr);
PolygonMesh read_ply(const std::string& name, std::string_view bytes);
// `notes` receives what was read but ignored (e.g. bytes after the last triangle of a binary STL).
PolygonMesh read_stl(const std::string& name, std::string_view bytes, std::vector<std::string>& notes);

}  // namespace voxr
