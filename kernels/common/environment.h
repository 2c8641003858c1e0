/* environment.h — what a ray that leaves the scene sees: an equirectangular (latitude-longitude) RGBA image,
 * read by the device (shade.cl) and the host (host/render/environment_map.h) with the same arithmetic. In
 * the C subset OpenCL C 1.2 and C++20 both accept.
 *
 * Directions are world (anchor-relative) unit vectors, y up. The image's column u in [0, 1) is the longitude
 * measured from -z towards +x (u = 0.5 + atan2(x, -z) / 2 pi: the image's centre column looks along -z, the
 * way a default camera looks); its row v in [0, 1] the polar angle from +y (v = acos(y) / pi: row 0 is
 * straight up). Texel (i, j) covers [i, i+1] x [j, j+1] / (width, height); lookups are bilinear between texel
 * centres, wrapping in u and clamping in v. A 1 x 1 image is a constant environment. */
#ifndef VOXR_ENVIRONMENT_H
#define VOXR_ENVIRONMENT_H

#ifdef __OPENCL_VERSION__
#define VOXR_GLOBAL __global
#define VOXR_ATAN2 atan2
#define VOXR_ACOS acos
#define VOXR_FLOOR floor
#define VOXR_SQRT sqrt
#else
#include <cmath>
#define VOXR_GLOBAL
#define VOXR_ATAN2 std::atan2
#define VOXR_ACOS std::acos
#define VOXR_FLOOR std::floor
#define VOXR_SQRT std::sqrt
#endif

#define VOXR_PI_F 3.14159265358979f

/* Texel coordinates (x in [0, width), y in [0, height]) of direction (dx, dy, dz), which need not be unit. */
inline void voxr_environment_texel(float dx, float dy, float dz, unsigned width, unsigned height, float* x,
                                   float* y) {
  const float len = VOXR_SQRT(dx * dx + dy * dy + dz * dz);
  float cy = len > 0.0f ? dy / len : 1.0f;
  cy = cy > 1.0f ? 1.0f : (cy < -1.0f ? -1.0f : cy);
  float u = 0.5f + VOXR_ATAN2(dx, -dz) / (2.0f * VOXR_PI_F);
  u = u - VOXR_FLOOR(u);
  *x = u * (float)width;
  *y = VOXR_ACOS(cy) / VOXR_PI_F * (float)height;
}

/* RGB radiance seen along (dx, dy, dz): `rgba` holds width * height texels of 4 floats, row 0 first. */
inline void voxr_environment_lookup(const VOXR_GLOBAL float* rgba, unsigned width, unsigned height, float dx,
                                    float dy, float dz, float* out_rgb) {
  float x, y;
  voxr_environment_texel(dx, dy, dz, width, height, &x, &y);
  const float fx = x - 0.5f, fy = y - 0.5f;
  const float x0f = VOXR_FLOOR(fx), y0f = VOXR_FLOOR(fy);
  const float ax = fx - x0f, ay = fy - y0f;
  const int w = (int)width, h = (int)height;
  int x0 = (int)x0f % w;
  if (x0 < 0) x0 += w;
  const int x1 = (x0 + 1) % w;
  int y0 = (int)y0f, y1 = (int)y0f + 1;
  y0 = y0 < 0 ? 0 : (y0 >= h ? h - 1 : y0);
  y1 = y1 < 0 ? 0 : (y1 >= h ? h - 1 : y1);
  const VOXR_GLOBAL float* t00 = rgba + 4 * (y0 * w + x0);
  const VOXR_GLOBAL float* t10 = rgba + 4 * (y0 * w + x1);
  const VOXR_GLOBAL float* t01 = rgba + 4 * (y1 * w + x0);
  const VOXR_GLOBAL float* t11 = rgba + 4 * (y1 * w + x1);
  for (int c = 0; c < 3; ++c) {
    const float top = t00[c] + ax * (t10[c] - t00[c]);
    const float bottom = t01[c] + ax * (t11[c] - t01[c]);
    out_rgb[c] = top + ay * (bottom - top);
  }
}

#endif
