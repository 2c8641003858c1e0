// Mesh formats read through Assimp: glTF 2.0 (.gltf, .glb), FBX, Collada (.dae) and 3MF. Assimp keeps
// positions and node transforms in float (ai_real); this reader composes the node hierarchy and transforms
// each vertex in double, so no rounding is added beyond what Assimp already did.
#pragma once

#include <filesystem>

#include "mesh/polygon_mesh.h"

namespace voxr {

// Lower-case file extensions (with the dot) that read_with_assimp accepts.
inline constexpr const char* kAssimpExtensions[] = {".gltf", ".glb", ".fbx", ".dae", ".3mf"};

// True when `file`'s extension (any case) is one of kAssimpExtensions.
bool is_assimp_extension(const std::filesystem::path& file);

// Every polygon face of every mesh instance in `file`'s node hierarchy, in world units (the file's units;
// Collada's <unit> and up axis are applied by Assimp as a root transform), each instance transformed by
// its node's accumulated transform in double. A mesh referenced by n nodes appears n times. Faces keep
// their corner count (no triangulation); corners at identical positions are merged (CornerWelder, over the
// whole file), so a closed mesh stays closed by index. Winding is reversed under mirroring transforms so
// faces keep their orientation. Points and lines are skipped (they have no area); skinning, morph targets and
// animation are ignored (the bind pose is read). `materials` gives each face its aiMesh's mMaterialIndex,
// Assimp's number for the material, which for glTF, Collada and FBX is the order in which meshes first use
// the file's materials (Assimp's glTF reader loads materials as primitives reference them, walking the nodes
// depth-first, so a glTF's own `materials` index is not kept; a primitive without one gets Assimp's default
// material after those); empty when every face has material 0.
// Surface colour (docs/mesh-files.md#colour): COLOR_0 per vertex, TEXCOORD_0 when a material has a texture
// (corners are then welded by position, colour and UV), one look per material the faces use in order of first
// use (base colour factor: AI_MATKEY_BASE_COLOR, else COLOR_DIFFUSE with OPACITY; texture:
// aiTextureType_BASE_COLOR, else DIFFUSE, embedded or a file relative to the mesh, else its file name beside
// the mesh); nothing when the file has no vertex colours and only plain white materials.
// Throws voxr::Error, one line starting with the path: missing or empty file, unknown extension, a file that
// does not look like its format (checked before Assimp sees it), a file Assimp cannot parse or validate (with
// Assimp's message), a position that is not finite or beyond 1e30 after its transforms, or no polygon faces
// (with the points and lines skipped); a colour outside [0, 1], a texture coordinate that is not finite, a
// texture that is missing or cannot be decoded.
PolygonMesh read_with_assimp(const std::filesystem::path& file);

}  // namespace voxr
