// The path tracer: shading as a function f(G, seed) of one surface sample G and a seed [ASVGF18 Sec. 3.2].
//
// Pass: trace_path(context, G, eye, seed, sample_index) -> PathSample.
//   in:  the frame's scene, pose, Embree scene, lights and materials (TraceContext); a primary surface sample
//        G = (instance, triangle, barycentrics) from the visibility buffer; the eye it is seen from; the seed
//   out: demodulation-ready radiance split into direct and indirect [SVGF17 Sec. 3], their components, and the
//        path record (light sample, shadow blocker, secondary hit) for motion vectors [TRMV21 Sec. 4]
//
// The path [SVGF17 Sec. 3]: primary visibility comes from the rasterizer; at each vertex x_k, next-event
// estimation to an emissive triangle chosen by power, a point uniform on its area, plus one BSDF-sampled ray;
// vertices 0 .. B where B = max_bounces (1 by default: one indirect ray and two shadow rays per pixel, as in
// SVGF). Multiple importance sampling with the power heuristic (Veach 1997, Sec. 9.2) joins light and BSDF
// sampling wherever both are traced; at the last vertex no BSDF ray is traced and light sampling stands alone
// (MIS weight 1). From the second vertex on, glossy lobes are regularized (Kaplanyan and Dachsbacher 2013) by
// a roughness floor, TraceOptions::regularized_roughness.
//
// Every random number comes from Sampler(seed, sample_index) in a fixed order, so the same G and seed give a
// bit-identical PathSample: what A-SVGF's re-shading of forward-projected samples relies on [ASVGF18 Eq. 6].
#pragma once

#include "raster/surface.h"
#include "raster/visibility.h"
#include "scenes/scene.h"
#include "trace/embree_scene.h"
#include "trace/lights.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace rtdr {

// The shading term's samples for TRMV's input: one estimate spreads by 0.07-0.22 % of the term under a square
// light (tests/trace_shading_test.cpp); a power of 2 makes the M points a (0, 2)-net.
inline constexpr int kTrmvShadingSamples = 64;

struct TraceOptions {
  // B: indirect bounces after the primary hit [SVGF17 Sec. 3 uses 1]. Range [0, 1024].
  int max_bounces = 1;
  // Path-space regularization: from the second vertex on, roughness is at least this [SVGF17 Sec. 3,
  // Kaplanyan and Dachsbacher 2013]. Range [0, 1]; 0 turns it off.
  float regularized_roughness = 0.3f;
  // M: light samples per pixel of the noise-free shading term `direct.shading` [TRMV21 Sec. 4.3]
  // (trace/shading.h) at 1 spp; an N-spp frame takes one estimate of M ceil(sqrt(N)). Range [0, 1024]; 0 (the
  // default) leaves the layer out: at kTrmvShadingSamples it costs several times a 1-spp frame's tracing
  // (trace/README.md), which only TRMV's input needs (rtdr render --shading-samples, and rtdr eval by itself when a
  // method reads the layer).
  int shading_samples = 0;
};

// Where the path went, for the motion vectors of [TRMV21 Sec. 4]. kInvalidId instances mean "none".
struct PathRecord {
  glm::vec3 light_position{0.0f};   // the primary vertex's light sample
  uint32_t light_instance = kInvalidId;
  glm::vec3 blocker_position{0.0f};  // the nearest occluder of that shadow ray, when it is blocked
  uint32_t blocker_instance = kInvalidId;
  glm::vec3 secondary_position{0.0f};  // the surface the primary BSDF ray hit
  uint32_t secondary_instance = kInvalidId;
  glm::vec3 secondary_direction{0.0f};  // the primary BSDF ray's direction (unit)
  // The indirect radiance arriving at x_0 along that ray (what x_1 on sends back, x_1's own emission excluded:
  // that is direct light) and the ray's sampling pdf (solid angle), for TRMV's cones [TRMV21 Sec. 4.3]
  // (filters/trmv/cones.h). 0 and 0 when no ray was traced.
  glm::vec3 secondary_incoming{0.0f};
  float secondary_pdf = 0.0f;
};

// Radiance leaving the primary surface towards the eye, emission excluded (the emission layer holds it).
struct PathSample {
  glm::vec3 direct{0.0f};      // light arriving straight from emitters: NEE at x_0 and emitters hit from x_0
  glm::vec3 indirect{0.0f};    // everything that scattered at least once more
  // Components, from which trace/render_frame.cpp writes TRMV's layers (direct.visibility, indirect.diffuse, ...):
  glm::vec3 direct_unshadowed{0.0f};  // the NEE term at x_0 without its visibility
  float direct_visibility = 0.0f;     // 1 when the NEE shadow ray at x_0 reached the light, else 0
  glm::vec3 indirect_diffuse{0.0f};   // indirect through the diffuse lobe at x_0
  glm::vec3 indirect_glossy{0.0f};    // indirect through the specular lobe at x_0 (diffuse + glossy = indirect)
  PathRecord record;
  glm::vec3 albedo{0.0f};  // of the primary surface: what SVGF demodulates by [SVGF17 Sec. 3]
  uint32_t rays = 0;  // rays traced (BSDF and shadow rays; primary visibility was rasterized)
};

// A ray as the tracer cast it, for replaying the same rays in a bare Embree loop (rtdr bench).
struct LoggedRay {
  Ray ray;
  float tfar;
  bool any_hit;  // cast with rtcOccluded1 (true) or rtcIntersect1 (false)
};

// Everything of one frame that every path reads.
struct TraceContext {
  const Scene& scene;
  const ScenePose& pose;
  const EmbreeScene& embree;
  const LightSet& lights;
  const SurfaceTable& surfaces;
  TraceOptions options;
  std::vector<LoggedRay>* ray_log = nullptr;  // when set, every ray cast is appended (not thread-safe)
};

PathSample trace_path(const TraceContext& context, const SurfaceSample& primary, const glm::vec3& eye, uint32_t seed,
                      uint32_t sample_index);

}  // namespace rtdr
