// Tracing every pixel of a frame, and writing the radiance layers. See render_frame.h.
#include "trace/render_frame.h"

#include "trace/render_key.h"

#include "core/color.h"
#include "core/error.h"
#include "core/parallel.h"
#include "motion/backproject.h"
#include "motion/dual.h"
#include "motion/glossy.h"
#include "motion/shadow.h"
#include "core/sampler.h"
#include "trace/shading.h"

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rtdr {
namespace {

// Three float channels of one layer, e.g. direct.R, direct.G, direct.B, written a pixel at a time.
struct Channels3 {
  FloatPlane *c0, *c1, *c2;
  Channels3(Frame& frame, const std::string& layer, const char* const names[3])
      : c0(&frame.add_float(layer + "." + names[0])), c1(&frame.add_float(layer + "." + names[1])),
        c2(&frame.add_float(layer + "." + names[2])) {}
  void set(size_t i, const glm::vec3& v) { c0->data[i] = v.x, c1->data[i] = v.y, c2->data[i] = v.z; }
};

const char* const kRGB[3] = {"R", "G", "B"};
const char* const kXYZ[3] = {"X", "Y", "Z"};

// The radiance layers of docs/buffers.md, created in the frame before tracing so that the loop writes each
// pixel's results straight into them (no second copy of a 200 MB frame).
struct RadianceLayers {
  Channels3 direct, indirect, unshadowed, indirect_diffuse, indirect_glossy;
  std::optional<Channels3> shading;  // only when TraceOptions::shading_samples > 0
  uint32_t shading_samples = 0;      // its light samples per pixel at this frame's spp (shading_sample_count)
  FloatPlane& visibility;
  UIntPlane& seed;
  Channels3 light, blocker, secondary, direction, incoming;
  FloatPlane& pdf;
  UIntPlane &light_id, &blocker_id, &secondary_id;

  RadianceLayers(Frame& f, const RenderSettings& settings)
      : direct(f, "direct", kRGB), indirect(f, "indirect", kRGB), unshadowed(f, "direct.unshadowed", kRGB),
        indirect_diffuse(f, "indirect.diffuse", kRGB), indirect_glossy(f, "indirect.glossy", kRGB),
        visibility(f.add_float("direct.visibility")), seed(f.add_uint("rng.seed")), light(f, "path.light", kXYZ),
        blocker(f, "path.blocker", kXYZ), secondary(f, "path.secondary", kXYZ), direction(f, "path.direction", kXYZ),
        incoming(f, "path.incoming", kRGB), pdf(f.add_float("path.pdf")),
        light_id(f.add_uint("path.light.instance", kInvalidId)), blocker_id(f.add_uint("path.blocker.instance", kInvalidId)),
        secondary_id(f.add_uint("path.secondary.instance", kInvalidId)) {
    if (settings.trace.shading_samples <= 0) return;
    shading.emplace(f, "direct.shading", kRGB);
    shading_samples = shading_sample_count(settings.trace.shading_samples, settings.spp);
  }

  void set_record(size_t i, const PathRecord& r) {
    light.set(i, r.light_position);
    blocker.set(i, r.blocker_position);
    secondary.set(i, r.secondary_position);
    direction.set(i, r.secondary_direction);
    incoming.set(i, r.secondary_incoming);
    pdf.data[i] = r.secondary_pdf;
    light_id.data[i] = r.light_instance;
    blocker_id.data[i] = r.blocker_instance;
    secondary_id.data[i] = r.secondary_instance;
  }
};

// Traces `spp` samples of pixel i and stores their mean, demodulated by the pixel's albedo. The shading term
// [TRMV21 Sec. 4.3] is one estimate per pixel from M ceil(sqrt(spp)) light samples (trace/shading.h): it
// draws from a sequence of its own, so the paths' numbers, and every other layer, are the same without it.
uint32_t trace_pixel(const TraceContext& c, const SurfaceSample& s, const glm::vec3& eye, uint32_t seed, int spp,
                     size_t i, RadianceLayers& out) {
  glm::vec3 direct(0.0f), indirect(0.0f), unshadowed(0.0f), diffuse(0.0f), glossy(0.0f), albedo(0.0f);
  float visibility = 0.0f;
  uint32_t rays = 0;
  for (int k = 0; k < spp; ++k) {
    const PathSample p = trace_path(c, s, eye, seed, uint32_t(k));
    direct += p.direct;
    indirect += p.indirect;
    unshadowed += p.direct_unshadowed;
    diffuse += p.indirect_diffuse;
    glossy += p.indirect_glossy;
    visibility += p.direct_visibility;
    rays += p.rays;
    if (k == 0) out.set_record(i, p.record), albedo = p.albedo;  // the record of sample 0
  }
  // Demodulate [SVGF17 Sec. 3]: divide by the albedo of the directly visible surface.
  const glm::vec3 scale = 1.0f / (float(spp) * demodulation_factor(albedo));
  out.direct.set(i, direct * scale);
  out.indirect.set(i, indirect * scale);
  out.unshadowed.set(i, unshadowed * scale);
  out.indirect_diffuse.set(i, diffuse * scale);
  out.indirect_glossy.set(i, glossy * scale);
  if (out.shading)
    out.shading->set(i, direct_shading(c, s, eye, seed, out.shading_samples) / demodulation_factor(albedo));
  out.visibility.data[i] = visibility / float(spp);
  return rays;
}

}  // namespace

TraceStats trace_layers(const Scene& scene, const FrameGeometry& g, const RenderSettings& settings, Frame& frame,
                        const RowsDone& rows_done, const PixelSeeds* seeds) {
  const int width = g.vis.width, height = g.vis.height;
  const size_t pixels = size_t(width) * size_t(height);
  if (seeds && (seeds->seed.size() != pixels ||
                (!seeds->light_choice_frame.empty() && seeds->light_choice_frame.size() != pixels)))
    throw Error("trace_layers: " + std::to_string(seeds->seed.size()) + " seeds and " +
                std::to_string(seeds->light_choice_frame.size()) + " light-choice frames for a " +
                std::to_string(width) + "x" + std::to_string(height) + " frame");
  const EmbreeScene embree(scene, g.pose);
  const SurfaceTable surfaces(scene, g.pose);
  // One light set per frame whose powers choose lights: this frame's, and those the pixel seeds ask for.
  std::map<int, LightSet> lights;
  lights.emplace(g.index, LightSet(scene, g.pose));
  if (seeds)
    for (int f : seeds->light_choice_frame)
      if (!lights.count(f)) lights.emplace(f, LightSet(scene, g.pose, scene.pose(scene.time_of_frame(f))));
  std::map<int, TraceContext> contexts;
  for (const auto& [f, set] : lights) contexts.emplace(f, TraceContext{scene, g.pose, embree, set, surfaces, settings.trace});

  RadianceLayers layers(frame, settings);
  // Rays per second measure the tracing loop alone (not the BVH build or Embree's one-time start-up).
  const auto start = std::chrono::steady_clock::now();
  std::vector<uint64_t> rays_per_row(size_t(height), 0);  // summed after the loop: no shared counter
  parallel_rows(height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = g.vis.index(x, y);
      const uint32_t seed = seeds ? seeds->seed[i] : pixel_seed(settings.seed, g.index, x, y);
      layers.seed.data[i] = seed;
      const SurfaceSample s = g.vis.sample(x, y);
      if (!s.valid()) continue;  // background: every radiance layer stays 0
      const int choice = seeds && !seeds->light_choice_frame.empty() ? seeds->light_choice_frame[i] : g.index;
      rays_per_row[size_t(y)] += trace_pixel(contexts.at(choice), s, g.view.eye, seed, settings.spp, i, layers);
    }
    if (rows_done) rows_done(1);
  });
  TraceStats stats;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (uint64_t r : rays_per_row) stats.rays += r;
  return stats;
}

void write_path_motion_layers(const Scene& scene, const FrameGeometry& geometry, Frame& frame) {
  write_shadow_motion_layers(geometry, frame);      // from the path record just traced [TRMV21 Eq. 3]
  write_dual_motion_layers(scene, geometry, frame);  // from the previous visibility buffer [TRMV21 Eq. 6]
  write_glossy_motion_layers(geometry, frame);       // from the path record's secondary hit [TRMV21 Eq. 5]
}

Frame render_frame(const Scene& scene, int frame_index, int width, int height, const RenderSettings& settings,
                   TraceStats* stats, const RowsDone& rows_done) {
  const FrameGeometry geometry = rasterize_frame(scene, frame_index, width, height);
  Frame frame(width, height);
  write_gbuffer_layers(scene, geometry, frame);
  write_motion_layers(scene, geometry, frame);
  const TraceStats s = trace_layers(scene, geometry, settings, frame, rows_done);
  write_path_motion_layers(scene, geometry, frame);
  stamp_render_header(frame, render_key(scene, frame_index, width, height, settings));  // trace/render_key.h
  if (stats) *stats = s;
  return frame;
}

}  // namespace rtdr
