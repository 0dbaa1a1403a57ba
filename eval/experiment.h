// The evaluation harness: every method, now and later, is judged by exactly this code.
//
// run_eval renders (or takes from the cache) the 1-spp inputs and the reference frames of a scene, runs each
// method over the sequence in order, and measures each filtered frame against the reference:
//   rmse, relmse      on linear HDR radiance (the method's `color` against the reference's colour)
//   ssim, flip        on tone-mapped display values in [0, 1] (the method's `display`, TAA included,
//                     against the reference tone mapped with the same operator, no TAA)
//   temporal_error    between consecutive display frames of the method [SVGF17 Sec. 5.4]
//   ref_temporal_error  the same between consecutive reference frames: the scene's own change, the same in every
//                    method's row (temporal_error.png draws it beside the methods)
//   brightness_error  relative error of the image's mean luminance (linear HDR): bias without the noise
//   umbra_rmse       rmse over the moving umbrae only, Fig. 5's umbra (eval/metrics.h umbra_regions; NaN
//                    where a frame has none, as under a moving camera)
//   gradient_share   the share of the input's pixels that are gradient samples (0 without them)
//   ms_total, ms_<pass>  time of the method's passes on this frame: wall time of the golden passes, device time
//                     of the Vulkan ports; the ports' "transfer" (the host packing and unpacking planes) has its
//                     own column and is not in ms_total, as in rtdr bench
// A method is named by a spec "name[:param=value[:param=value...]]", e.g. "svgf:atrous_levels=3", where the
// parameters are rows of filters/svgf/svgf_params.h or filters/asvgf/asvgf_params.h; adding a method is a line in filters/method.cpp. Two more
// keys choose where it runs: backend=cpu (the golden passes, the default) or backend=vulkan (the shader ports,
// svgf, asvgf and trmv), and with backend=vulkan, illumination=fp32 or fp16 (the ports' illumination records,
// gpu/vulkan_context.h; without it, $RTDR_VK_ILLUMINATION or the device's default).
// Keys gradient_<row> set a row of trace/gradients.h's table for this method's input alone, e.g.
// "asvgf:gradient_stratum_size=2": the method runs on frames with gradient samples made with the run's gradient
// parameters and these rows changed (Fig. 5's stratum study), while the other methods keep the run's input.
// The key max_bounces=N renders this method's input AND its references with N indirect bounces (TraceOptions; 0:
// next-event estimation only, one shadow ray per pixel, the paper's PILLARS [ASVGF18 Sec. 4]), so that one run
// compares estimators, each against the converged image of its own; EvalConfig::max_bounces sets it for the run.
#pragma once

#include "filters/image.h"
#include "filters/method.h"
#include "filters/svgf/svgf_params.h"
#include "trace/gradients.h"
#include "trace/render_frame.h"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rtdr {

struct MethodSpec {
  std::string text;    // as given, e.g. "svgf:alpha=0.1"
  std::string name;    // "svgf"
  std::string params;  // "alpha=0.1" ("" for the defaults); backend and illumination included
  SvgfParams svgf;    // from the method's defaults (filters/method.h), then the spec's keys
  AsvgfParams asvgf;  // likewise; keys of all three tables are accepted
  TrmvParams trmv;    // likewise, and first for trmv (trmv:alpha=0.2 is TRMV's alpha, not SVGF's); and
                      // motion=traditional|shadow|dual|glossy|all, trmv's motion row by name
  std::string backend = "cpu";  // "cpu" or "vulkan"
  std::string illumination;     // backend=vulkan: "fp32", "fp16", or "" for the context's default
  // The gradient_<row> keys, row name without the prefix, in the order given: this method's own input.
  std::vector<std::pair<std::string, double>> gradient_rows;
  int max_bounces = -1;  // max_bounces=N: this method's input and references; -1: the run's (EvalConfig)
};
// Throws rtdr::Error for an unknown method or parameter, a value outside its range, an unknown back end or
// illumination records, or illumination without backend=vulkan.
MethodSpec parse_method_spec(const std::string& text);
// The parameter tables a spec's method is made with.
MethodParams spec_params(const MethodSpec& spec);
// The gradient input a spec's method runs on: `run` (the run's gradient parameters) with the spec's
// gradient_<row> keys applied.
GradientParams spec_gradient(const MethodSpec& spec, const GradientParams& run);
// The parameter sweeps of the speed-versus-accuracy chart: svgf's a-trous levels 1 to 5, alpha in {0.05, 0.1,
// 0.2, 0.5}, and the 3x3 kernel (the 5x5 is the default); and when `methods` names asvgf, Fig. 5's stratum study,
// asvgf on 2x2 and 4x4 strata (3x3 is the default).
std::vector<std::string> standard_sweep(const std::vector<std::string>& methods);

struct EvalConfig {
  std::string scene;
  std::vector<MethodSpec> methods;
  int first_frame = 0, last_frame = 0;  // inclusive
  int width = 320, height = 180;
  int ref_spp = 256;
  uint32_t seed = 0;
  int max_bounces = 1;  // indirect bounces of inputs and references (TraceOptions); a spec's max_bounces=N overrides
  std::string cache_dir = "out/cache";  // "" disables the cache
  // A-SVGF's input for every method: 1-spp frames with gradient samples (trace/gradients.h), rendered in order
  // from frame 0, as the paper compares methods on "identical 1 spp input". Implied when a method reads
  // gradient.source (asvgf) or names gradient rows of its own (MethodSpec::gradient_rows).
  bool gradients = false;
  GradientParams gradient;
  // Called with every filtered frame, in order, for measures of the caller's own (the stability suite's
  // regions): the method's spec, the frame index, the method's output and the reference's colour.
  std::function<void(const MethodSpec&, int, const Frame&, const RgbPlane&)> observe;
  // Makes a spec's method. Unset: the golden passes' make_method(spec.name, spec.svgf), and an error for any other
  // back end; rtdr eval sets app/backend.h's SpecMethods, which also makes the Vulkan ports.
  std::function<std::unique_ptr<Method>(const MethodSpec&)> make_method;
};

struct MetricsRow {
  std::string method, params;
  int frame = 0;
  double rmse = 0, relmse = 0, ssim = 0, flip = 0;
  double temporal_error = 0;  // NaN on the first frame (nothing to compare with)
  double ref_temporal_error = 0;  // the reference's, between this frame and the one before; NaN on the first
  double brightness_error = 0;  // relative error of the mean luminance, linear HDR (eval/metrics.h)
  double umbra_rmse = 0;        // rmse over the frame's moving umbrae; NaN where it has none
  double gradient_share = 0;    // the share of the input's pixels that are gradient samples
  double ms_total = 0;
  std::map<std::string, double> ms;  // per pass
};

// Called with (units done, units total) as frames are rendered and filtered.
using EvalProgress = std::function<void(int, int)>;

struct EvalResult {
  std::vector<MetricsRow> rows;
  // The last frame side by side, for a strip image: the 1-spp input, each method's display (every spec, in the
  // order run), the reference.
  std::vector<std::pair<std::string, RgbPlane>> last_frame;
};

// The colour a rendered frame shows, what the methods are measured against: its demodulated illumination
// remodulated, emission + albedo (direct + indirect).
RgbPlane frame_colour(const Frame& frame);

// What run_eval renders (or takes from the cache): 1-spp inputs of the config's seed (with gradient samples when
// config.gradients), and references of ref_spp samples of the same estimator with another seed, both with
// `max_bounces` indirect bounces (-1: the run's, config.max_bounces; or a spec's own).
RenderSettings input_settings(const EvalConfig& config, int max_bounces = -1);
RenderSettings reference_settings(const EvalConfig& config, int max_bounces = -1);
// The bounces a spec's method is measured with: its own max_bounces, else the run's.
int spec_bounces(const MethodSpec& spec, const EvalConfig& config);

// What run_eval renders, or takes from the cache: frames first_frame..last_frame of each of these sequences, at the
// config's size. The plan of a run's renders (eval/render_plan.h) lists them from here too.
struct EvalRenders {
  // A sequence of 1-spp inputs: input_settings(config, bounces), with TRMV's shading term (kTrmvShadingSamples)
  // when a method reads it (trmv), and with gradient samples made with `gradient` when the inputs carry them.
  struct Input {
    RenderSettings settings;
    std::optional<GradientParams> gradient;
  };
  // Each input sequence: the run's first (config.max_bounces and config.gradient: every method's input but those
  // of specs with max_bounces or gradient_<row> keys of their own), then each other one the specs' keys make, in
  // the order of the specs. Inputs carry gradient samples all or none.
  std::vector<Input> inputs;
  // Each reference sequence, reference_settings(config, bounces): the run's bounces first, then the specs' own.
  std::vector<RenderSettings> references;
  // For each method, in the order of config.methods: its input sequence and its reference sequence (indices).
  std::vector<size_t> method_input, method_reference;
};
// `methods`: the config's methods, made, in the order of config.methods; only what they read is asked.
EvalRenders eval_renders(const EvalConfig& config, const std::vector<const Method*>& methods);

// Throws rtdr::Error for a config run_eval refuses before it renders: frames outside 0..kMaxFrameIndex or out of
// order, a size below the SSIM window, gradient parameters or bounces out of range.
void check_eval_config(const EvalConfig& config);

// Every method is made before the first frame is rendered, so a spec that cannot run (no Vulkan device, say) fails
// at once rather than after the references.
EvalResult run_eval(const EvalConfig& config, const EvalProgress& progress = {});

// method, params, frame, rmse, relmse, ssim, flip, temporal_error, ref_temporal_error, brightness_error, umbra_rmse,
// gradient_share, ms_total, then one ms_<pass> column per pass
// of any method (empty where a method has no such pass). Written atomically.
void write_metrics_csv(const std::string& path, const std::vector<MetricsRow>& rows);

}  // namespace rtdr
