/* refraction.h — the interface optics every refraction method and the Embree reference share, so that the
 * matched reference differs from the voxel methods only by their discretisation. Scalar functions in the C
 * subset OpenCL C 1.2 and C++20 both accept.
 *
 * The path model (RefractionPath in voxr_layout.h; DESIGN.md "Materials and the reference"):
 *   - At the first dielectric surface the camera ray meets, Schlick's F (Schlick 1994) weights one mirror
 *     lookup of the environment; the refracted ray carries 1 - F.
 *   - Every later refraction (Snell's law, n1 sin t1 = n2 sin t2) multiplies the path by 1 - F (Schlick).
 *   - Total internal reflection (n1 sin t1 > n2) mirrors the ray and costs nothing.
 *   - Inside a dielectric the path is attenuated by Beer-Lambert, exp(-sigma_a * length), per channel.
 *   - A sheet crossed multiplies by its transmittance; an opaque surface ends the path (shaded there, with
 * its transparent shadow); leaving the scene ends it in the environment; VOXR_PATH_MAX_EVENTS interfaces end
 *     it with nothing (VOXR_PATH_LOST).
 * Media are entered and left by the surfaces' winding and counted per material (media_stack.h): a solid
 * nested in another of the same material is no interface; nested media of different materials form a
 * stack. */
#ifndef VOXR_REFRACTION_H
#define VOXR_REFRACTION_H

#ifdef __OPENCL_VERSION__
#define VOXR_RSQRT_ARG(x) sqrt(x)
#else
#include <cmath>
#define VOXR_RSQRT_ARG(x) std::sqrt(x)
#endif

/* cos of the transmitted angle for incidence cos_i (>= 0) from index n1 into n2, or -1 on total internal
 * reflection. */
inline float voxr_refracted_cos(float cos_i, float n1, float n2) {
  const float eta = n1 / n2;
  const float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  return sin2_t >= 1.0f ? -1.0f : VOXR_RSQRT_ARG(1.0f - sin2_t);
}

/* Schlick's approximation of the Fresnel reflectance, incidence cos_i (>= 0) from n1 into n2: F0 + (1 - F0)
 * (1 - c)^5 with F0 = ((n1 - n2) / (n1 + n2))^2 and c the cosine on the less dense side (the transmitted one
 * when n1 > n2); 1 on total internal reflection. At normal incidence it is exact. */
inline float voxr_schlick(float cos_i, float n1, float n2) {
  if (n1 == n2) return 0.0f; /* index-matched: no interface to reflect at (the formula's (1 - c)^5 is not 0) */
  const float r = (n1 - n2) / (n1 + n2);
  const float f0 = r * r;
  float c = cos_i;
  if (n1 > n2) {
    c = voxr_refracted_cos(cos_i, n1, n2);
    if (c < 0.0f) return 1.0f;
  }
  const float m = 1.0f - c;
  return f0 + (1.0f - f0) * m * m * m * m * m;
}

/* The exact Fresnel reflectance of unpolarized light (the full reference): the mean of the s and p
 * reflectances; 1 on total internal reflection. */
inline float voxr_fresnel_exact(float cos_i, float n1, float n2) {
  const float cos_t = voxr_refracted_cos(cos_i, n1, n2);
  if (cos_t < 0.0f) return 1.0f;
  const float rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const float rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
  return 0.5f * (rs * rs + rp * rp);
}

#endif
