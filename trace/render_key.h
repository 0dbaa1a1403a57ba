// The render key: everything a rendered frame is a function of, written into the frame's own header, so that a
// frame read back from a file can say exactly how it was made. rtdr render, the frame cache (eval/frame_cache.h)
// and a gradient sequence's next frame (trace/gradients.h) all compare frames by it; a cluster's workers and the
// eval that reads their frames agree through it (docs/reliability.md, "The frame cache").
//
// Keyed attributes (compared; a frame differing in any of them is another frame):
//   rtdr.renderer            kRendererVersion, bumped whenever the renderer's output changes meaning
//   rtdr.scene               the scene's name, for people (the hash identifies it)
//   rtdr.scene.hash          Scene::content_hash: the glTF file and every buffer and image it loads
//   rtdr.frame               the frame index
//   rtdr.size                WIDTHxHEIGHT
//   rtdr.spp, rtdr.seed      RenderSettings
//   rtdr.max_bounces, rtdr.regularized_roughness, rtdr.shading_samples    every field of TraceOptions
//   rtdr.gradients           1 for A-SVGF's input (trace/gradients.h), else 0; then rtdr.gradient.<row> for every
//                            row of its parameter table
// Recorded, not keyed (provenance): rtdr.build (the build: version, compiler, Embree) and rtdr.cpu (the processor
// features Embree and libm choose their code paths by). Frames are bit-identical for any thread count; across
// machines, only for the same build and the same features.
// Stamped last: rtdr.checksum, frame_checksum (core/frame.h) of the planes as rendered.
#pragma once

#include "core/frame.h"
#include "scenes/scene.h"
#include "trace/render_frame.h"

#include <map>
#include <set>
#include <string>

namespace rtdr {

struct GradientParams;

// 1: the first versioned frames; 2: TRMV's shadow motion (motion.shadow, motion.shadow_splat); 3: the
// energy-preserving dielectric (trace/brdf.h) and double-sided emitters; 4: the dual motion vector (motion.dual,
// motion/dual.h) and the cones' samples (path.incoming, path.pdf); 5: the glossy vector's lobe centre and current
// footprint (motion.glossy_mean, glossy.footprint), and no motion.shadow_splat (the filter splats: filters/trmv/).
inline constexpr int kRendererVersion = 5;

using Attributes = std::map<std::string, std::string>;

// The keyed attributes of frame `frame_index` of `scene` at width x height; with `gradients`, of the frame with
// gradient samples rendered with those parameters.
Attributes render_key(const Scene& scene, int frame_index, int width, int height, const RenderSettings& settings,
                      const GradientParams* gradients = nullptr);

// The provenance attributes of this build on this machine.
Attributes render_provenance();

// The last step of rendering a frame: its header becomes `key`, the provenance and the checksum of its planes.
void stamp_render_header(Frame& frame, const Attributes& key);

// Why `frame`'s header does not match `key`: its first keyed attribute (in either) that differs, as
// "rtdr.spp is 1, not 64" or "rtdr.max_bounces is missing"; "" when every keyed attribute agrees. Attributes in
// `ignore` are not compared.
std::string key_mismatch(const Frame& frame, const Attributes& key, const std::set<std::string>& ignore = {});

// Why `frame`'s planes are not the ones its rtdr.checksum was stamped over ("" when they are).
std::string checksum_mismatch(const Frame& frame);

}  // namespace rtdr
