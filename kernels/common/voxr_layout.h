/* voxr_layout.h — the one description of everything the host and the kernels both read: parameter blocks
 * passed by value, the records one stage writes and another reads, and the packing of shared words.
 * Written in the C subset that OpenCL C 1.2 and C++20 both accept: fixed-size scalar arrays, no vector
 * types, no padding surprises (every member is 4 bytes wide). host/cl/layout_checks.cpp static_asserts
 * the sizes, and tests/layout_test.cpp compares every entry of VOXR_LAYOUT_ENTRIES with the value a kernel
 * (kernels/test/) measures on the device. */
#ifndef VOXR_LAYOUT_H
#define VOXR_LAYOUT_H

#ifndef __OPENCL_VERSION__
#include <stdint.h>
typedef uint32_t uint;
#endif

/* Vertices are snapped to a lattice of 1/VOXR_SUBVOXEL voxel in grid space, so every membership predicate
 * (triangle/box overlap, pixel-centre coverage, slab depth) is decided by exact 64-bit integer arithmetic:
 * identical on every device and equal to the CPU reference bit for bit. */
#define VOXR_SUBVOXEL_BITS 8
#define VOXR_SUBVOXEL (1 << VOXR_SUBVOXEL_BITS)

/* Triangles longer than this along any grid axis (in voxels) would overflow the exact predicates; the host
 * splits them before upload (host/voxelize/triangle_splitter.h). */
#define VOXR_MAX_TRIANGLE_EXTENT 2040

/* Normal sums are fixed point: each triangle adds its unit normal times VOXR_NORMAL_ONE. A voxel's sums are
 * packed into 32-bit halves (vox_scanline.h), which stay exact while at most VOXR_MAX_ATTRIBUTE_TRIANGLES
 * triangles write one voxel; the host refuses count/normal for meshes with more triangles than that. */
#define VOXR_NORMAL_ONE 256
#define VOXR_MAX_ATTRIBUTE_TRIANGLES ((1u << 23) - 1u)

/* Rasterization rules. */
#define VOXR_MODE_CONSERVATIVE 0 /* every voxel whose closed box the closed triangle touches */
#define VOXR_MODE_CENTER 1       /* voxel column centre inside the projection, depth in [k, k+1) */

/* Grid parameters passed by value to the voxelization kernels. */
typedef struct VoxGridParams {
  float world_to_grid[12]; /* rows of a 3x4 affine: world -> grid units */
  uint dims[4];            /* x, y, z; [3]: the attribute pass's entries (writes at ranks past it dropped) */
  uint rows_per_copy;      /* rows of one slab that a single raster work item handles */
  uint triangle_count;
  uint margin;   /* conservative mode: voxel boxes are widened by this many 1/VOXR_SUBVOXEL units on every
                    side, the bound on how far snapping and the float transform move a vertex */
  uint channels; /* attribute pass: the ChannelSet bits to accumulate (host/grid/channel_table.h) */
  uint list_capacity; /* triangle-list pass (VOX_PASS 2): entries of the id array (writes past it dropped) */
  uint first_slice;   /* a window of a larger grid: dims[2] slices from this one of the grid world_to_grid maps
                         to; snapped z is taken relative to it (an exact integer shift, so a window's voxels
                         are bit for bit those of the whole grid's slices) */
} VoxGridParams;

/* Copy records, the duplication step the slice voxelizer (a triangle's slabs x blocks of rows), the slicemap
 * voxelizer (its tiles of column centres) and the kernel rasterizer (its pixel tiles) share
 * (util/expand_copies.cl, host/cl/record_bins.h). A setup kernel writes per triangle its copy count and a
 * CopyBox: the copies are the cells of a box `width` cells across from cell `first`, row by row (count =
 * width x rows). A cell packs a column in the low 16 bits and a row in the high 16. */
#define VOXR_CELL(column, row) ((column) | ((row) << 16))
#define VOXR_CELL_COLUMN(cell) ((cell)&0xffffu)
#define VOXR_CELL_ROW(cell) ((cell) >> 16)

typedef struct CopyBox {
  uint first; /* VOXR_CELL of the box's first cell */
  uint width; /* cells per row */
} CopyBox;

/* One copy: a triangle and one cell of its box, one work item of the consumer kernel. The slice voxelizer's
 * cell is (block of rows_per_copy rows, slab k), the slicemap's (column tile, row tile), the rasterizer's
 * (tile column, tile row) of VOXR_RASTER_TILE pixels. */
typedef struct CopyRecord {
  uint triangle;
  uint cell;
} CopyRecord;

#define VOXR_MAX_BLOCKS 0xffffu

/* A triangle in exact grid coordinates (vox_triangle.h), written by the setup stages and read by every
 * later stage instead of the mesh: vertex c is (x[c], y[c], z[c]) in 1/VOXR_SUBVOXEL voxel units. */
typedef struct VoxSnappedTriangle {
  int x[3];
  int y[3];
  int z[3];
  uint material;
  uint source; /* the triangle's index in the mesh (vox_setup.cl; the triangle-list pass writes it) */
  uint pad;
} VoxSnappedTriangle;

/* The colour channel's inputs (host/voxelize/device_colors.h, kernels/common/vox_color.h): how many entries
 * each per-vertex / per-triangle array holds (0: absent; an index at or past the count reads as white, no
 * texture coordinates, no look), and one record per look: its RGBA8 factor and its texture's place in the
 * texel atlas (width 0: no texture). */
typedef struct VoxColorParams {
  uint vertex_rgba;   /* entries of the vertex colours */
  uint vertex_uv;     /* entries of the vertex texture coordinates (two floats each) */
  uint triangle_look; /* entries of the per-triangle look indices (0: every triangle has look 0) */
  uint looks;         /* entries of the look table */
} VoxColorParams;

typedef struct VoxColorLook {
  uint factor;       /* RGBA8, R in the low byte */
  uint texel_offset; /* the texture's first texel in the atlas */
  uint width;        /* texels; 0 for no texture */
  uint height;
} VoxColorLook;

/* The rank index of a dense occupancy array: one 64-bit word per 32-bit occupancy word, holding the word
 * itself in the low half and the number of set voxels before it (its first set voxel's rank) in the high
 * half, so a voxel's rank costs one load and a popcount (grid_view.h). */
#define VOXR_RANKED(rank, bits) (((ulong)(rank) << 32) | (ulong)(bits))
#define VOXR_RANKED_RANK(w) ((uint)((w) >> 32))
#define VOXR_RANKED_BITS(w) ((uint)(w))

/* The row-padded bit layout of the solid stages (vox_solid_bits.h): word k * slice_words + j * words_x +
 * i / 32 holds voxel (i, j, k) at bit i % 32. */
typedef struct VoxSolidLayout {
  uint dims[4]; /* x, y, z, unused */
  uint words_x; /* ceil(dims.x / 32) */
  uint slice_words;
  uint pad[2];
} VoxSolidLayout;

/* What grid_view.h needs besides the channel buffers: the grid's frame and which channels exist. */
typedef struct VoxGridView {
  float world_to_grid[12]; /* rows of a 3x4 affine: world -> grid units (voxel (i,j,k) = [i,i+1]x...) */
  uint dims[4];            /* x, y, z, unused */
  uint channels;           /* ChannelSet bits (host/grid/channel_table.h) */
  uint voxels_set;         /* entries of each sparse channel */
  uint has_rank_index;     /* 1 when the rank index describes the occupancy (grid_view.h gv_rank) */
  uint pad;
} VoxGridView;

/* ---- Rendering (host/render, kernels/raster, kernels/render) ---- */

/* Material kinds as the kernels read them (core/material.h MaterialKind, same order). */
#define VOXR_MATERIAL_OPAQUE 0
#define VOXR_MATERIAL_DIELECTRIC 1
#define VOXR_MATERIAL_SHEET 2

/* A material on the device (host/render/render_scene.h fills it from core/material.h). */
typedef struct RenderMaterial {
  float color[3];         /* diffuse reflectance (opaque, sheet) */
  uint kind;              /* VOXR_MATERIAL_* */
  float transmittance[3]; /* per crossing (sheet) */
  float ior;              /* dielectric */
  float absorption[3];    /* sigma_a per world unit (dielectric) */
  float pad;
} RenderMaterial;

/* The light and the environment, positions relative to the scene's anchor. */
typedef struct RenderLight {
  float position[3];  /* point light */
  uint directional;   /* 1: directional, 0: point */
  float direction[3]; /* directional: unit vector, the way light travels */
  float pad0;
  float intensity[3]; /* point: irradiance intensity / d^2 at distance d; directional: irradiance */
  float pad1;
  float ambient[3]; /* environment colour: the constant ambient term and what rays that miss see */
  float pad2;
} RenderLight;

/* The crease rule of shading normals (raster_resolve.cl and the reference alike): a vertex normal more than
 * 45 degrees from the triangle's own normal smooths over a crease, so the triangle's normal stands in for it
 * at that corner before interpolating; a box's faces shade flat (its corner normals are 54.7 degrees off each
 * face), a tessellated sphere's stay smooth. (Comparing only the interpolated normal let a box face's centre
 * shade 11-32 degrees off, and glass boxes refract as if curved.) */
#define VOXR_CREASE_COS 0.70710678f

/* A pixel that sees no triangle. */
#define VOXR_NO_TRIANGLE 0xffffffffu

/* What the camera sees at one pixel, resolved from the visibility buffer (raster_resolve.cl) or found by the
 * reference's primary ray. Positions relative to the anchor, normals unit length and turned towards the
 * viewer; `triangle` is VOXR_NO_TRIANGLE where the pixel sees nothing (the other fields are then 0). */
typedef struct SurfaceSample {
  float position[3];
  uint triangle;
  float normal[3]; /* shading normal: interpolated vertex normal */
  uint material;
  float geometric_normal[3];
  float distance;       /* from the eye along the pixel's ray */
  float barycentric[2]; /* of vertices 1 and 2 */
  float pad[2];
} SurfaceSample;

/* A SurfaceSample found by marching a voxel grid (the end of a voxel refraction path): no triangle, but a
 * surface all the same (position, normal, material from the voxel). Only VOXR_NO_TRIANGLE means "nothing". */
#define VOXR_VOXEL_HIT 0xfffffffeu

/* ---- Refraction (host/render/refraction_method.h, kernels/common/refraction.h) ----
 * One record per pixel describing the path its camera ray took through dielectrics, written by every
 * refraction method (voxel, image-space, the Embree reference) and read by shade.cl:
 *   pixel = fresnel * environment(reflect_direction) + throughput * L(end)
 * where `end` is a SurfaceSample (the opaque surface the path ends on, or VOXR_NO_TRIANGLE: the environment
 * in exit_direction). A pixel that sees no dielectric has events 0, throughput 1, fresnel 0 and its end
 * sample is the primary one; exit_direction is then the camera ray's direction (what a miss shows). */
#define VOXR_PATH_EVENTS_MASK 0xffu /* interfaces met: refractions and total internal reflections */
#define VOXR_PATH_TIR (1u << 8)     /* at least one total internal reflection */
#define VOXR_PATH_ENV (1u << 9)     /* the path ends in the environment */
#define VOXR_PATH_LOST (1u << 10)   /* the event limit was reached: the path contributes nothing */
#define VOXR_PATH_MAX_EVENTS 32

typedef struct RefractionPath {
  float throughput[3];        /* RGB weight of L(end): product of (1 - F) per refraction and Beer-Lambert */
  uint events;                /* VOXR_PATH_* */
  float reflect_direction[3]; /* unit, world: the first surface's mirror direction (fresnel > 0) */
  float fresnel;              /* Schlick F at the first surface (0 where the pixel sees no dielectric) */
  float exit_position[3];     /* anchor-relative world: where the path left its last interface */
  float pad0;
  float
      exit_direction[3]; /* unit, world: the direction the path leaves with (the camera ray's if events 0) */
  float pad1;
} RefractionPath;

/* One level of voxel refraction's grids (host/render/voxel_refraction.h). The grid is axis aligned: world
 * (anchor-relative) = origin + voxel_size * grid units. */
typedef struct VoxelLevelParams {
  float origin[3];
  float voxel_size;
  uint brick_dims[3]; /* the empty-space bit grid: one bit per VOXR_BRICK^3 voxels, x fastest */
  uint present;       /* 0: no such level */
} VoxelLevelParams;

/* What refract_voxel.cl needs besides the grid views: the fine level (the grid fitted to the dielectrics, or
 * the whole scene's) the march starts in, and the coarse level (the whole scene) it goes on in after leaving
 * the fine grid's box. */
typedef struct VoxelRefractParams {
  VoxelLevelParams fine;
  VoxelLevelParams coarse; /* present 0: the fine level is the whole scene's grid */
  uint two_surface;        /* 1: voxel-two, 0: voxel-multi */
  uint step_dda;           /* 1: 3-D DDA, 0: the papers' step along the dominant axis */
  uint smooth_normals;     /* 1: 3x3x3 weighted normals, 0: the voxel's own */
  float cos_threshold;     /* cos of the angle threshold between a run's normals */
  uint max_steps;          /* voxels visited at most per path, both levels together */
  uint pad[3];
} VoxelRefractParams;

/* Voxels per side of a brick of the empty-space grid voxel refraction skips through. */
#define VOXR_BRICK 8

/* What image_space.cl needs besides its buffers (host/render/image_space_refraction.h). */
typedef struct ImageSpaceParams {
  uint triangle_count; /* of the mesh */
  uint inward_count;   /* entries of the per-vertex inward distances (d_N) */
  uint iterations;     /* of the nearby-geometry lookup */
  float scene_size;    /* the lookup's first guess where the exit point's pixel shows no opaque surface */
} ImageSpaceParams;

/* What distance_maps.cl needs besides its buffers (host/render/distance_map_refraction.h): the cube maps
 * about `reference` (anchor-relative), face f's texel (x, y) at (f * layer_res + y) * layer_res + x, layer l
 * of the refractor's maps starting at l * 6 * layer_res^2. */
typedef struct DistanceMapParams {
  float reference[3];
  uint layer_res;     /* texels per cube face side */
  uint layers;        /* refractor layers (depth-peeled) */
  uint max_events;    /* interfaces met at most (<= VOXR_PATH_MAX_EVENTS) */
  uint search_steps;  /* linear search steps per segment */
  uint secant_steps;  /* secant refinement steps */
  float radius;       /* the refractor's bounding sphere about the reference point */
  float scene_radius; /* the whole scene's bounding sphere about the reference point */
  float epsilon;      /* world units: where a search starts past the point it leaves */
  float pad;
} DistanceMapParams;

/* The cube map's faces (host/render/distance_map_refraction.h): forward, right, up per face, in the order
 * +x, -x, +y, -y, +z, -z; right = forward x up (CameraFrame's convention). A direction's face is its
 * largest component's. */
#define VOXR_CUBE_FACES                                                                            \
  {                                                                                                \
    {1, 0, 0, 0, 0, 1, 0, 1, 0}, {-1, 0, 0, 0, 0, -1, 0, 1, 0}, {0, 1, 0, -1, 0, 0, 0, 0, -1},     \
        {0, -1, 0, -1, 0, 0, 0, 0, 1}, {0, 0, 1, -1, 0, 0, 0, 1, 0}, {0, 0, -1, 1, 0, 0, 0, 1, 0}, \
  }

/* Where a receiver finds its column and slab in a light's grid (host/render/light_frame.h). Orthographic
 * (directional light): grid = to_light * p. Frustum (point light): q = to_light * p is the point in the
 * light's view (z along the view, world units) and grid = ((q.x / q.z - u0) * inv_du,
 * (q.y / q.z - v0) * inv_dv, (inv_near - 1 / q.z) * depth_scale): a projective map, so triangles stay
 * triangles and slabs are depth slices (uniform in 1/z). */
typedef struct ShadowFrame {
  float to_light[12]; /* rows of a 3x4 affine from anchor-relative world coordinates */
  uint dims[4];
  uint projective;
  float u0, v0, inv_du, inv_dv;
  float inv_near, depth_scale;
  float voxel_size; /* orthographic: the voxel edge in world units */
} ShadowFrame;

/* The light frame fitted on the device (host/render/light_frame.h DeviceLightFrame,
 * kernels/render/shadow/light_project.cl), by value. Fit: which triangles can shadow the receivers' box and
 * their light-space boxes; vectors as xyz + w, anchor-relative. */
typedef struct LightFitParams {
  float receivers_lo[4], receivers_hi[4]; /* the receivers' box */
  float row0[4], row1[4], row2[4];        /* the light space's axes */
  float light[4];                         /* point light: position; directional: the light's direction */
  uint projective;                        /* point light */
  float eps;                              /* casts_on's tolerance */
  float depth_floor;                      /* point light: the near cut of casters */
  uint point;                             /* a point light (projective, or far enough to be parallel) */
} LightFitParams;

/* Light mesh pieces: projection into a point light's grid, near clip, oversize splitting. */
typedef struct LightPiecesParams {
  float m0[4], m1[4], m2[4]; /* the voxelized grid's world_to_grid rows (identity for a point light) */
  float view0[4], view1[4], view2[4]; /* point light: the light view's axes */
  float light[4];                     /* point light: anchor-relative position */
  float dims[4];                      /* the grid's dims as floats */
  float z_min;                        /* point light: the near clip (half the first slab's depth) */
  uint projective;
  uint write; /* 0: count, 1: write */
  uint pad;
} LightPiecesParams;

/* ---- The kernel rasterizer (host/render/visibility_rasterizer.h, kernels/raster) ---- */

/* Screen positions are snapped to 1/VOXR_SUBPIXEL pixel; coverage is then decided by exact 64-bit integer
 * edge functions (raster_coverage.h), identical on every device and in the CPU reference. */
#define VOXR_SUBPIXEL_BITS 8
#define VOXR_SUBPIXEL (1 << VOXR_SUBPIXEL_BITS)
/* One raster work item covers a tile of VOXR_RASTER_TILE x VOXR_RASTER_TILE pixels (a 64-bit mask). */
#define VOXR_RASTER_TILE 8
/* A triangle clipped by the near plane and the four guard-band planes has at most 3 + 5 vertices. */
#define VOXR_RASTER_MAX_VERTICES 8
/* Largest image side, in pixels (tile indices fit 16 bits). */
#define VOXR_RASTER_MAX_SIDE 16384
/* Guard band: triangles are clipped so every screen position lies within +-VOXR_RASTER_GUARD pixels, which
 * keeps snapped coordinates below 2^29 and the edge functions' products below 2^61. */
#define VOXR_RASTER_GUARD (1 << 21)

/* What raster_setup.cl needs to bin a mesh for one view. */
typedef struct RasterParams {
  float view_projection[16]; /* column-major (glm): anchor-relative world -> clip; z/w in [0, 1] is drawn */
  uint width;                /* image size in pixels; row 0 is the top (y_ndc = +1) */
  uint height;
  uint kind_mask;      /* bit 1 << RenderMaterial.kind of the triangles drawn */
  uint triangle_count; /* of the mesh */
  uint material_count; /* triangles whose material id is not below this are not drawn */
  float guard[2];      /* guard-band planes |x| <= guard[0] w, |y| <= guard[1] w */
  uint cull;           /* VOXR_CULL_*: which faces are not drawn */
} RasterParams;

/* Face culling (RasterParams.cull): the faces dropped, front (counter-clockwise as the viewer sees it) or
 * back (VOXR_PRIM_BACK); a culled triangle gets vertex_count 0. */
#define VOXR_CULL_NONE 0u
#define VOXR_CULL_FRONT 1u
#define VOXR_CULL_BACK 2u

/* A primitive's flags: the triangle appears clockwise in the image as the viewer sees it (rows up), i.e. it
 * shows its back when the mesh winds counter-clockwise seen from outside. */
#define VOXR_PRIM_BACK 1u

/* One triangle after setup (raster_setup.cl), clipped and snapped: a convex polygon of vertex_count vertices
 * (x[i], y[i]) in 1/VOXR_SUBPIXEL pixel, image rows down, ordered so its signed area sum(x_i y_{i+1} -
 * x_{i+1} y_i) is positive; vertex_count 0 when it is not drawn (material kind, culled, clipped away, no
 * area, no pixel centre in its box). Its pixels' z_ndc is depth[0] (px - width/2) + depth[1] (py - height/2)
 * + depth[2] at pixel centre (px, py) in pixels. Its copies (CopyBox, written beside it) are the tiles of
 * VOXR_RASTER_TILE x VOXR_RASTER_TILE pixels its box of pixel centres meets. */
typedef struct RasterPrim {
  uint vertex_count;
  uint flags; /* VOXR_PRIM_* */
  float depth[3];
  uint pad;
  int x[VOXR_RASTER_MAX_VERTICES];
  int y[VOXR_RASTER_MAX_VERTICES];
} RasterPrim;

/* The visibility buffer holds one 64-bit word per pixel: (float bits of z_ndc in [0, 1]) << 32 | triangle,
 * so a 64-bit atomic min keeps the nearest triangle and, at equal depth, the lower id. A pixel no triangle
 * covers keeps the cleared word, all bits set (its low half is VOXR_NO_TRIANGLE). */

/* The camera as raster_resolve.cl reads it (host/render/camera_frame.h CameraFrame): the ray through pixel
 * point (px, py) is normalize(forward + sx right + sy up), sx = (2 px / width - 1) tan_half_fov_y aspect,
 * sy = (1 - 2 py / height) tan_half_fov_y. Anchor-relative positions. */
typedef struct RenderCamera {
  float eye[3];
  uint width;
  float forward[3];
  uint height;
  float right[3];
  float tan_half_fov_y;
  float up[3];
  float aspect;
} RenderCamera;

/* Every size and offset the host and the device must agree on, in one list that both expand: SIZE(T) for a
 * struct, OFFSET(T, field) for a member. */
/* clang-format off */
#define VOXR_LAYOUT_ENTRIES(SIZE, OFFSET)                                                                \
  SIZE(VoxGridParams)                                                                                    \
  OFFSET(VoxGridParams, world_to_grid) OFFSET(VoxGridParams, dims) OFFSET(VoxGridParams, rows_per_copy)   \
  OFFSET(VoxGridParams, triangle_count) OFFSET(VoxGridParams, margin) OFFSET(VoxGridParams, channels)     \
  OFFSET(VoxGridParams, list_capacity) OFFSET(VoxGridParams, first_slice)                                 \
  SIZE(CopyBox) OFFSET(CopyBox, first) OFFSET(CopyBox, width)                                             \
  SIZE(CopyRecord) OFFSET(CopyRecord, triangle) OFFSET(CopyRecord, cell)                                  \
  SIZE(VoxSnappedTriangle) OFFSET(VoxSnappedTriangle, x) OFFSET(VoxSnappedTriangle, y)                    \
  OFFSET(VoxSnappedTriangle, z) OFFSET(VoxSnappedTriangle, material) OFFSET(VoxSnappedTriangle, source)  \
  SIZE(VoxColorParams) OFFSET(VoxColorParams, vertex_rgba) OFFSET(VoxColorParams, vertex_uv)            \
  OFFSET(VoxColorParams, triangle_look) OFFSET(VoxColorParams, looks)                                     \
  SIZE(VoxColorLook) OFFSET(VoxColorLook, factor) OFFSET(VoxColorLook, texel_offset)                      \
  OFFSET(VoxColorLook, width) OFFSET(VoxColorLook, height)                                                \
  SIZE(VoxSolidLayout) OFFSET(VoxSolidLayout, dims) OFFSET(VoxSolidLayout, words_x)                       \
  OFFSET(VoxSolidLayout, slice_words)                                                                     \
  SIZE(VoxGridView) OFFSET(VoxGridView, world_to_grid) OFFSET(VoxGridView, dims)                          \
  OFFSET(VoxGridView, channels) OFFSET(VoxGridView, voxels_set) OFFSET(VoxGridView, has_rank_index)       \
  SIZE(RenderMaterial) OFFSET(RenderMaterial, color) OFFSET(RenderMaterial, kind)                         \
  OFFSET(RenderMaterial, transmittance) OFFSET(RenderMaterial, ior) OFFSET(RenderMaterial, absorption)    \
  SIZE(RenderLight) OFFSET(RenderLight, position) OFFSET(RenderLight, directional)                        \
  OFFSET(RenderLight, direction) OFFSET(RenderLight, intensity) OFFSET(RenderLight, ambient)              \
  SIZE(SurfaceSample) OFFSET(SurfaceSample, position) OFFSET(SurfaceSample, triangle)                     \
  OFFSET(SurfaceSample, normal) OFFSET(SurfaceSample, material) OFFSET(SurfaceSample, geometric_normal)   \
  OFFSET(SurfaceSample, distance) OFFSET(SurfaceSample, barycentric)                                      \
  SIZE(RefractionPath) OFFSET(RefractionPath, throughput) OFFSET(RefractionPath, events)                 \
  OFFSET(RefractionPath, reflect_direction) OFFSET(RefractionPath, fresnel)                               \
  OFFSET(RefractionPath, exit_position) OFFSET(RefractionPath, exit_direction)                            \
  SIZE(VoxelLevelParams) OFFSET(VoxelLevelParams, origin) OFFSET(VoxelLevelParams, voxel_size)            \
  OFFSET(VoxelLevelParams, brick_dims) OFFSET(VoxelLevelParams, present)                                  \
  SIZE(VoxelRefractParams) OFFSET(VoxelRefractParams, fine) OFFSET(VoxelRefractParams, coarse)            \
  OFFSET(VoxelRefractParams, two_surface) OFFSET(VoxelRefractParams, cos_threshold)                       \
  OFFSET(VoxelRefractParams, max_steps)                                                                   \
  SIZE(ImageSpaceParams) OFFSET(ImageSpaceParams, triangle_count) OFFSET(ImageSpaceParams, inward_count)  \
  OFFSET(ImageSpaceParams, iterations) OFFSET(ImageSpaceParams, scene_size)                               \
  SIZE(DistanceMapParams) OFFSET(DistanceMapParams, reference) OFFSET(DistanceMapParams, layer_res)       \
  OFFSET(DistanceMapParams, layers) OFFSET(DistanceMapParams, max_events)                                 \
  OFFSET(DistanceMapParams, search_steps) OFFSET(DistanceMapParams, secant_steps)                         \
  OFFSET(DistanceMapParams, radius) OFFSET(DistanceMapParams, scene_radius)                               \
  OFFSET(DistanceMapParams, epsilon)                                                                      \
  SIZE(ShadowFrame) OFFSET(ShadowFrame, to_light) OFFSET(ShadowFrame, dims)                               \
  OFFSET(ShadowFrame, projective) OFFSET(ShadowFrame, u0) OFFSET(ShadowFrame, inv_dv)                     \
  OFFSET(ShadowFrame, depth_scale) OFFSET(ShadowFrame, voxel_size)                                        \
  SIZE(RasterParams) OFFSET(RasterParams, view_projection) OFFSET(RasterParams, width)                    \
  OFFSET(RasterParams, height) OFFSET(RasterParams, kind_mask) OFFSET(RasterParams, triangle_count)       \
  OFFSET(RasterParams, material_count) OFFSET(RasterParams, guard) OFFSET(RasterParams, cull)             \
  SIZE(RasterPrim) OFFSET(RasterPrim, vertex_count) OFFSET(RasterPrim, flags)                             \
  OFFSET(RasterPrim, depth) OFFSET(RasterPrim, x) OFFSET(RasterPrim, y)                                   \
  SIZE(LightFitParams) OFFSET(LightFitParams, receivers_hi) OFFSET(LightFitParams, row2)                 \
  OFFSET(LightFitParams, light) OFFSET(LightFitParams, projective) OFFSET(LightFitParams, depth_floor)    \
  SIZE(LightPiecesParams) OFFSET(LightPiecesParams, view0) OFFSET(LightPiecesParams, dims)                \
  OFFSET(LightPiecesParams, z_min) OFFSET(LightPiecesParams, write)                                       \
  SIZE(RenderCamera) OFFSET(RenderCamera, eye) OFFSET(RenderCamera, width) OFFSET(RenderCamera, forward)   \
  OFFSET(RenderCamera, height) OFFSET(RenderCamera, right) OFFSET(RenderCamera, tan_half_fov_y)           \
  OFFSET(RenderCamera, up) OFFSET(RenderCamera, aspect)
/* clang-format on */

#endif
