// The evaluation harness. What is measured, on which images, is described in experiment.h.
#include "eval/experiment.h"

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "eval/frame_cache.h"
#include "eval/metrics.h"
#include "eval/run_memory.h"
#include "filters/method.h"
#include "filters/svgf/modulate.h"
#include "filters/svgf/tonemap.h"
#include "scenes/gltf_loader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace rtdr {
namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, sep);) parts.push_back(part);
  return parts;
}

// The Rec. 709 luminance of every pixel (core/color.h).
FloatPlane luminance_plane(const RgbPlane& rgb) {
  FloatPlane l(rgb.width, rgb.height);
  for (size_t i = 0; i < l.data.size(); ++i) l.data[i] = luminance(rgb.data[i]);
  return l;
}

// The method a spec names, on its back end.
std::unique_ptr<Method> make_spec_method(const EvalConfig& c, const MethodSpec& spec) {
  if (c.make_method) return c.make_method(spec);
  if (spec.backend != "cpu") throw Error("method spec '" + spec.text + "': this caller runs backend=cpu only");
  return make_method(spec.name, spec_params(spec));
}

// One method over the whole sequence: a row of metrics per frame.
void evaluate_method(const MethodSpec& spec, Method& method, const std::vector<Frame>& inputs,
                     const std::vector<RgbPlane>& ref_colour, const std::vector<RgbPlane>& ref_display,
                     const std::vector<double>& ref_temporal, const std::vector<Region>& umbrae, const EvalConfig& c,
                     EvalResult& result,
                     const std::function<void()>& tick) {
  RgbPlane previous_display;
  for (size_t k = 0; k < inputs.size(); ++k) {
    const Frame out = method.filter(inputs[k]);
    const RgbPlane colour = rgb_plane(out, "color"), display = rgb_plane(out, "display");
    MetricsRow row;
    row.method = spec.name;
    row.params = spec.params;
    row.frame = c.first_frame + int(k);
    row.rmse = rmse(colour, ref_colour[k]);
    row.relmse = relmse(colour, ref_colour[k]);
    row.ssim = ssim(display, ref_display[k]);
    row.flip = flip(display, ref_display[k]).mean;
    row.brightness_error = brightness_error(colour, ref_colour[k]);
    row.umbra_rmse = rmse(colour, ref_colour[k], umbrae[k]);
    row.gradient_share = gradient_sample_share(inputs[k]);
    row.temporal_error = k == 0 ? std::numeric_limits<double>::quiet_NaN() : temporal_error(display, previous_display);
    row.ref_temporal_error = ref_temporal[k];
    row.ms = method.pass_times();
    row.ms_total = total_ms(row.ms);  // without the host's transfer, as rtdr bench
    result.rows.push_back(row);
    previous_display = display;
    if (c.observe) c.observe(spec, row.frame, out, ref_colour[k]);
    if (k + 1 == inputs.size()) result.last_frame.push_back({spec.text, display});
    tick();
  }
}

// Parses a whole decimal number ("4", "0.05", "1e-4"); false on anything else ("2.9junk", "", " 4").
bool parse_double(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && stop == end;
}

// A gradient_<row> key (trace/gradients.h's table): checked against the row's range and kept for the method's
// own input. False for any other key.
bool set_gradient_row(MethodSpec& spec, const std::string& key, double value) {
  const std::string prefix = "gradient_";
  if (key.rfind(prefix, 0) != 0) return false;
  GradientParams check;
  if (!set_param(check, key.substr(prefix.size()), value)) return false;
  spec.gradient_rows.push_back({key.substr(prefix.size()), value});
  return true;
}

// A key of a table the spec's method reads, its own first (filters/method.h set_method_param). False for any other.
bool set_spec_param(MethodSpec& spec, const std::string& key, double value) {
  MethodParams params = spec_params(spec);
  if (!set_method_param(spec.name, params, key, value)) return false;
  spec.svgf = params.svgf;
  spec.asvgf = params.asvgf;
  spec.trmv = params.trmv;
  return true;
}

}  // namespace

MethodSpec parse_method_spec(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.empty() || parts[0].empty()) throw Error("method spec '" + text + "' is empty");
  MethodSpec spec;
  spec.text = text;
  spec.name = parts[0];
  const MethodParams defaults = method_defaults(spec.name);  // throws for an unknown name, listing the known ones
  spec.svgf = defaults.svgf;
  spec.asvgf = defaults.asvgf;
  spec.trmv = defaults.trmv;
  for (size_t i = 1; i < parts.size(); ++i) {
    const size_t eq = parts[i].find('=');
    const std::string key = parts[i].substr(0, eq), value_text = eq == std::string::npos ? "" : parts[i].substr(eq + 1);
    double value = 0.0;
    if (key == "backend") {
      if (value_text != "cpu" && value_text != "vulkan")
        throw Error("method spec '" + text + "': backend '" + value_text + "' is not one of: cpu, vulkan");
      spec.backend = value_text;
    } else if (key == "illumination") {
      if (value_text != "fp32" && value_text != "fp16")
        throw Error("method spec '" + text + "': illumination '" + value_text + "' is not one of: fp32, fp16");
      spec.illumination = value_text;
    } else if (key == "max_bounces") {
      int bounces = -1;
      const auto [end, ec] = std::from_chars(value_text.data(), value_text.data() + value_text.size(), bounces);
      if (ec != std::errc() || end != value_text.data() + value_text.size() || bounces < 0 || bounces > 1024)
        throw Error("method spec '" + text + "': max_bounces '" + value_text + "' is not a whole number in [0, 1024]");
      spec.max_bounces = bounces;
    } else if (key == "motion" && trmv_motion_from_name(value_text) >= 0) {
      spec.trmv.motion = trmv_motion_from_name(value_text);  // trmv_params.h's motion row, by name
    } else if (eq == std::string::npos || !parse_double(value_text, value) ||
               !(set_spec_param(spec, key, value) || set_gradient_row(spec, key, value))) {
      throw Error("method spec '" + text + "': '" + parts[i] +
                  "' is not parameter=value of svgf_params.h, asvgf_params.h, trmv_params.h or gradient_<row> of "
                  "trace/gradients.h, motion=traditional|shadow|dual|glossy|all, backend=cpu|vulkan, illumination=fp32|fp16 or "
                  "max_bounces=N");
    }
    spec.params += (spec.params.empty() ? "" : ":") + parts[i];
  }
  if (!spec.illumination.empty() && spec.backend != "vulkan")
    throw Error("method spec '" + text + "': illumination=" + spec.illumination + " needs backend=vulkan");
  validate(spec.svgf);
  validate(spec.asvgf);
  validate(spec.trmv);
  return spec;
}

MethodParams spec_params(const MethodSpec& spec) {
  MethodParams params(spec.svgf);
  params.asvgf = spec.asvgf;
  params.trmv = spec.trmv;
  return params;
}

GradientParams spec_gradient(const MethodSpec& spec, const GradientParams& run) {
  GradientParams params = run;
  for (const auto& [row, value] : spec.gradient_rows) set_param(params, row, value);
  return params;
}

std::vector<std::string> standard_sweep(const std::vector<std::string>& methods) {
  std::vector<std::string> specs;
  for (int levels = 1; levels <= 4; ++levels) specs.push_back("svgf:atrous_levels=" + std::to_string(levels));
  for (const char* alpha : {"0.05", "0.1", "0.5"}) specs.push_back(std::string("svgf:alpha=") + alpha + ":alpha_moments=" + alpha);
  specs.push_back("svgf:kernel_size=3");  // plus "svgf" itself: 5 levels, alpha 0.2, the 5x5 kernel
  // [ASVGF18 Fig. 5]: the stratum size, plus "asvgf" itself on 3x3 strata.
  const auto asvgf = [](const std::string& spec) { return spec == "asvgf" || spec.rfind("asvgf:", 0) == 0; };
  if (std::any_of(methods.begin(), methods.end(), asvgf))
    for (const char* s : {"2", "4"}) specs.push_back(std::string("asvgf:gradient_stratum_size=") + s);
  return specs;
}

// [SVGF17 Sec. 3]: remodulated exactly as the methods remodulate their filtered illumination.
RgbPlane frame_colour(const Frame& f) {
  return remodulate(rgb_plane(f, "direct"), rgb_plane(f, "indirect"), rgb_plane(f, "albedo"), rgb_plane(f, "emission"));
}

RenderSettings input_settings(const EvalConfig& c, int max_bounces) {
  RenderSettings settings;
  settings.seed = c.seed;
  settings.trace.max_bounces = max_bounces < 0 ? c.max_bounces : max_bounces;
  return settings;
}

RenderSettings reference_settings(const EvalConfig& c, int max_bounces) {
  RenderSettings settings;
  settings.spp = c.ref_spp;
  settings.seed = c.seed + 1000003u;
  settings.trace.max_bounces = max_bounces < 0 ? c.max_bounces : max_bounces;
  return settings;
}

int spec_bounces(const MethodSpec& spec, const EvalConfig& c) { return spec.max_bounces >= 0 ? spec.max_bounces : c.max_bounces; }

namespace {

// The references of one estimator (one sequence of EvalRenders::references): colour and tone-mapped display per
// frame, the reference's own change between frames, and the moving umbrae.
struct References {
  std::vector<RgbPlane> colour, display;
  std::vector<double> temporal;
  std::vector<Region> umbrae;
};

References render_references(FrameCache& cache, const EvalConfig& c, const RenderSettings& settings,
                             const std::function<void()>& tick) {
  References r;
  std::vector<FloatPlane> direct, depth;  // for the umbrae
  std::vector<RgbPlane> position;
  const TonemapParams tonemap_params;
  for (int f = c.first_frame; f <= c.last_frame; ++f) {  // no overflow: checked against kMaxFrameIndex
    const Frame ref = cache.get(f, c.width, c.height, settings);
    r.colour.push_back(frame_colour(ref));
    r.display.push_back(tonemap(r.colour.back(), tonemap_params));
    direct.push_back(luminance_plane(rgb_plane(ref, "direct")));
    depth.push_back(ref.float_channel("depth.Z"));
    position.push_back(xyz_plane(ref, "position"));
    tick();
  }
  r.umbrae = umbra_regions(direct, position, depth);
  // The reference's own change between frames [SVGF17 Sec. 5.4]: the scene's real motion, what a method's temporal
  // error is read against.
  r.temporal.push_back(std::numeric_limits<double>::quiet_NaN());
  for (size_t k = 1; k < r.display.size(); ++k) r.temporal.push_back(temporal_error(r.display[k], r.display[k - 1]));
  return r;
}

// One input sequence: with gradient samples (rendered in order from frame 0), or without.
std::vector<Frame> render_inputs(FrameCache& cache, const EvalConfig& c, const EvalRenders::Input& input,
                                 const std::function<void()>& tick) {
  std::vector<Frame> inputs;
  if (input.gradient)
    inputs = cache.gradient_frames(c.first_frame, c.last_frame, c.width, c.height, input.settings, *input.gradient);
  for (int f = c.first_frame; f <= c.last_frame; ++f) {
    if (!input.gradient) inputs.push_back(cache.get(f, c.width, c.height, input.settings));
    tick();
  }
  return inputs;
}

// The index of `item` in `list`, added at the end when no element is `same` as it.
template <typename T, typename Same>
size_t index_of(std::vector<T>& list, T item, Same same) {
  for (size_t k = 0; k < list.size(); ++k)
    if (same(list[k], item)) return k;
  list.push_back(std::move(item));
  return list.size() - 1;
}

}  // namespace

void check_eval_config(const EvalConfig& c) {
  if (c.first_frame < 0 || c.last_frame < c.first_frame || c.last_frame > kMaxFrameIndex)
    throw Error("frames " + std::to_string(c.first_frame) + "-" + std::to_string(c.last_frame) +
                ": need 0 <= first <= last <= " + std::to_string(kMaxFrameIndex));
  // SSIM needs one whole window [Wang04 Sec. III-C]: say so before rendering anything, not after.
  const int window = 2 * kSsimRadius + 1;
  if (c.width < window || c.height < window)
    throw Error("size " + std::to_string(c.width) + "x" + std::to_string(c.height) + ": evaluation needs at least " +
                std::to_string(window) + "x" + std::to_string(window) + " (the SSIM window)");
  if (c.gradients) validate(c.gradient);
  if (c.max_bounces < 0 || c.max_bounces > 1024)
    throw Error("max_bounces " + std::to_string(c.max_bounces) + " is not in [0, 1024]");
}

EvalRenders eval_renders(const EvalConfig& c, const std::vector<const Method*>& methods) {
  // With gradient samples when asked, or when a method reads them (asvgf) or names gradient rows of its own: then
  // every method without rows of its own gets the same input. With TRMV's shading term when a method reads it
  // (trmv): then every method's input carries it.
  bool gradients = c.gradients;
  int shading_samples = 0;
  for (size_t m = 0; m < methods.size(); ++m) {
    gradients = gradients || methods[m]->reads_gradient_samples() || !c.methods[m].gradient_rows.empty();
    if (methods[m]->reads_shading_term()) shading_samples = kTrmvShadingSamples;
  }
  const auto input = [&](int bounces, const GradientParams& gradient) {
    EvalRenders::Input in{input_settings(c, bounces), std::nullopt};
    in.settings.trace.shading_samples = shading_samples;
    if (gradients) in.gradient = gradient;
    return in;
  };
  // Inputs are the same sequence when their bounces and gradient parameters are; references when their bounces are.
  const auto same_input = [](const EvalRenders::Input& a, const EvalRenders::Input& b) {
    return a.settings.trace.max_bounces == b.settings.trace.max_bounces &&
           (a.gradient ? param_values(*a.gradient) : std::vector<double>{}) ==
               (b.gradient ? param_values(*b.gradient) : std::vector<double>{});
  };
  const auto same_reference = [](const RenderSettings& a, const RenderSettings& b) {
    return a.trace.max_bounces == b.trace.max_bounces;
  };
  EvalRenders r;
  r.inputs.push_back(input(c.max_bounces, c.gradient));  // the run's first
  r.references.push_back(reference_settings(c, c.max_bounces));
  for (const MethodSpec& spec : c.methods) {
    const int bounces = spec_bounces(spec, c);
    r.method_input.push_back(index_of(r.inputs, input(bounces, spec_gradient(spec, c.gradient)), same_input));
    r.method_reference.push_back(index_of(r.references, reference_settings(c, bounces), same_reference));
  }
  return r;
}

EvalResult run_eval(const EvalConfig& c, const EvalProgress& progress) {
  check_eval_config(c);
  const Scene scene = load_scene(c.scene);
  std::vector<std::unique_ptr<Method>> methods;
  std::vector<const Method*> made;
  for (const MethodSpec& spec : c.methods) {
    methods.push_back(make_spec_method(c, spec));
    made.push_back(methods.back().get());
  }
  const EvalRenders renders = eval_renders(c, made);
  const int frames = c.last_frame - c.first_frame + 1;
  const int total = int(renders.inputs.size() + renders.references.size() + c.methods.size()) * frames;
  int done = 0;
  auto tick = [&] {
    if (progress) progress(++done, total);
  };

  // What the run will hold, against the memory there is (run_memory.h), before anything is rendered or cached.
  uint64_t most_method_planes = 0;
  for (const std::unique_ptr<Method>& m : methods) most_method_planes = std::max(most_method_planes, method_planes(*m));
  const EvalRenders::Input& first = renders.inputs.front();
  require_run_fits("eval", c.width, c.height,
                   eval_planes(rendered_frame_planes(scene, first.settings, first.gradient.has_value()), frames,
                               most_method_planes, int(renders.inputs.size()), int(renders.references.size())),
                   memory_budget());
  // Inputs (1 spp, the seed's noise) and references (ref_spp samples of the same estimator, another seed).
  FrameCache cache(c.cache_dir, scene);
  std::vector<std::vector<Frame>> inputs;
  for (const EvalRenders::Input& input : renders.inputs) inputs.push_back(render_inputs(cache, c, input, tick));
  std::vector<References> references;
  for (const RenderSettings& settings : renders.references)
    references.push_back(render_references(cache, c, settings, tick));

  EvalResult result;
  const TonemapParams tonemap_params;
  result.last_frame.push_back({"1 spp input", tonemap(frame_colour(inputs.front().back()), tonemap_params)});
  for (size_t m = 0; m < methods.size(); ++m) {
    const References& r = references[renders.method_reference[m]];
    evaluate_method(c.methods[m], *methods[m], inputs[renders.method_input[m]], r.colour, r.display, r.temporal,
                    r.umbrae, c, result, tick);
    methods[m].reset();  // its history's memory
  }
  result.last_frame.push_back({"reference " + std::to_string(c.ref_spp) + " spp", references.front().display.back()});
  return result;
}

void write_metrics_csv(const std::string& path, const std::vector<MetricsRow>& rows) {
  std::set<std::string> passes;
  for (const MetricsRow& r : rows)
    for (const auto& [pass, ms] : r.ms) passes.insert(pass);
  std::ostringstream csv;
  csv.precision(9);
  csv << "method,params,frame,rmse,relmse,ssim,flip,temporal_error,ref_temporal_error,brightness_error,umbra_rmse,"
         "gradient_share,ms_total";
  for (const std::string& p : passes) csv << ",ms_" << p;
  csv << '\n';
  for (const MetricsRow& r : rows) {
    csv << r.method << ',' << r.params << ',' << r.frame << ',' << r.rmse << ',' << r.relmse << ',' << r.ssim << ','
        << r.flip << ',' << r.temporal_error << ',' << r.ref_temporal_error << ',' << r.brightness_error << ',' << r.umbra_rmse << ','
        << r.gradient_share << ',' << r.ms_total;
    for (const std::string& p : passes) {
      csv << ',';
      if (r.ms.count(p)) csv << r.ms.at(p);
    }
    csv << '\n';
  }
  write_text_file(path, csv.str());
}

}  // namespace rtdr
