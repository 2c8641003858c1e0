/* shadow_tolerances.h — the exact shadow ray's tolerances, fractions of the scene's size (the soup's largest
 * side), defined once for the reference (host/reference/reference_scene.h kStartEpsilon, kMergeDistance) and
 * the voxel-exact lookup (kernels/render/shadow/shadow_exact.cl, host/render/techniques/
 * voxel_exact_shadows.cpp). C subset: the host and the kernels include it. */
#ifndef SHADOW_TOLERANCES_H
#define SHADOW_TOLERANCES_H

/* Hits nearer than this to the receiver are ignored: a surface point computed by a primary ray lies off its
 * plane by rounding, and would otherwise see its own or a neighbouring coplanar triangle. */
#define VOXR_SHADOW_START_EPSILON 1e-5f
/* Hits less than this apart on triangles that share a vertex index are one meeting of the ray with one
 * surface (at a shared edge or vertex). */
#define VOXR_SHADOW_MERGE_DISTANCE 1e-5f

#endif
