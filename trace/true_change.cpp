// The true temporal change of a frame's shading. See true_change.h.
#include "trace/true_change.h"

#include "raster/gbuffer_frame.h"
#include "trace/render_key.h"

namespace rtdr {

Frame render_true_change_frame(const Scene& scene, int frame_index, int width, int height,
                               const RenderSettings& settings, TraceStats* stats) {
  Frame frame = render_frame(scene, frame_index, width, height, settings, stats);
  // Frame i's surface samples, seen from frame i-1: its visibility buffer with the previous pose, lights and eye;
  // the same surface sample shaded under both frames, as the temporal gradient compares them [ASVGF18 Eq. 2].
  // The index stays i, so every pixel draws the seeds frame i drew (pixel_seed), and unchanged light cancels.
  FrameGeometry previous = rasterize_frame(scene, frame_index, width, height);
  previous.pose = previous.prev_pose;
  previous.view = previous.prev_view;
  Frame shaded(width, height);
  trace_layers(scene, previous, settings, shaded);
  for (const char* stream : {"direct", "indirect"})
    frame.set_rgb(std::string("truth.prev_") + stream, shaded.get_rgb(stream));
  Attributes key = render_key(scene, frame_index, width, height, settings);
  key["rtdr.true_change"] = "1";  // another frame than render_frame's: never taken for one by the cache
  stamp_render_header(frame, key);
  return frame;
}

}  // namespace rtdr
