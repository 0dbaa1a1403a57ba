// What `rtdr view` serves (docs/view.md): a sequence filtered once, with every frame's pass buffers and the method
// as it stood after that frame, so that any question about any frame is answered from memory, at once.
//
// Per viewable frame it keeps the method's input layers, its output and dump layers (filters/passes.h, as
// `rtdr filter --dump-passes` writes them), and a copy of the method (Method::clone), which probes the frame as
// `rtdr probe` does after filtering frames 0 to F. With `rtdr view --ref`, also the reference's colour and display,
// the FLIP map against it and the frame's metrics (eval/metrics.h); with --port-dumps, the port's dump of the frame.
// Every file it reads must lie inside its folder: a symlink out of --in, --ref or --port-dumps is refused.
#pragma once

#include "core/frame.h"
#include "filters/method.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rtdr {

struct ViewOptions {
  std::string method = "svgf";
  std::string in;          // the rendered sequence (rtdr render)
  std::string ref;         // reference frames of the same indices (rtdr render --spp N), or ""
  std::string port_dumps;  // a port's `rtdr filter --backend vulkan --dump-passes` of the same frames, or ""
  std::string frames;      // the viewable range ("" = every frame); history is built from the first frame
  int port = 8731;
  MethodParams params;
};

// The layer sources of /api/layer: the method's input frame, its output and dump (golden), the port's dump, and
// the reference with its error map.
enum class LayerSource { Input, Golden, Port, Reference };
// "input", "golden", "port", "ref" -> the source; nullopt for anything else.
std::optional<LayerSource> parse_layer_source(const std::string& name);

// One layer's float channels, each width * height float32 values, row-major, top row first.
struct LayerPlanes {
  int width = 0, height = 0;
  std::vector<std::string> channels;  // "R", "G", "B"; "X", "Y"(, "Z"); or "" for a scalar
  std::string bytes;                  // the planes one after another, native (little-endian) float32
};

// The float channels of `frame` that make layer `name`: name.R/G/B, else name.X/Y(/Z), else name itself.
// nullopt when the frame has none of them.
std::optional<LayerPlanes> layer_planes(const Frame& frame, const std::string& name);

class ViewSequence {
 public:
  // Filters the sequence and reads the reference and port frames; `progress` gets one line per frame. Throws
  // rtdr::Error for a frame missing from --ref or --port-dumps, a file that leads out of its folder, a sequence
  // that would not fit in the memory available, and anything that `rtdr probe` would refuse.
  ViewSequence(const ViewOptions& options, const std::function<void(const std::string&)>& progress);

  // /api/info: the method, the frames, the size, the streams, and the layers in the order of the method's passes
  // (docs/view.md has the fields).
  const nlohmann::json& info() const { return info_; }
  // The layer `name` of frame `frame` from `source`; nullopt when there is no such frame, source or layer.
  std::optional<LayerPlanes> layer(LayerSource source, int frame, const std::string& name) const;
  // What `rtdr probe --json` prints for the same question. Throws rtdr::Error as rtdr probe does (a pass the method
  // does not run, a level it did not run, a pixel outside), and for a frame that is not viewable.
  std::string probe_json(int frame, int x, int y, const std::string& pass, const std::string& stream,
                         int level) const;
  // The frame's metrics against the reference (rmse, relmse, ssim, flip); null without --ref or such a frame.
  nlohmann::json metrics(int frame) const;
  size_t frame_count() const { return frames_.size(); }

 private:
  struct FrameState {
    int index = 0;
    Frame input;                    // the layers the method reads
    Frame golden;                   // its output and dump layers
    std::unique_ptr<Method> state;  // the method after this frame, for the probe
    Frame port;                     // --port-dumps: the port's output and dump layers
    Frame reference;                // --ref: color, display (tone mapped as the method's), error.flip
    nlohmann::json metrics;         // --ref: rmse, relmse, ssim, flip
  };
  const FrameState* find(int frame) const;
  void add_reference(FrameState& f) const;
  void make_info();

  ViewOptions options_;
  std::vector<FrameState> frames_;
  nlohmann::json info_;
};

}  // namespace rtdr
