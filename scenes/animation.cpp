// Sampling keyframe tracks at time t (glTF spec Sec. 3.11.2 "Animation samplers").
#include "scenes/animation.h"

#include <algorithm>

namespace rtdr {

KeySpan find_key_span(const std::vector<float>& times, double t) {
  const int n = int(times.size());
  // "!(t >= first)" rather than "t < first": a NaN time holds the first key instead of reading past the last.
  if (n == 0 || !(t >= times.front())) return {-1, 0.0f};
  if (t >= times.back()) return {n - 1, 0.0f};
  // First key strictly after t; the span starts one before it. A t just below the last key can round up to
  // it as a float, where upper_bound finds no key after it: the span is then the last one.
  const int k1 = std::min(n - 1, int(std::upper_bound(times.begin(), times.end(), float(t)) - times.begin()));
  const int k0 = k1 - 1;
  const double u = (t - times[k0]) / double(times[k1] - times[k0]);
  return {k0, float(std::clamp(u, 0.0, 1.0))};
}

namespace {

template <class T>
T sample_track(const Track<T>& track, double t, T (*lerp)(const T&, const T&, float)) {
  const KeySpan s = find_key_span(track.times, t);
  if (s.k < 0) return track.values.front();                        // before the first key: hold it
  if (s.k + 1 >= int(track.values.size())) return track.values.back();  // at or after the last key
  if (track.interpolation == Interpolation::Step || s.u == 0.0f) return track.values[s.k];
  return lerp(track.values[s.k], track.values[s.k + 1], s.u);
}

float lerp_float(const float& a, const float& b, float u) { return a + (b - a) * u; }
glm::vec3 lerp_vec3(const glm::vec3& a, const glm::vec3& b, float u) { return a + (b - a) * u; }

// Spherical linear interpolation along the shorter arc: q and -q are the same rotation, so flip b
// when the quaternions point into opposite hemispheres (glTF spec, Appendix C "Spherical Linear
// Interpolation"). Falls back to normalised lerp when they are nearly parallel.
glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b_in, float u) {
  glm::quat b = b_in;
  float cos_theta = glm::dot(a, b);
  if (cos_theta < 0.0f) {
    b = -b;
    cos_theta = -cos_theta;
  }
  if (cos_theta > 0.9995f) return glm::normalize(a * (1.0f - u) + b * u);
  const float theta = std::acos(cos_theta);
  const float sin_theta = std::sin(theta);
  const float wa = std::sin((1.0f - u) * theta) / sin_theta;
  const float wb = std::sin(u * theta) / sin_theta;
  return glm::normalize(a * wa + b * wb);
}

}  // namespace

template <>
float Track<float>::sample(double t) const { return sample_track(*this, t, &lerp_float); }
template <>
glm::vec3 Track<glm::vec3>::sample(double t) const { return sample_track(*this, t, &lerp_vec3); }
template <>
glm::quat Track<glm::quat>::sample(double t) const { return sample_track(*this, t, &slerp_shortest); }

}  // namespace rtdr
