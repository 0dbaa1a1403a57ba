// The surface reflectance model: glTF 2.0 metallic-roughness (glTF spec Appendix B), a Lambertian
// diffuse lobe and a GGX (Trowbridge-Reitz) specular lobe with the height-correlated Smith masking-
// shadowing term and Schlick's Fresnel.
//
//   f = f_diffuse + f_specular
//   f_diffuse  = (1 - metallic) base / pi (1 - E_spec(n.v)) (1 - E_spec(n.l)) / (1 - E_avg)   (albedo scaling)
//   f_specular = F(v.h) D(h) G2(v, l) / (4 |n.v| |n.l|),  F0 = mix(0.04, base, metallic),  alpha = roughness^2
//
// The diffuse lobe is scaled by what the dielectric's specular lobe (F0 = 0.04) does not reflect: E_spec(mu)
// is that lobe's directional albedo, E_avg = 2 int_0^1 E_spec(mu) mu dmu its cosine-weighted average, both from
// a table (trace/ggx_albedo_table.h, made by tools/make_ggx_albedo_table.py). This is the albedo scaling of
// Kelemen and Szirmay-Kalos 2001 ("A Microfacet Based Coupled Specular-Matte BRDF Model with Importance
// Sampling", its matte term) as Kulla and Conty 2017 ("Revisiting Physically Based Shading at Imageworks",
// the albedo-scaling layering of a diffuse base under a specular coat) use it: reciprocal, since it is
// symmetric in n.v and n.l, and the dielectric's directional albedo is exactly
//   E(mu_o) = E_spec(mu_o) + base (1 - E_spec(mu_o)) = base + (1 - base) E_spec(mu_o)   (metallic 0),
// at most 1, and equal to base wherever the specular lobe reflects little. Why and what differs from glTF and
// Cycles: trace/README.md, "Deviations and choices".
//
// The two lobes are kept apart (eval returns both) so the path tracer can split diffuse from glossy
// light exactly, as the motion-vector work of [TRMV21 Sec. 4] needs. Directions point away from the
// surface; n is the shading normal; every vector is unit length and in the same space.
#pragma once

#include "core/geometry.h"
#include "scenes/scene.h"

#include <glm/glm.hpp>

namespace rtdr {

struct SurfaceBsdf {
  glm::vec3 base_color{1.0f};
  float roughness = 1.0f;
  float metallic = 0.0f;
};

struct BsdfValue {
  glm::vec3 diffuse{0.0f};   // f_diffuse, without the cosine
  glm::vec3 specular{0.0f};  // f_specular, without the cosine
  glm::vec3 total() const { return diffuse + specular; }
};

// f and the mixture's pdf for one direction pair.
struct BsdfEval {
  BsdfValue f;
  float pdf = 0.0f;  // solid angle, of the whole two-lobe mixture
};

struct BsdfSample {
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;            // of the whole mixture, solid angle; 0 means no sample
  bool specular_lobe = false;  // which lobe generated it (the pdf is the mixture's either way)
  BsdfValue f;                 // f(wo, wi), so the caller need not evaluate again
};

// ggx_alpha(roughness) and kMinGgxAlpha, the lobe's width from the material's roughness: scenes/scene.h.
// GGX normal distribution D(h) for cos_theta_h = n.h (Walter et al. 2007, Eq. 33).
float ggx_d(float cos_theta_h, float alpha);
// Smith Lambda for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function", Eq. 72).
float ggx_lambda(float cos_theta, float alpha);
// Schlick's Fresnel approximation.
glm::vec3 fresnel_schlick(glm::vec3 f0, float cos_theta);
// E_spec(roughness, mu): the directional albedo of the dielectric's specular lobe (F0 = 0.04) seen at n.v = mu,
// bilinear in (roughness, sqrt(mu)) between the entries of trace/ggx_albedo_table.h (each clamped to [0, 1]);
// within 2e-4 of the lobe's albedo at roughness >= 0.1 (tests/trace_brdf_test.cpp), and never below it by more
// than the quadrature's error near grazing angles (tools/make_ggx_albedo_table.py).
float dielectric_specular_albedo(float roughness, float mu);
// E_avg(roughness) = 2 int_0^1 E_spec(roughness, mu) mu dmu, of the same (piecewise-linear) table.
float dielectric_specular_albedo_average(float roughness);

// The BSDF at one shading point for one outgoing direction wo: everything that depends only on the
// material, n and wo (the tangent frame, alpha, F0, Lambda(wo), the lobe choice) is computed once, as pbrt's
// BSDF objects do, and shared by every evaluation and sample at that vertex.
class Bsdf {
 public:
  Bsdf(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo);

  // f and pdf for the incident direction wi (0 for directions below the surface or when wo is).
  BsdfEval evaluate(const glm::vec3& wi) const;
  // u_lobe picks the lobe; u picks the direction (cosine-weighted hemisphere, or GGX visible normals,
  // Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)).
  BsdfSample sample(float u_lobe, glm::vec2 u) const;
  // Probability of choosing the specular lobe, from the Fresnel reflectance at n.v.
  float specular_probability() const { return p_spec_; }

 private:
  SurfaceBsdf m_;
  glm::vec3 n_, wo_, t_, b_;  // shading normal, outgoing direction, tangent frame
  glm::vec3 f0_;
  float n_dot_v_, alpha_, lambda_v_, p_spec_;
  glm::vec3 diffuse_v_;  // (1 - metallic) base / pi (1 - E_spec(n.v)) / (1 - E_avg): f_diffuse without the n.l factor
};

// One-shot forms of the above, for tests and single queries.
BsdfValue bsdf_eval(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi);
float specular_lobe_probability(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo);
float bsdf_pdf(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi);
BsdfSample bsdf_sample(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo, float u_lobe, glm::vec2 u);

// The tangent frame around n: orthonormal_basis, core/geometry.h.

}  // namespace rtdr
