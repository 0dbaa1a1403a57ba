// The registry of methods: one line each. See method.h.
#include "filters/method.h"

#include "core/error.h"
#include "filters/asvgf/asvgf.h"
#include "filters/svgf/svgf.h"
#include "filters/params.h"
#include "filters/trmv/trmv.h"

#include <algorithm>
#include <chrono>
#include <functional>

namespace rtdr {
namespace {

// The options of a method: which stages run; every parameter keeps its declared default.
SvgfOptions stages(const char* name, bool temporal, SpatialFilter spatial, bool taa = true, bool adaptive = false) {
  SvgfOptions o;
  o.name = name;
  o.temporal = temporal;
  o.spatial = spatial;
  o.taa = taa;
  o.adaptive = adaptive;
  return o;
}

// One method: its name, and either the stages of SVGF's pipeline it runs (`options`; SvgfFilter runs them) or its
// own class (`make`). `defaults` is where it departs from the tables' defaults; `own_params` sets a key of the table
// it reads before SVGF's, for the names both have (trmv's alpha is TRMV's, not SVGF's).
struct MethodEntry {
  const char* name;
  std::function<SvgfOptions()> options;
  std::function<void(MethodParams&)> defaults = [](MethodParams&) {};
  std::function<std::unique_ptr<Method>(const MethodParams&)> make = nullptr;
  std::function<bool(MethodParams&, const std::string&, double)> own_params = nullptr;
  std::function<std::string(const MethodParams&)> describe = nullptr;
};

// svgf runs every stage of [SVGF17 Sec. 3]; asvgf is SVGF with the adaptive alpha and the 3x3 box [ASVGF18 Sec. 4],
// its defaults A-SVGF's own (asvgf_defaults, filters/asvgf/asvgf.h);
// a-eaw is EAW followed by A-SVGF's adaptive temporal filter, our stand-in for the paper's A-RAE [ASVGF18 Fig. 6]; accum stops after the temporal accumulation [SVGF17 Sec. 4.1]; eaw
// is Dammertz 2010's edge-avoiding a-trous without temporal reuse, a baseline of [SVGF17 Sec. 5.1].
const std::vector<MethodEntry>& registry() {
  static const std::vector<MethodEntry> methods = {
      {"svgf", [] { return stages("svgf", true, SpatialFilter::Atrous); }},
      {"asvgf", [] { return stages("asvgf", true, SpatialFilter::Atrous, true, true); }, asvgf_defaults},
      {"a-eaw",
       [] {
         SvgfOptions o = stages("a-eaw", false, SpatialFilter::Eaw, true, true);
         o.ema_after_spatial = true;
         return o;
       },
       asvgf_defaults},
      {"accum", [] { return stages("accum", true, SpatialFilter::None); }},
      {"eaw", [] { return stages("eaw", false, SpatialFilter::Eaw); }},
      {"eaw-accum", [] { return stages("eaw-accum", true, SpatialFilter::Eaw); }},
      {"none", [] { return stages("none", false, SpatialFilter::None, false); }},
      // TRMV is not one of SVGF's pipelines: its own class (filters/trmv/trmv.h).
      {"trmv", nullptr, [](MethodParams&) {},
       [](const MethodParams& p) -> std::unique_ptr<Method> { return std::make_unique<TrmvFilter>(p); },
       [](MethodParams& p, const std::string& key, double value) { return set_param(p.trmv, key, value); },
       [](const MethodParams& p) { return describe_params(trmv_param_table(), param_values(p.trmv)); }},
  };
  return methods;
}

// The registry's entry of method `name`; throws rtdr::Error listing the known names when there is none.
const MethodEntry& find_method(const std::string& name) {
  for (const MethodEntry& m : registry())
    if (name == m.name) return m;
  std::string known;
  for (const std::string& n : method_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("--method '" + name + "' is not one of: " + known);
}

}  // namespace

Probe Method::probe(const std::string& pass, int x, int y, const std::string& stream, int level) const {
  return log_.probe(pass, stream, level, x, y);
}

double Method::time_pass(const std::string& pass, const std::function<void()>& run) {
  const auto start = std::chrono::steady_clock::now();
  run();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  times_[pass] += ms;
  return ms;
}

std::unique_ptr<Method> Method::clone() const {
  throw Error("method " + name() + " on this back end cannot be copied");
}

InputChannels common_input_channels(const std::vector<std::string>& illumination) {
  InputChannels c;
  c.floats = {"depth.Z",  "depth.dX", "depth.dY", "normal.X",   "normal.Y",   "normal.Z",  "motion.X",
              "motion.Y", "albedo.R", "albedo.G", "albedo.B",   "emission.R", "emission.G", "emission.B"};
  c.floats.insert(c.floats.end(), illumination.begin(), illumination.end());
  c.uints = {"id.mesh"};
  for (const char* channel : {"emission.R", "emission.G", "emission.B", "indirect.R", "indirect.G", "indirect.B"})
    c.defaults[channel] = 0.0f;
  return c;
}

std::string missing_layer_fix(const std::string& layer) {
  if (layer == "gradient")  // trace/gradients.h
    return "render the frames with `rtdr render --gradients` (A-SVGF's gradient samples)";
  if (layer == "direct.shading")  // trace/shading.h; kTrmvShadingSamples is what rtdr eval renders
    return "render the frames with `rtdr render --shading-samples N` (TRMV's shading term; rtdr eval uses 64)";
  return "";
}

void fill_input_defaults(Frame& frame, const InputChannels& channels) {
  for (const auto& [name, value] : channels.defaults)
    if (!frame.has(name)) frame.add_float(name, value);
}

double total_ms(const PassTimes& times) {
  double total = 0.0;
  for (const auto& [pass, ms] : times)
    if (pass != kTransferPass) total += ms;
  return total;
}

bool Method::reads_gradient_samples() const {
  const std::vector<std::string> uints = inputs().uints;
  return std::find(uints.begin(), uints.end(), "gradient.source") != uints.end();
}

bool Method::reads_shading_term() const {
  const std::vector<std::string> floats = inputs().floats;
  return std::find(floats.begin(), floats.end(), "direct.shading.R") != floats.end();
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const MethodEntry& m : registry()) names.push_back(m.name);
  return names;
}

bool is_svgf_pipeline(const std::string& name) { return bool(find_method(name).options); }

SvgfOptions method_options(const std::string& name, const MethodParams& params) {
  const MethodEntry& m = find_method(name);
  if (!m.options) throw Error("method " + name + " is not one of SVGF's pipelines: it has a class of its own");
  SvgfOptions options = m.options();
  options.svgf = params.svgf;
  options.asvgf = params.asvgf;
  options.eaw = params.eaw;
  options.tonemap = params.tonemap;
  options.taa_params = params.taa;
  return options;
}

MethodParams method_defaults(const std::string& name) {
  MethodParams params;
  find_method(name).defaults(params);
  return params;
}

bool set_method_param(const std::string& name, MethodParams& params, const std::string& key, double value) {
  const MethodEntry& m = find_method(name);
  return (m.own_params && m.own_params(params, key, value)) || set_param(params.svgf, key, value) ||
         set_param(params.asvgf, key, value) || set_param(params.trmv, key, value);
}

std::string describe_method_params(const std::string& name, const MethodParams& params) {
  const MethodEntry& m = find_method(name);
  if (m.describe) return m.describe(params);
  // SVGF's pipelines: SVGF's table where a temporal or spatial stage runs, and A-SVGF's where it adapts alpha.
  const SvgfOptions options = m.options();
  std::string text = options.temporal || options.spatial != SpatialFilter::None ? describe(params.svgf) : "";
  if (options.adaptive) text += describe_params(asvgf_param_table(), param_values(params.asvgf));
  return text;
}

std::unique_ptr<Method> make_method(const std::string& name) { return make_method(name, method_defaults(name)); }

std::unique_ptr<Method> make_method(const std::string& name, const MethodParams& params) {
  const MethodEntry& m = find_method(name);
  if (m.make) return m.make(params);
  return std::make_unique<SvgfFilter>(method_options(name, params));
}

}  // namespace rtdr
