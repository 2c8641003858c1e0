/* shading.h — the one shading model, read by the device (kernels/render/shade.cl) and the Embree reference
 * (host/reference) alike, so their images differ only where shadows (later: refraction) differ. Written in
 * the C subset OpenCL C 1.2 and C++20 both accept, one colour channel at a time.
 *
 *   opaque, sheet:  L = albedo * (ambient + E * max(0, n . l) * T)
 *                   E: irradiance from the light at the point (point light: intensity / d^2; directional:
 *                   intensity), n: shading normal turned towards the viewer, l: unit vector to the light,
 *                   T: transmittance from the point to the light (the shadow method's answer, RGB).
 *                   Sheets are two-sided: lit only from the side the viewer sees.
 *   dielectric:     flat until refraction is rendered: L = ambient * exp(-sigma_a * 1 world unit).
 *   no surface:     L = ambient (the environment colour). */
#ifndef VOXR_SHADING_H
#define VOXR_SHADING_H

#ifdef __OPENCL_VERSION__
#define VOXR_EXP exp
#else
#include <cmath>
#define VOXR_EXP std::exp
#endif

/* One channel of a lit opaque or sheet surface. cos_theta = n . l, may be negative. */
inline float voxr_shade_surface(float albedo, float ambient, float irradiance, float cos_theta,
                                float transmittance) {
  const float lit = cos_theta > 0.0f ? irradiance * cos_theta * transmittance : 0.0f;
  return albedo * (ambient + lit);
}

/* One channel of a dielectric surface while refraction is not rendered. */
inline float voxr_shade_dielectric_flat(float ambient, float absorption) {
  return ambient * VOXR_EXP(-absorption);
}

#endif
