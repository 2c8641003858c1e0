// Mesh files -> triangle soup. OBJ, PLY and STL are parsed by OpenMesh's readers (after a strict check of the
// file, see mesh_loader.cpp), ASCII OFF by voxr itself; polygons are fan-triangulated and every triangle gets
// material id 0.
#pragma once

#include <filesystem>

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
// unsupported extension, cannot be parsed (naming the line for text formats), is truncated, refers to
// vertices it does not have, holds no triangles or has a vertex that is NaN, infinite or beyond float range.
// Binary OFF and n-dimensional OFF are not supported. OpenMesh's own diagnostics are silenced, never
// printed. Safe to call from several threads (OpenMesh reads are serialised: its diagnostic streams are
// global).
TriangleSoup load_mesh(const std::filesystem::path& file);

}  // namespace voxr
