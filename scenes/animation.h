// Keyframe tracks, sampled at any time t, as glTF 2.0 defines them (glTF spec Sec. 3.11 "Animations").
//
// A track holds strictly increasing key times and one value per key. Before the first key it holds the
// first value, after the last key the last value. LINEAR interpolates componentwise, except rotations,
// which use spherical linear interpolation along the shorter arc (the glTF spec's slerp); STEP holds the
// value of the last key at or before t. CUBICSPLINE is rejected by the loader with a clear error.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace rtdr {

enum class Interpolation { Step, Linear };

template <class T>
struct Track {
  std::vector<float> times;  // seconds, strictly increasing
  std::vector<T> values;     // one per key
  Interpolation interpolation = Interpolation::Linear;

  bool empty() const { return times.empty(); }
  T sample(double t) const;  // defined for float, glm::vec3 and glm::quat in animation.cpp
};

// The key interval for time t: keys[k] <= t < keys[k+1], and the fraction u in [0, 1) within it.
// Returns k = -1 before the first key and k = last index at or after the last key (u = 0 in both).
struct KeySpan {
  int k;
  float u;
};
KeySpan find_key_span(const std::vector<float>& times, double t);

}  // namespace rtdr
