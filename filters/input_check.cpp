// What a method requires of each input frame. See input_check.h.
#include "filters/input_check.h"

#include "filters/asvgf/gradient_image.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rtdr {
namespace {

// A channel's problem: of the other type, or (a float) holding NaN or infinity; "" when it has none.
std::string channel_problem(const Frame& frame, const std::string& name, bool want_float) {
  const bool is_float = frame.float_channels().count(name) > 0;
  if (is_float != want_float)
    return "channel '" + name + "' is stored as " + (is_float ? "float" : "uint") + ", but the method reads it as " +
           (want_float ? "float" : "uint");
  if (!want_float) return "";
  const FloatPlane& plane = frame.float_channel(name);
  size_t bad = 0, first_bad = 0;
  for (size_t i = 0; i < plane.data.size(); ++i)
    if (!std::isfinite(plane.data[i]) && bad++ == 0) first_bad = i;
  if (!bad) return "";
  const float v = plane.data[first_bad];
  return "channel '" + name + "' holds NaN or infinity at " + std::to_string(bad) + " pixels, the first at (" +
         std::to_string(first_bad % size_t(plane.width)) + ", " + std::to_string(first_bad / size_t(plane.width)) +
         "): " + (std::isnan(v) ? "NaN" : v > 0.0f ? "+Inf" : "-Inf");
}

// The layers that lack channels the method reads, grouped by layer (the name before the last '.', as
// docs/buffers.md names layers), each once.
std::vector<std::string> missing_layers(const Frame& frame, const InputChannels& channels) {
  std::vector<std::pair<std::string, std::vector<std::string>>> missing;  // layer, its missing channels, in order
  const auto note = [&](const std::string& name) {
    if (frame.has(name) || channels.defaults.count(name)) return;  // present, or left out with its default
    const std::string layer = name.substr(0, name.rfind('.'));
    if (missing.empty() || missing.back().first != layer) missing.push_back({layer, {}});
    missing.back().second.push_back(name);
  };
  for (const std::string& name : channels.floats) note(name);
  for (const std::string& name : channels.uints) note(name);
  std::vector<std::string> problems;
  for (const auto& [layer, names] : missing) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    bool partly = false;  // some channel of the layer is there
    for (const auto& [n, plane] : frame.float_channels()) partly = partly || n.rfind(layer + ".", 0) == 0;
    for (const auto& [n, plane] : frame.uint_channels()) partly = partly || n.rfind(layer + ".", 0) == 0;
    // For a layer `rtdr render` writes only when asked, the flag that writes it (filters/method.h missing_layer_fix).
    const std::string fix = missing_layer_fix(layer);
    problems.push_back((partly ? "layer '" + layer + "' lacks " + list : "missing layer '" + layer + "' (" + list + ")") +
                       (fix.empty() ? "" : ": " + fix));
  }
  return problems;
}

}  // namespace

std::vector<std::string> gradient_strata_problems(const UIntPlane& source, int s) {
  if (s < 1 || source.width < 1) return {};
  const int strata_x = (source.width + s - 1) / s, strata_y = (source.height + s - 1) / s;
  std::vector<glm::ivec2> first(size_t(strata_x) * size_t(strata_y), glm::ivec2(-1));  // each stratum's first sample
  std::string problem;
  size_t crowded = 0;  // strata with more than one sample, counted at their second
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x) {
      if (source.at(x, y) == kInvalidId) continue;
      glm::ivec2& seen = first[size_t(y / s) * size_t(strata_x) + size_t(x / s)];
      if (seen.x == -2) continue;  // a crowded stratum, counted already
      if (seen.x == -1) {
        seen = {x, y};
        continue;
      }
      if (crowded++ == 0)
        problem = "stratum (" + std::to_string(x / s) + ", " + std::to_string(y / s) + ") of " + std::to_string(s) +
                  "x" + std::to_string(s) + " pixels holds two gradient samples, at (" + std::to_string(seen.x) +
                  ", " + std::to_string(seen.y) + ") and (" + std::to_string(x) + ", " + std::to_string(y) +
                  "); a stratum holds at most one (trace/gradients.h)";
      seen = glm::ivec2(-2);
    }
  if (crowded == 0) return {};
  if (crowded > 1) problem += "; " + std::to_string(crowded - 1) + " more strata hold more than one";
  return {problem};
}

std::vector<std::string> input_problems(const Frame& frame, const InputChannels& channels) {
  std::vector<std::string> problems;
  for (const std::string& name : channels.floats)
    if (frame.has(name))
      if (std::string p = channel_problem(frame, name, true); !p.empty()) problems.push_back(std::move(p));
  for (const std::string& name : channels.uints)
    if (frame.has(name))
      if (std::string p = channel_problem(frame, name, false); !p.empty()) problems.push_back(std::move(p));
  for (std::string& p : missing_layers(frame, channels)) problems.push_back(std::move(p));
  // A method that reads gradient samples: the stratum size of the header, and one sample per stratum at most.
  if (std::find(channels.uints.begin(), channels.uints.end(), "gradient.source") == channels.uints.end())
    return problems;
  int s = 0;
  if (std::string p = stratum_size_problem(frame, &s); !p.empty()) {
    problems.push_back(std::move(p));
    return problems;
  }
  if (frame.uint_channels().count("gradient.source"))
    for (std::string& p : gradient_strata_problems(frame.uint_channel("gradient.source"), s))
      problems.push_back(std::move(p));
  return problems;
}

}  // namespace rtdr
