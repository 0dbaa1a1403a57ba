// The noise-free shading term of TRMV: direct light at the primary hit x_0 without visibility [TRMV21 Sec. 4.3].
//
// Pass: direct_shading(context, G, eye, seed, samples) -> S(x_0, wo), per pixel, before demodulation.
//   in:  the frame's lights and materials (TraceContext), the primary surface sample G, the eye, the pixel seed
//   out: S = int_A Le(y) f(wo, wi) cos(theta_x) cos(theta_y) / |y - x|^2 dA(y), the whole unshadowed direct
//        integral over every emitter's emitting faces (its front, or both when doubleSided), wi = unit(y - x): no visibility V(x, y), no MIS weight
//
// TRMV splits the output into shading (direct illumination without shadows), visibility, glossy and other
// indirect light [TRMV21 Sec. 4], filters the noisy ones, and assumes that the shading part "can already be
// reasonably approximated in a noise-free way", by Linearly Transformed Cosines [TRMV21 Sec. 4.3, HDHN16].
// Ours is a Monte Carlo stand-in for LTC, exact in expectation for our own BRDF (LTC only fits it): M points on
// the lights, chosen as next-event estimation chooses them (a light by power, a point uniform on its area,
// trace/lights.h), and no ray at all, so M can be large:
//   S ~ (1 / M) sum_j Le f(wo, wi_j) cos(theta_x) cos(theta_y) / (|y_j - x|^2 p_A(y_j)),
// p_A = the light's choice probability / its area. Directions below the geometric surface count 0, as in the
// path's next-event estimation (a shadow ray can never leave that way).
//
// Random numbers. Sample j of a pixel with seed s is the point j of the sequence under the seed
// hash_combine(s, kShadingStream), one 2D point of its first dimension pair: its first coordinate chooses the
// light and, rescaled within that light's share, places the point with the second (LightSet::sample_reusing).
// The path's numbers come from the seed s itself (core/sampler.h), so the two sequences are independent,
// and computing S changes no bit of any other layer. With M a power of 2 the M points form a (0, log2 M, 2)-net,
// so a light whose share of the power is a power of 1/2 gets a net of its own: far smoother than M
// independent points.
//
// Per pixel, not per path: render_frame.cpp calls it once per pixel, with M ceil(sqrt(N)) samples for an N-spp
// frame (shading_sample_count), the indices 0 .. M ceil(sqrt(N)) - 1 of one sequence; so a reference's S is the
// same estimator with more samples, and its first M are the 1-spp frame's. Why sqrt(N) and not N: a path layer's
// error falls like N^-1/2, and the net's error at least like 1 / samples on a smooth integrand (sigma_1 / sigma_64
// = 72 to 256 at the points of tests/trace_shading_test.cpp: M^-1.0 to M^-1.3), so S's error keeps falling at
// least as fast as the paths' while it starts 70 to 250 times below one light sample's. M N samples would make
// a reference several times slower (S costs more than a 1-spp path: trace/README.md), for precision nobody sees.
//
// Recombination (trace/README.md): direct ~ S * Vbar, Vbar the filtered visibility. S already holds the whole
// unshadowed integral, the part `direct` gets from its BSDF ray included, so S * Vbar replaces `direct`; adding
// `direct`'s BSDF-hit emission to it would count that light twice.
#pragma once

#include "raster/surface.h"
#include "trace/lights.h"
#include "trace/path_tracer.h"
#include "core/sampler.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace rtdr {

// The tag that gives the shading term its own sequence: hash_combine(pixel seed, kShadingStream) is its seed. Any
// fixed value serves; this one is the ASCII bytes of "shad".
inline constexpr uint32_t kShadingStream = 0x73686164U;

// The estimator above, for any reflectance: f(wi) returns the BRDF value f(wo, wi) (rgb, without the cosine)
// for a unit incident direction wi. `x` needs only its position, shading normal and geometric normal. The
// tests pass a Lambertian f through the very same code to compare with Lambert's polygon formula.
template <class Reflectance>
glm::vec3 unshadowed_direct(const LightSet& lights, const SurfacePoint& x, uint32_t shading_seed, uint32_t samples,
                            const Reflectance& f) {
  if (lights.empty() || samples == 0) return glm::vec3(0.0f);
  const SamplePair pair(shading_seed, 0);
  glm::dvec3 sum(0.0);  // double: a reference sums up to 2^30 terms
  for (uint32_t j = 0; j < samples; ++j) {
    const LightSample ls = lights.sample_reusing(pair.at(j));
    const glm::vec3 d = ls.position - x.position;
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > 0.0f) || !(ls.pdf_area > 0.0f)) continue;
    const glm::vec3 wi = d / std::sqrt(dist2);
    const float cos_light = ls.emitted_cosine(-wi);  // 0 or less behind a one-sided emitter (trace/lights.h)
    const float cos_surface = glm::dot(x.normal, wi);
    if (!(cos_light > 0.0f) || !(cos_surface > 0.0f) || !(glm::dot(x.geo_normal, wi) > 0.0f)) continue;
    // Le f cos(theta_x) cos(theta_y) / (r^2 p_A): the area form of the light integral [TRMV21 Sec. 4.3].
    sum += glm::dvec3(f(wi) * ls.radiance * (cos_surface * cos_light / (dist2 * ls.pdf_area)));
  }
  return glm::vec3(sum / double(samples));
}

// The samples of one pixel's S in an N-spp frame: M ceil(sqrt(N)), M = TraceOptions::shading_samples (see above).
uint32_t shading_sample_count(int shading_samples, int spp);

// S at the primary surface sample G seen from `eye`, with the path's BSDF at x_0 (trace_path's, unregularized),
// from `samples` light samples under the pixel seed `seed`. 0 where the frame has no lights.
glm::vec3 direct_shading(const TraceContext& context, const SurfaceSample& primary, const glm::vec3& eye, uint32_t seed,
                         uint32_t samples);

}  // namespace rtdr
