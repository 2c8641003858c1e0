// Mesh files -> triangle soup. OBJ, OFF, PLY and STL are parsed by OpenMesh's readers; polygons are
// fan-triangulated and every triangle gets material id 0.
#pragma once

#include <filesystem>
#include <string>

#include "core/triangle_soup.h"

namespace voxr {

// Extensions load_mesh accepts (lower case, with the dot).
inline constexpr const char* kMeshExtensions[] = {".obj", ".off", ".ply", ".stl"};

// True when `file`'s extension (any case) is one of kMeshExtensions.
bool is_mesh_file(const std::filesystem::path& file);

// Reads `file` into a soup. Vertex indices are kept as the file gives them, so a watertight file gives a
// watertight soup (faces OpenMesh's half-edge mesh would reject as non-manifold are kept as they are);
// STL, which has no shared vertices, has identical corners merged by OpenMesh's reader.
// Throws voxr::Error whose message starts with the file path when the file is missing or unreadable, has an
// unsupported extension, cannot be parsed, refers to vertices it does not have, holds no triangles or has
// a vertex that is NaN or infinite. OpenMesh's own diagnostics are captured, never printed; the first one
// is quoted in the error when parsing fails. Safe to call from several threads (loads are serialised,
// because OpenMesh's diagnostic streams are global).
TriangleSoup load_mesh(const std::filesystem::path& file);

}  // namespace voxr
