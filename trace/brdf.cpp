// glTF metallic-roughness BRDF: evaluation, pdf and importance sampling. Formulas in brdf.h.
#include "trace/brdf.h"

#include "trace/ggx_albedo_table.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rtdr {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

glm::vec3 f0_of(const SurfaceBsdf& m) { return glm::mix(glm::vec3(0.04f), m.base_color, m.metallic); }

// Cosine-weighted direction around +Z (Malley's method: uniform disk, lifted to the hemisphere).
glm::vec3 sample_cosine_hemisphere(glm::vec2 u) {
  const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}

// A GGX visible normal around +Z for the view direction v (in the local frame), Heitz 2018, Sec. 2:
// stretch v to the hemisphere configuration, sample the projected disk, unstretch.
glm::vec3 sample_ggx_visible_normal(const glm::vec3& v, float alpha, glm::vec2 u) {
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z));
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 = len2 > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : glm::vec3(1, 0, 0);
  const glm::vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

}  // namespace

float ggx_d(float cos_theta_h, float alpha) {
  if (cos_theta_h <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float c2 = cos_theta_h * cos_theta_h;
  const float denom = c2 * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * denom * denom);
}

float ggx_lambda(float cos_theta, float alpha) {
  const float c2 = std::max(cos_theta * cos_theta, 1e-12f);
  const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

glm::vec3 fresnel_schlick(glm::vec3 f0, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m5 = (m * m) * (m * m) * m;
  return f0 + (glm::vec3(1.0f) - f0) * m5;
}

float dielectric_specular_albedo(float roughness, float mu) {
  using namespace ggx_albedo_table;
  // Bilinear between the table's entries: roughness i / (kRoughnessCount - 1), sqrt(mu) j / (kMuCount - 1)
  // (the entries crowd towards grazing angles, where a smooth lobe's albedo changes fastest).
  const float x = std::clamp(roughness, 0.0f, 1.0f) * float(kRoughnessCount - 1);
  const float y = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * float(kMuCount - 1);
  const int i = std::min(int(x), kRoughnessCount - 2), j = std::min(int(y), kMuCount - 2);
  const float s = x - float(i), t = y - float(j);
  const float lower = (1.0f - t) * kSpecularAlbedo[i][j] + t * kSpecularAlbedo[i][j + 1];
  const float upper = (1.0f - t) * kSpecularAlbedo[i + 1][j] + t * kSpecularAlbedo[i + 1][j + 1];
  return (1.0f - s) * lower + s * upper;
}

float dielectric_specular_albedo_average(float roughness) {
  using namespace ggx_albedo_table;
  // Linear in roughness, like the table: the average of the bilinear table is exactly this (the generator
  // integrates each row as the lookup above interpolates it).
  const float x = std::clamp(roughness, 0.0f, 1.0f) * float(kRoughnessCount - 1);
  const int i = std::min(int(x), kRoughnessCount - 2);
  const float s = x - float(i);
  return (1.0f - s) * kAverageAlbedo[i] + s * kAverageAlbedo[i + 1];
}

Bsdf::Bsdf(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo)
    : m_(m), n_(n), wo_(wo), f0_(f0_of(m)), n_dot_v_(glm::dot(n, wo)), alpha_(ggx_alpha(m.roughness)) {
  orthonormal_basis(n, t_, b_);
  lambda_v_ = ggx_lambda(n_dot_v_, alpha_);
  // The lobe choice: proportional to the Fresnel reflectance at n.v against the diffuse weight, never below
  // 10% for either lobe so neither is starved of samples; metals have no diffuse lobe.
  const float spec = luminance(fresnel_schlick(f0_, std::max(0.0f, n_dot_v_)));
  const float diff = (1.0f - m.metallic) * luminance(m.base_color);
  p_spec_ = (m.metallic >= 1.0f || diff <= 0.0f) ? 1.0f : std::clamp(spec / (spec + diff), 0.1f, 0.9f);
  // Albedo scaling [Kelemen and Szirmay-Kalos 2001; Kulla and Conty 2017]: the outgoing half of the diffuse
  // weight, (1 - E_spec(n.v)) / (1 - E_avg); evaluate() multiplies by the incoming half, 1 - E_spec(n.l).
  const float e_v = dielectric_specular_albedo(m.roughness, std::max(0.0f, n_dot_v_));
  const float e_avg = dielectric_specular_albedo_average(m.roughness);
  diffuse_v_ = (1.0f - m.metallic) * m.base_color * ((1.0f - e_v) / (kPi * (1.0f - e_avg)));
}

BsdfEval Bsdf::evaluate(const glm::vec3& wi) const {
  const float n_dot_l = glm::dot(n_, wi);
  if (n_dot_v_ <= 0.0f || n_dot_l <= 0.0f) return {};
  const glm::vec3 h = glm::normalize(wo_ + wi);
  const float n_dot_h = glm::dot(n_, h);
  const glm::vec3 F = fresnel_schlick(f0_, glm::dot(wo_, h));
  const float D = ggx_d(n_dot_h, alpha_);
  // Height-correlated Smith masking-shadowing (Heitz 2014, Eq. 99).
  const float G2 = 1.0f / (1.0f + lambda_v_ + ggx_lambda(n_dot_l, alpha_));
  BsdfEval e;
  // The diffuse lobe gets what the dielectric's specular lobe does not reflect, on the way out and on the way
  // in: f_d = (1 - metallic) base / pi (1 - E_spec(n.v)) (1 - E_spec(n.l)) / (1 - E_avg), the albedo scaling
  // of Kelemen and Szirmay-Kalos 2001 (Kulla and Conty 2017). Its directional albedo is base (1 - E_spec(n.v)),
  // so the dielectric's is base + (1 - base) E_spec(n.v) <= 1. glTF's fresnel_mix (1 - F(v.h)) returns up to
  // 1.85x the incident energy at grazing angles (tests/trace_brdf_test.cpp, ENERGY), and the coupling
  // (1 - F(n.v)) (1 - F(n.l)) of Ashikhmin and Shirley 2000 that replaced it lost 10% at roughness 1 (a diffuse
  // room 11-12% darker than Cycles); see "Deviations and choices" in trace/README.md.
  e.f.diffuse = diffuse_v_ * (1.0f - dielectric_specular_albedo(m_.roughness, n_dot_l));
  e.f.specular = F * (D * G2 / (4.0f * n_dot_v_ * n_dot_l));
  // The mixture's pdf: cosine-weighted diffuse, and for the specular lobe the density of reflecting about a
  // visible normal, D_v(h) / (4 v.h) = G1(v) D(h) / (4 n.v) (Heitz 2018, Eq. 17).
  const float G1 = 1.0f / (1.0f + lambda_v_);
  e.pdf = (1.0f - p_spec_) * n_dot_l / kPi + p_spec_ * G1 * D / (4.0f * n_dot_v_);
  return e;
}

BsdfSample Bsdf::sample(float u_lobe, glm::vec2 u) const {
  BsdfSample s;
  if (n_dot_v_ <= 0.0f) return s;
  s.specular_lobe = u_lobe < p_spec_;
  if (s.specular_lobe) {
    // Reflect the view direction about a sampled visible microfacet normal.
    const glm::vec3 wo_local(glm::dot(wo_, t_), glm::dot(wo_, b_), n_dot_v_);
    const glm::vec3 h_local = sample_ggx_visible_normal(wo_local, alpha_, u);
    const glm::vec3 h = h_local.x * t_ + h_local.y * b_ + h_local.z * n_;
    s.wi = glm::reflect(-wo_, h);
  } else {
    const glm::vec3 d = sample_cosine_hemisphere(u);
    s.wi = d.x * t_ + d.y * b_ + d.z * n_;
  }
  s.wi = glm::normalize(s.wi);
  const BsdfEval e = evaluate(s.wi);  // pdf 0 when a specular sample went below the surface
  s.pdf = e.pdf;
  s.f = e.f;
  return s;
}

BsdfValue bsdf_eval(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi) {
  return Bsdf(m, n, wo).evaluate(wi).f;
}

float specular_lobe_probability(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo) {
  return Bsdf(m, n, wo).specular_probability();
}

float bsdf_pdf(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi) {
  return Bsdf(m, n, wo).evaluate(wi).pdf;
}

BsdfSample bsdf_sample(const SurfaceBsdf& m, const glm::vec3& n, const glm::vec3& wo, float u_lobe, glm::vec2 u) {
  return Bsdf(m, n, wo).sample(u_lobe, u);
}

}  // namespace rtdr
