// The path tracer f(G, seed). The path, the MIS rule and the outputs are described in path_tracer.h.
#include "trace/path_tracer.h"

#include "core/color.h"
#include "trace/brdf.h"
#include "core/sampler.h"

#include <algorithm>
#include <cmath>

namespace rtdr {
namespace {

// The power heuristic with beta = 2 (Veach 1997, Eq. 9.13): the weight of a sample drawn with density
// pdf_this when another strategy could have drawn it with density pdf_other.
float power_heuristic(float pdf_this, float pdf_other) {
  const float a = pdf_this * pdf_this, b = pdf_other * pdf_other;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// Where a ray leaving surface p in direction `dir` starts: nudged off the surface along the geometric
// normal, on the side the ray goes, by an amount that grows with the coordinates' magnitude (float
// spacing), so the ray does not hit the triangle it leaves.
glm::vec3 offset_origin(const SurfacePoint& p, const glm::vec3& dir) {
  const glm::vec3 a = glm::abs(p.position);
  const float scale = 1e-4f * (1.0f + std::max({a.x, a.y, a.z}));
  return p.position + p.geo_normal * (glm::dot(dir, p.geo_normal) >= 0.0f ? scale : -scale);
}

// The BSDF of a surface seen from wo, with glossy lobes regularized to at least `min_roughness`.
Bsdf bsdf_of(const SurfacePoint& p, const glm::vec3& wo, float min_roughness) {
  return Bsdf({p.albedo, std::max(p.roughness, min_roughness), p.metallic}, p.normal, wo);
}

// Next-event estimation at one vertex: one light sample and its shadow ray.
struct LightConnection {
  glm::vec3 unshadowed{0.0f};         // f cos Le w / p, without visibility
  bool visible = false;
  glm::vec3 light_position{0.0f};
  uint32_t light_instance = kInvalidId;
  glm::vec3 blocker_position{0.0f};
  uint32_t blocker_instance = kInvalidId;
};

LightConnection connect_to_light(const TraceContext& c, const SurfacePoint& x, const Bsdf& bsdf, float u_select,
                                 glm::vec2 u_point, bool use_mis, bool find_blocker, uint32_t& rays) {
  LightConnection out;
  if (c.lights.empty()) return out;
  const LightSample ls = c.lights.sample(u_select, u_point);
  out.light_position = ls.position;
  out.light_instance = c.lights.lights()[size_t(ls.light)].instance;

  const glm::vec3 to_light = ls.position - x.position;
  const float dist2 = glm::dot(to_light, to_light);
  const glm::vec3 wi = to_light / std::sqrt(dist2);
  const float cos_light = ls.emitted_cosine(-wi);  // 0 or less behind a one-sided emitter (trace/lights.h)
  const float cos_surface = glm::dot(x.normal, wi);
  if (cos_light <= 0.0f || cos_surface <= 0.0f || glm::dot(x.geo_normal, wi) <= 0.0f || ls.pdf_area <= 0.0f)
    return out;

  // Area density to solid angle: p_omega = p_A r^2 / cos(theta_light) (pbrt-v4 Eq. 4.9).
  const float pdf_light = ls.pdf_area * dist2 / cos_light;
  const BsdfEval e = bsdf.evaluate(wi);
  const float w = use_mis ? power_heuristic(pdf_light, e.pdf) : 1.0f;
  out.unshadowed = e.f.total() * cos_surface * ls.radiance * (w / pdf_light);

  // The shadow ray, from just off the surface to just short of the light point.
  const glm::vec3 origin = offset_origin(x, wi);
  const glm::vec3 span = ls.position - origin;
  const float length = glm::length(span);
  const Ray ray{origin, span / length};
  const float tfar = length * (1.0f - 1e-4f);
  ++rays;
  if (c.ray_log) c.ray_log->push_back({ray, tfar, !find_blocker});
  if (find_blocker) {  // the nearest blocker is part of the path record [TRMV21 Sec. 4.1]
    const Hit blocker = c.embree.intersect(ray, 0.0f, tfar);
    out.visible = blocker.instance == kInvalidId;
    if (!out.visible) {
      out.blocker_instance = blocker.instance;
      out.blocker_position = ray.origin + blocker.t * ray.direction;
    }
  } else {
    out.visible = !c.embree.occluded(ray, 0.0f, tfar);
  }
  return out;
}

// Emitted radiance picked up when a BSDF-sampled ray from x (density pdf_bsdf) hits surface y, weighted
// against light sampling, which could have chosen the same point.
glm::vec3 emission_hit(const TraceContext& c, const SurfacePoint& x, const SurfacePoint& y, const Hit& hit,
                       float pdf_bsdf) {
  // Not an emitter, or the back of a single-sided one (raster/surface.h); a double-sided one emits from both.
  if (luminance(y.emission) <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 d = y.position - x.position;
  const float cos_light = std::abs(glm::dot(y.geo_normal, glm::normalize(d)));
  const float pdf_light = cos_light > 0.0f ? c.lights.pdf_area(hit.instance, hit.triangle) * glm::dot(d, d) / cos_light : 0.0f;
  return y.emission * power_heuristic(pdf_bsdf, pdf_light);
}

}  // namespace

// One path from the primary hit [SVGF17 Sec. 3]; all its random numbers come from (seed, sample_index), so
// re-shading the same G with the same seed is bit-identical [ASVGF18 Sec. 3.2, ASVGF18 Eq. 6].
PathSample trace_path(const TraceContext& c, const SurfaceSample& primary, const glm::vec3& eye, uint32_t seed,
                      uint32_t sample_index) {
  PathSample out;
  Sampler sampler(seed, sample_index);
  const int last = std::max(0, c.options.max_bounces);
  SurfacePoint x = c.surfaces.at(primary, eye);
  out.albedo = x.albedo;
  glm::vec3 wo = glm::normalize(eye - x.position);

  glm::vec3 incoming(0.0f);    // radiance arriving at x_0 along its BSDF ray, from x_1 on (the indirect light)
  glm::vec3 beta(1.0f);        // throughput from x_1 to the current vertex
  BsdfValue weight0;           // x_0's f cos / p, per lobe: splits `incoming` into diffuse and glossy
  for (int k = 0; k <= last; ++k) {
    const Bsdf bsdf = bsdf_of(x, wo, k == 0 ? 0.0f : c.options.regularized_roughness);
    // The vertex's random numbers, always drawn in this order: (light choice, lobe choice), the light point,
    // the BSDF direction. So the dimensions a sample uses never depend on the scene.
    const glm::vec2 u_choices = sampler.next_2d();
    const glm::vec2 u_light_point = sampler.next_2d();
    // Next-event estimation; MIS only where a BSDF ray follows (not at the last vertex).
    const LightConnection nee = connect_to_light(c, x, bsdf, u_choices.x, u_light_point, k < last, k == 0, out.rays);
    if (k == 0) {
      out.direct_unshadowed = nee.unshadowed;
      out.direct_visibility = nee.visible ? 1.0f : 0.0f;
      out.direct += nee.visible ? nee.unshadowed : glm::vec3(0.0f);
      out.record.light_position = nee.light_position;
      out.record.light_instance = nee.light_instance;
      out.record.blocker_position = nee.blocker_position;
      out.record.blocker_instance = nee.blocker_instance;
    } else if (nee.visible) {
      incoming += beta * nee.unshadowed;
    }
    if (k == last) break;

    // One BSDF-sampled ray to the next vertex.
    const BsdfSample bs = bsdf.sample(u_choices.y, sampler.next_2d());
    if (bs.pdf <= 0.0f || glm::dot(x.geo_normal, bs.wi) <= 0.0f) break;  // absorbed, or below the surface
    const BsdfValue& f = bs.f;
    const float cos_theta = glm::dot(x.normal, bs.wi);
    const glm::vec3 weight = f.total() * (cos_theta / bs.pdf);
    const Ray ray{offset_origin(x, bs.wi), bs.wi};
    const Hit hit = c.embree.intersect(ray);
    ++out.rays;
    if (c.ray_log) c.ray_log->push_back({ray, kRayInfinity, false});
    if (k == 0) out.record.secondary_direction = bs.wi, out.record.secondary_pdf = bs.pdf;
    if (hit.instance == kInvalidId) break;  // escaped: there is no environment light
    const SurfacePoint y = c.surfaces.at({hit.instance, hit.triangle, hit.bary}, x.position);
    const glm::vec3 emitted = emission_hit(c, x, y, hit, bs.pdf);
    if (k == 0) {
      out.record.secondary_position = y.position;
      out.record.secondary_instance = hit.instance;
      out.direct += weight * emitted;
      weight0 = {f.diffuse * (cos_theta / bs.pdf), f.specular * (cos_theta / bs.pdf)};
    } else {
      incoming += beta * weight * emitted;
      beta *= weight;
    }
    x = y;
    wo = -bs.wi;
  }
  out.record.secondary_incoming = incoming;
  out.indirect_diffuse = weight0.diffuse * incoming;
  out.indirect_glossy = weight0.specular * incoming;
  out.indirect = out.indirect_diffuse + out.indirect_glossy;
  return out;
}

}  // namespace rtdr
