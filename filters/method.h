// A denoising method as the tools see it: frames in, frames out, in sequence order, with whatever
// history it keeps. `rtdr filter`, `rtdr probe`, the evaluation harness and the benchmarks all go through
// this interface. A method that is SVGF's pipeline with some stages switched off or swapped is one line of the
// registry in method.cpp; make_method() looks its name up there.
//
// Input frame: the layers `rtdr render` writes (docs/buffers.md): the G-buffer, motion, and the demodulated
// 1-spp `direct` and `indirect` illumination. Output frame: `color.R/G/B` (linear HDR radiance, remodulated
// and recombined: emission + albedo * (direct + indirect)) and `display.R/G/B` (tone mapped, then TAA where
// the method uses it; display-referred linear, sRGB-encode to view).
#pragma once

#include "core/frame.h"
#include "filters/pass_log.h"
#include "filters/probe.h"
#include "filters/asvgf/asvgf_params.h"
#include "filters/baselines/eaw.h"
#include "filters/svgf/svgf_params.h"
#include "filters/svgf/tonemap.h"
#include "filters/taa/taa.h"
#include "filters/trmv/trmv_params.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace rtdr {

// Wall time of each pass of the last frame, milliseconds, by pass name ("temporal", "atrous", ...).
using PassTimes = std::map<std::string, double>;
// The pass name under which a back end reports work that is not filtering: the Vulkan ports' host packing and
// unpacking of planes, and their copies to the host (gpu/svgf_vulkan.h).
inline constexpr const char* kTransferPass = "transfer";
// A frame's total, as rtdr bench and rtdr eval report it: the sum of its pass times without kTransferPass.
double total_ms(const PassTimes& times);

// The channels a method reads from every input frame, by type. `rtdr filter` checks all of them in every frame
// (present, of this type, and, for floats, finite) before it writes anything.
struct InputChannels {
  std::vector<std::string> floats;
  std::vector<std::string> uints;
  // Float channels among them that an input may leave out, and the value they then hold at every pixel
  // (docs/buffers.md, "Feeding your engine's frames"): what an engine without them would write.
  std::map<std::string, float> defaults;
};
// What every method reads: the G-buffer (SurfacePlanes::from_frame), albedo and emission, then `illumination` (the
// method's own noisy channels), and id.mesh; emission and indirect light default to 0 (an engine with no emitters
// in view has no emission; one that does not split its illumination puts it all in `direct`).
InputChannels common_input_channels(const std::vector<std::string>& illumination);
// How to make frames hold `layer` where `rtdr render` writes it only when asked: "gradient" (A-SVGF's gradient
// samples: render them with `rtdr render --gradients`) and "direct.shading" (TRMV's shading term: `rtdr render
// --shading-samples N`); "" for any other layer. Every error about a frame that lacks such a layer ends with it
// (rtdr filter, probe, compare and check, through app/sequence.h).
std::string missing_layer_fix(const std::string& layer);
// Adds every channel of channels.defaults that `frame` lacks, filled with its default. Callers that hand a
// user's frame to Method::filter call it first (rtdr filter, probe and compare do, through app/sequence.h).
void fill_input_defaults(Frame& frame, const InputChannels& channels);

class Method {
 public:
  virtual ~Method() = default;
  virtual std::string name() const = 0;
  // Filters the next frame of the sequence. When `dump` is given, every intermediate buffer is added to it
  // as the layers its passes declare (filters/passes.h, docs/buffers.md "Filter passes"): what the frame's pass
  // log holds (passes()).
  virtual Frame filter(const Frame& in, Frame* dump = nullptr) = 0;
  // Forgets all history (the next frame is treated as the first).
  virtual void reset() = 0;
  // A copy of the method with its history: filtering the same next frame, the copy makes what this one would.
  // The copy's pass log starts empty (this one's points at this one's planes), so a copy probes only after it has
  // filtered a frame. `rtdr view` keeps, per frame, a copy that filtered it. A method that cannot be copied (a
  // Vulkan back end's, whose state lives on the device) throws rtdr::Error.
  virtual std::unique_ptr<Method> clone() const;
  // Re-runs `pass` at pixel (x, y) of the LAST filtered frame, on exactly the inputs that pass saw, with a
  // probe attached. `stream` is the stream or component for per-stream passes, `level` the level. By default
  // the pass log's (filters/pass_log.h); a back end that logs no golden function says so instead.
  virtual Probe probe(const std::string& pass, int x, int y, const std::string& stream, int level) const;
  // What the last frame's passes did, in order: their layers and their golden per-pixel functions.
  const PassLog& passes() const { return log_; }
  // The passes probe() accepts: those the method runs, in order (filters/passes.h declares each).
  virtual std::vector<std::string> probe_passes() const = 0;
  // Every channel filter() reads from its input frame.
  virtual InputChannels inputs() const = 0;
  // Every channel filter() adds to `dump`: the dump layers of the passes it runs (filters/passes.h).
  virtual std::vector<std::string> dump_channels() const = 0;
  const PassTimes& pass_times() const { return times_; }
  // Whether its input must carry A-SVGF's gradient samples (it reads gradient.source, trace/gradients.h).
  bool reads_gradient_samples() const;
  // Whether its input must carry TRMV's shading term (it reads direct.shading, trace/shading.h).
  bool reads_shading_term() const;

 protected:
  Method() = default;
  // What clone() copies: the pass times, not the pass log (see clone()).
  Method(const Method& other) : times_(other.times_) {}
  Method& operator=(const Method&) = delete;
  // Runs `run` and adds its wall time to times_[pass]; returns the milliseconds.
  double time_pass(const std::string& pass, const std::function<void()>& run);
  // Logs a run of the pass declared as `name` (filters/passes.h) on `stream` at `level`, for its layers and its
  // probe (filters/pass_log.h). filter() starts each frame's log with log_.begin and ends it with
  // `if (dump) log_.dump(*dump)`.
  PassRun& log_pass(std::string_view name, std::string_view stream = {}, int level = -1) {
    return log_.add(find_pass(name), stream, level);
  }
  PassTimes times_;
  PassLog log_;
};

// "svgf" (the pipeline of [SVGF17 Sec. 3]), "accum" (its temporal accumulation only, [SVGF17 Sec. 4.1]), "eaw"
// (Dammertz 2010, no temporal reuse), "eaw-accum"
// (our temporal accumulation, then EAW), "none" (the 1-spp input, remodulated), "trmv" (Zeng et al. 2021's
// filter-then-accumulate with reliable motion vectors, filters/trmv/trmv.h). Throws rtdr::Error for an unknown
// name, listing the known ones.
// Every parameter table a method reads, each at its declared defaults unless set: SVGF's (svgf_params.h), A-SVGF's
// (asvgf_params.h), EAW's (eaw.h), tone mapping's (tonemap.h), TAA's (taa.h) and TRMV's (trmv_params.h). Made from
// SvgfParams alone, the others keep their defaults.
struct MethodParams {
  MethodParams(const SvgfParams& svgf_params = {}) : svgf(svgf_params) {}  // NOLINT: implicit on purpose
  SvgfParams svgf;
  AsvgfParams asvgf;
  EawParams eaw;
  TonemapParams tonemap;
  TaaParams taa;
  TrmvParams trmv;
};

// A method's own defaults: the tables' declared defaults, except where the method's paper chose otherwise (asvgf and
// a-eaw: asvgf_defaults in filters/asvgf/asvgf.h, alpha = 0.1 and the 3x3 box). Throws for an unknown name.
MethodParams method_defaults(const std::string& name);
// `params` are the tunables; a method ignores the tables of the stages it does not run. Without them, the
// method's own defaults.
std::unique_ptr<Method> make_method(const std::string& name);
std::unique_ptr<Method> make_method(const std::string& name, const MethodParams& params);
// The stages and parameters make_method() gives the SvgfFilter of method `name` (for other back ends of the same
// method, gpu/svgf_vulkan.h). Throws like make_method(), and for a method with a class of its own (trmv: its golden
// passes are TrmvFilter's, filters/trmv/trmv.h, its Vulkan ports TrmvVulkan's, gpu/trmv_vulkan.h).
struct SvgfOptions;
SvgfOptions method_options(const std::string& name, const MethodParams& params = {});
// The registry's names (filters/method.cpp), in its order.
std::vector<std::string> method_names();
// Whether method `name` is one of SVGF's pipelines (method_options gives its stages), rather than a class of its own.
// Throws for an unknown name.
bool is_svgf_pipeline(const std::string& name);
// Sets parameter `key` of the tables method `name` reads: its own table first where it has one (trmv:alpha is
// TRMV's alpha), then SVGF's, A-SVGF's and TRMV's. False when no table has the key; throws rtdr::Error, with the
// range, for a value outside it.
bool set_method_param(const std::string& name, MethodParams& params, const std::string& key, double value);
// The parameters method `name` reads, one "name = value" line each, as `rtdr filter` prints them.
std::string describe_method_params(const std::string& name, const MethodParams& params);

}  // namespace rtdr
