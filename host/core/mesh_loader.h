// Mesh files -> triangle soup. OFF, OBJ, PLY and STL are read by voxr's own readers (mesh/mesh_readers.h),
// in double precision; glTF, FBX, Collada and 3MF through Assimp (mesh/assimp_reader.h). Polygons are
// triangulated exactly (mesh/polygon_triangulation.h). Each triangle gets its face's material id as the
// reader numbers them: in the order faces first use the file's materials (OBJ: `usemtl` names; glTF,
// Collada, FBX: Assimp's material index, assimp_reader.h), 0 when the file has none.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/triangle_soup.h"

namespace voxr {

// True when `file`'s extension (any case) is one load_mesh reads.
bool is_mesh_file(const std::filesystem::path& file);

// The extensions load_mesh reads, lower case with the dot, comma-separated (for messages and --help).
std::string mesh_extensions();

// Reads `file` into a soup whose positions are relative to an anchor chosen for the mesh's place
// (triangle_soup.h: a mesh a million units from the origin keeps its precision). Vertex indices are kept as
// the file gives them (STL corners are merged by position). Messages about what was read but is suspect
// (non-planar or self-crossing polygons, faces of fewer than 3 corners, ignored trailing bytes) are appended
// to `warnings` when given, one line each, starting with the file path.
// Throws voxr::Error whose message starts with the file path when the file is missing or unreadable, has an
// unsupported extension, cannot be parsed (naming the line, or the element and property), is truncated,
// refers to vertices it does not have, holds no triangles or has a vertex that is NaN or infinite.
// Safe to call from several threads.
TriangleSoup load_mesh(const std::filesystem::path& file, std::vector<std::string>* warnings = nullptr);

// The soup of a triangle mesh the caller holds in memory, made exactly as load_mesh makes one from a file
// with the same numbers (same anchor, same float positions): positions is vertex_count x 3 doubles (x, y, z),
// triangles is triangle_count x 3 vertex indices, materials is empty or one id per triangle. Throws
// voxr::Error starting with `name` when a size is not a multiple of 3 (or materials' is not the triangle
// count), there are no triangles, an index is out of range, or a position is NaN or infinite.
TriangleSoup soup_from_arrays(std::span<const double> positions, std::span<const uint32_t> triangles,
                              std::span<const uint32_t> materials, const std::string& name);

}  // namespace voxr
