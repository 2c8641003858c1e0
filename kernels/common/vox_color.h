/* vox_color.h — the `color` channel's sample: the surface colour of one triangle at one voxel, shared by the
 * attribute pass of the slice family (vox_scanline.h, vox_direct.cl) and the CPU reference
 * (host/voxelize/reference_voxelizer.cpp), which compiles this file too, so both agree bit for bit (every
 * target and program builds with contraction off; the float operations below are written in one order).
 *
 *   where:   the point of the triangle closest to the voxel's centre (Ericson, "Real-Time Collision
 *            Detection" §5.1.5, ClosestPtPointTriangle: Voronoi regions of vertices, edges, face), computed
 *            on the snapped vertices in float relative to v0 (fixed point, 1/VOXR_SUBVOXEL voxel units).
 *            Its barycentric weights of v1 and v2 are rounded to 16-bit fixed point (w0 = 65536 - w1 - w2).
 *   colour:  vertex colour = (w0 c0 + w1 c1 + w2 c2 + 2^15) >> 16 per 8-bit component; texture
 *            coordinates = (w0 uv0 + w1 uv1) + w2 uv2 in float; texel: nearest, wrapped (GL_REPEAT):
 *            x = floor(frac(u) W), y = floor(frac(v) H) counted from the bottom row (row 0 of the image is
 *            v = 1); base colour c = (f t v + 32512) / 65025 per component (f: the look's factor, t: the
 *            texel, v: the vertex colour, all 8-bit; white where absent). Components are averaged as they
 *            are stored (sRGB-encoded for the usual formats), without linearising.
 * Accumulation (vox_scanline.h): per voxel two 64-bit sums, R + G 2^32 and B + A 2^32; each component sum
 * is at most 255 x VOXR_MAX_ATTRIBUTE_TRIANGLES < 2^31, so the halves never carry. vox_finalize.cl divides
 * by the voxel's count of (triangle, voxel) pairs rounding half up: (sum + n/2) / n. */
#ifndef VOX_COLOR_H
#define VOX_COLOR_H

#include "voxr_layout.h"

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#define VOXC_GLOBAL __global
#define VOXC_FLOOR floor
#else
#include <cmath>
#define VOXC_GLOBAL
#define VOXC_FLOOR std::floor
#endif

#define VOXC_ONE 65536 /* fixed-point barycentric one */
#define VOXC_WHITE 0xffffffffu

/* A voxel centre in the snapped triangles' fixed point (scalars: PoCL keeps private arrays in memory). */
typedef struct VoxCentre {
  long x, y, z;
} VoxCentre;

/* The centre of voxel (i, j, k) in the snapped triangles' fixed point: the one place that maps a voxel index
 * to a position for the colour sample. In a window of slices (VoxGridParams.first_slice) k and the snapped
 * vertices are both relative to the window's first slice, so the sample needs no offset. */
inline VoxCentre vox_voxel_centre(const VoxGridParams* grid, int i, int j, int k) {
  (void)grid;
  VoxCentre c;
  c.x = (long)i * VOXR_SUBVOXEL + VOXR_SUBVOXEL / 2;
  c.y = (long)j * VOXR_SUBVOXEL + VOXR_SUBVOXEL / 2;
  c.z = (long)k * VOXR_SUBVOXEL + VOXR_SUBVOXEL / 2;
  return c;
}

/* One triangle's colour inputs, set up once per triangle (or copy); scalar members only. */
typedef struct VoxColorTri {
  long ox, oy, oz;                    /* snapped v0, fixed point */
  float e1x, e1y, e1z, e2x, e2y, e2z; /* v1 - v0, v2 - v0 */
  float d11, d12, d22;                /* e1.e1, e1.e2, e2.e2 */
  uint rgba0, rgba1, rgba2;           /* vertex colours */
  float s0, s1, s2, t0, t1, t2;       /* texture coordinates (u, v) */
  uint factor;                        /* the look's factor */
  uint texel_offset, width, height;   /* the look's texture (width 0: none) */
  int is_flat;                        /* one colour everywhere (equal vertex colours, no texture) ... */
  uint flat_rgba;                     /* ... which is this one */
  int plain;                          /* white factor and no texture: the base colour is the vertex colour */
} VoxColorTri;

inline float vox_color_dot(float ax, float ay, float az, float x, float y, float z) {
  return (ax * x + ay * y) + az * z;
}

/* The geometry of the snapped triangle (x_c, y_c, z_c) for c = 0, 1, 2. */
inline void vox_color_geometry(VoxColorTri* c, long x0, long y0, long z0, long x1, long y1, long z1, long x2,
                               long y2, long z2) {
  c->ox = x0;
  c->oy = y0;
  c->oz = z0;
  c->e1x = (float)(x1 - x0);
  c->e1y = (float)(y1 - y0);
  c->e1z = (float)(z1 - z0);
  c->e2x = (float)(x2 - x0);
  c->e2y = (float)(y2 - y0);
  c->e2z = (float)(z2 - z0);
  c->d11 = vox_color_dot(c->e1x, c->e1y, c->e1z, c->e1x, c->e1y, c->e1z);
  c->d12 = vox_color_dot(c->e1x, c->e1y, c->e1z, c->e2x, c->e2y, c->e2z);
  c->d22 = vox_color_dot(c->e2x, c->e2y, c->e2z, c->e2x, c->e2y, c->e2z);
}

inline uint vox_color_mul(uint f, uint t, uint v, int shift) {
  const uint a = (f >> shift) & 255u, b = (t >> shift) & 255u, c = (v >> shift) & 255u;
  return ((a * b * c + 32512u) / 65025u) << shift;
}

/* The base colour of factor f, texel t and vertex colour v, per component. */
inline uint vox_color_combine(uint f, uint t, uint v) {
  return vox_color_mul(f, t, v, 0) | vox_color_mul(f, t, v, 8) | vox_color_mul(f, t, v, 16) |
         vox_color_mul(f, t, v, 24);
}

/* The colour inputs of mesh triangle `triangle` with vertex indices a, b, c (VoxColorParams says how many
 * entries each array holds; missing entries are white, no texture coordinates, no look). A triangle with
 * three equal vertex colours and no texture has one colour everywhere: the interpolation returns it exactly,
 * ((65536 c + 2^15) >> 16 = c), so vox_color_sample skips the closest point. */
inline void vox_color_fetch(VoxColorTri* t, VoxColorParams p, uint a, uint b, uint c, uint triangle,
                            VOXC_GLOBAL const uint* vertex_rgba, VOXC_GLOBAL const float* vertex_uv,
                            VOXC_GLOBAL const uint* triangle_look, VOXC_GLOBAL const VoxColorLook* looks) {
  t->rgba0 = a < p.vertex_rgba ? vertex_rgba[a] : VOXC_WHITE;
  t->rgba1 = b < p.vertex_rgba ? vertex_rgba[b] : VOXC_WHITE;
  t->rgba2 = c < p.vertex_rgba ? vertex_rgba[c] : VOXC_WHITE;
  const int uv = a < p.vertex_uv && b < p.vertex_uv && c < p.vertex_uv;
  t->s0 = uv ? vertex_uv[2 * (unsigned long)a] : 0.0f;
  t->t0 = uv ? vertex_uv[2 * (unsigned long)a + 1] : 0.0f;
  t->s1 = uv ? vertex_uv[2 * (unsigned long)b] : 0.0f;
  t->t1 = uv ? vertex_uv[2 * (unsigned long)b + 1] : 0.0f;
  t->s2 = uv ? vertex_uv[2 * (unsigned long)c] : 0.0f;
  t->t2 = uv ? vertex_uv[2 * (unsigned long)c + 1] : 0.0f;
  const uint look = p.triangle_look == 0 ? 0u : triangle < p.triangle_look ? triangle_look[triangle] : ~0u;
  t->factor = VOXC_WHITE;
  t->texel_offset = 0;
  t->width = 0;
  t->height = 0;
  if (look < p.looks) {
    const VoxColorLook l = looks[look];
    t->factor = l.factor;
    if (uv && l.width > 0 && l.height > 0) {
      t->texel_offset = l.texel_offset;
      t->width = l.width;
      t->height = l.height;
    }
  }
  t->is_flat = t->rgba0 == t->rgba1 && t->rgba1 == t->rgba2 && t->width == 0;
  t->flat_rgba = vox_color_combine(t->factor, VOXC_WHITE, t->rgba0);
  /* (255 * 255 * v + 32512) / 65025 = v: a white factor and texel leave the vertex colour as it is. */
  t->plain = t->factor == VOXC_WHITE && t->width == 0;
}

/* Clamps a weight to [0, 1] (NaN to 0) and rounds it to fixed point. */
inline int vox_color_weight(float w) {
  if (!(w > 0.0f)) return 0;
  if (w >= 1.0f) return VOXC_ONE;
  return (int)(w * (float)VOXC_ONE + 0.5f);
}

/* The fractional part of a texture coordinate times `size`, as a texel index in [0, size). */
inline uint vox_color_wrap(float s, uint size) {
  float f = s - VOXC_FLOOR(s);
  if (!(f >= 0.0f && f <= 1.0f)) f = 0.0f; /* infinite or NaN coordinates */
  const uint x = (uint)(f * (float)size);
  return x < size ? x : size - 1;
}

/* The base colour (RGBA8, R in the low byte) of triangle `c` at the point closest to `centre`. */
inline uint vox_color_sample(const VoxColorTri* c, VoxCentre centre, VOXC_GLOBAL const uint* texels) {
  if (c->is_flat) return c->flat_rgba;
  const float px = (float)(centre.x - c->ox);
  const float py = (float)(centre.y - c->oy);
  const float pz = (float)(centre.z - c->oz);
  /* Ericson's d1..d6 with p - v1 and p - v2 folded into the precomputed products. */
  const float d1 = vox_color_dot(c->e1x, c->e1y, c->e1z, px, py, pz);
  const float d2 = vox_color_dot(c->e2x, c->e2y, c->e2z, px, py, pz);
  const float d3 = d1 - c->d11, d4 = d2 - c->d12;
  const float d5 = d1 - c->d12, d6 = d2 - c->d22;
  float w1 = 0.0f, w2 = 0.0f;
  if (d1 <= 0.0f && d2 <= 0.0f) {
    /* vertex 0 */
  } else if (d3 >= 0.0f && d4 <= d3) {
    w1 = 1.0f;
  } else {
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
      const float den = d1 - d3;
      w1 = den > 0.0f ? d1 / den : 0.0f;
    } else if (d6 >= 0.0f && d5 <= d6) {
      w2 = 1.0f;
    } else {
      const float vb = d5 * d2 - d1 * d6;
      if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        const float den = d2 - d6;
        w2 = den > 0.0f ? d2 / den : 0.0f;
      } else {
        const float va = d3 * d6 - d5 * d4;
        const float e43 = d4 - d3, e56 = d5 - d6;
        if (va <= 0.0f && e43 >= 0.0f && e56 >= 0.0f) {
          const float den = e43 + e56;
          w2 = den > 0.0f ? e43 / den : 0.0f;
          w1 = 1.0f - w2;
        } else {
          const float sum = (va + vb) + vc;
          if (sum > 0.0f) {
            w1 = vb / sum;
            w2 = vc / sum;
          }
        }
      }
    }
  }
  int b1 = vox_color_weight(w1), b2 = vox_color_weight(w2);
  if (b1 + b2 > VOXC_ONE) b2 = VOXC_ONE - b1;
  const int b0 = VOXC_ONE - b1 - b2;

  uint vertex = 0;
  for (int s = 0; s < 32; s += 8) {
    const uint q = ((uint)b0 * ((c->rgba0 >> s) & 255u) + (uint)b1 * ((c->rgba1 >> s) & 255u)) +
                   (uint)b2 * ((c->rgba2 >> s) & 255u);
    vertex |= ((q + (VOXC_ONE / 2)) >> 16) << s;
  }
  if (c->plain) return vertex;
  uint texel = VOXC_WHITE;
  if (c->width > 0) {
    const float f0 = (float)b0 * (1.0f / (float)VOXC_ONE), f1 = (float)b1 * (1.0f / (float)VOXC_ONE);
    const float f2 = (float)b2 * (1.0f / (float)VOXC_ONE);
    const float u = (f0 * c->s0 + f1 * c->s1) + f2 * c->s2;
    const float v = (f0 * c->t0 + f1 * c->t1) + f2 * c->t2;
    const uint x = vox_color_wrap(u, c->width), y = c->height - 1u - vox_color_wrap(v, c->height);
    texel = texels[(unsigned long)c->texel_offset + (unsigned long)y * c->width + x];
  }
  return vox_color_combine(c->factor, texel, vertex);
}

/* The mean colour of `n` pairs from the two sums (R + G 2^32, B + A 2^32), rounding half up. */
inline uint vox_color_mean(long rg, long ba, uint n) {
  if (n == 0) return 0u;
  const unsigned long h = n / 2;
  const unsigned long r = ((unsigned long)rg & 0xffffffffUL), g = ((unsigned long)rg >> 32);
  const unsigned long b = ((unsigned long)ba & 0xffffffffUL), a = ((unsigned long)ba >> 32);
  return (uint)((r + h) / n) | ((uint)((g + h) / n) << 8) | ((uint)((b + h) / n) << 16) |
         ((uint)((a + h) / n) << 24);
}

#endif
