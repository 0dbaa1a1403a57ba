// The sequence `rtdr view` serves, filtered once. See view_sequence.h.
#include "app/view_sequence.h"

#include "app/backend.h"
#include "app/probe_report.h"
#include "app/sequence.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/memory_budget.h"
#include "eval/experiment.h"
#include "eval/metrics.h"
#include "filters/image.h"
#include "filters/passes.h"
#include "filters/svgf/tonemap.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <unistd.h>

namespace rtdr {
namespace {

namespace fs = std::filesystem;

// Throws unless `file`, with every symlink on its way resolved, lies inside `dir` (resolved alike).
void require_inside(const std::string& dir, const std::string& file, const std::string& flag) {
  std::error_code dir_error, file_error;
  const fs::path root = fs::canonical(dir, dir_error), target = fs::canonical(file, file_error);
  if (dir_error || file_error)
    throw Error(flag + ": cannot resolve '" + file + "': " + (dir_error ? dir_error : file_error).message());
  const auto [end, unused] = std::mismatch(root.begin(), root.end(), target.begin(), target.end());
  if (end != root.end())
    throw Error(flag + ": '" + file + "' leads out of '" + dir + "' (to '" + target.string() +
                "'): rtdr view reads only files inside the folders it is given");
}

// The resident memory of this process, in bytes (Linux's /proc).
size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * size_t(sysconf(_SC_PAGESIZE));
}

// A frame with only `channels` of `from`: what the view keeps of an input frame (the layers the method reads).
Frame keep_channels(const Frame& from, const InputChannels& channels) {
  Frame kept(from.width(), from.height());
  kept.attributes = from.attributes;
  kept.source = from.source;
  for (const std::string& name : channels.floats) kept.add_float(name).data = from.float_channel(name).data;
  return kept;
}

const char* const kRgbSuffixes[] = {"R", "G", "B"};
const char* const kVectorSuffixes[] = {"X", "Y", "Z"};

// The layers made of `channels`: name.R/G/B as one RGB layer, name.X/Y(/Z) as one vector layer, any other channel
// (and a lone name.X) as a scalar layer of its own name. In the order of their first channel.
nlohmann::json group_layers(const std::vector<std::string>& channels) {
  std::vector<std::pair<std::string, std::vector<std::string>>> groups;  // prefix, suffixes
  for (const std::string& c : channels) {
    const size_t dot = c.rfind('.');
    const std::string suffix = dot == std::string::npos ? "" : c.substr(dot + 1);
    const bool component = suffix.size() == 1 && std::strchr("RGBXYZ", suffix[0]) != nullptr;
    const std::string prefix = component ? c.substr(0, dot) : c;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == prefix; });
    if (it == groups.end()) it = groups.insert(groups.end(), {prefix, {}});
    if (component) it->second.push_back(suffix);
  }
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& [prefix, suffixes] : groups) {
    if (suffixes.size() == 1) {
      layers.push_back({{"name", prefix + "." + suffixes[0]}, {"kind", "scalar"}});
      continue;
    }
    const char* kind = suffixes.empty() ? "scalar" : suffixes[0] == "R" ? "rgb" : "vector";
    layers.push_back({{"name", prefix}, {"kind", kind}});
  }
  return layers;
}

// The layers of pass `pass` that `frame` holds: each declared layer for every stream of `streams` and every level
// it was written for. (The frame is the method's output and dump: the dump holds what the pass log logged, the
// output the colour and display that modulate, tone map and TAA make.)
nlohmann::json pass_layers(const PassDecl& pass, const Frame& frame, const std::vector<std::string>& streams) {
  nlohmann::json layers = nlohmann::json::array();
  for (const LayerDecl* layer : pass.writes) {
    const bool per_stream = layer->pattern.find("<s>") != std::string_view::npos;
    const bool per_level = layer->pattern.find("<i>") != std::string_view::npos;
    for (const std::string& stream : per_stream ? streams : std::vector<std::string>{""}) {
      for (int level = per_level ? 0 : -1; level < (per_level ? 64 : 0); ++level) {
        const std::vector<std::string> channels = layer_channels(*layer, stream, level);
        const bool present = std::all_of(channels.begin(), channels.end(), [&](const auto& c) { return frame.has(c); });
        if (!present) break;
        layers.push_back({{"name", layer_name(*layer, stream, level)},
                          {"pattern", layer->pattern},
                          {"kind", layer->type == LayerType::Rgb ? "rgb" : "scalar"},
                          {"meaning", layer->meaning},
                          {"cite", layer->cite},
                          {"stream", stream},
                          {"level", std::max(level, 0)},
                          // Values the tone map made, in [0, 1]: shown without another tone map.
                          {"display_referred", layer->cite.find("Reinhard02") != std::string_view::npos}});
        if (!per_level) break;
      }
    }
  }
  return layers;
}

// The streams (or components) the passes of `log` ran on, in the order they first ran.
std::vector<std::string> log_streams(const PassLog& log) {
  std::vector<std::string> streams;
  for (const PassRun& run : log.runs())
    if (!run.stream().empty() && std::find(streams.begin(), streams.end(), run.stream()) == streams.end())
      streams.push_back(run.stream());
  return streams;
}

const char* scope_name(PassScope scope) {
  return scope == PassScope::Frame ? "frame" : scope == PassScope::Stream ? "stream" : "stream_level";
}

}  // namespace

std::optional<LayerSource> parse_layer_source(const std::string& name) {
  if (name == "input") return LayerSource::Input;
  if (name == "golden") return LayerSource::Golden;
  if (name == "port") return LayerSource::Port;
  if (name == "ref") return LayerSource::Reference;
  return std::nullopt;
}

std::optional<LayerPlanes> layer_planes(const Frame& frame, const std::string& name) {
  LayerPlanes out{frame.width(), frame.height(), {}, {}};
  for (const auto& suffixes : {kRgbSuffixes, kVectorSuffixes}) {
    for (int i = 0; i < 3; ++i)
      if (frame.float_channels().count(name + "." + suffixes[i])) out.channels.push_back(suffixes[i]);
    if (out.channels.size() >= 2) break;
    out.channels.clear();
  }
  if (out.channels.empty()) {
    if (!frame.float_channels().count(name)) return std::nullopt;
    out.channels.push_back("");
  }
  for (const std::string& c : out.channels) {
    const FloatPlane& plane = frame.float_channel(c.empty() ? name : name + "." + c);
    out.bytes.append(reinterpret_cast<const char*>(plane.data.data()), plane.data.size() * sizeof(float));
  }
  return out;
}

ViewSequence::ViewSequence(const ViewOptions& o, const std::function<void(const std::string&)>& progress)
    : options_(o) {
  std::unique_ptr<Method> method = make_method(o.method, o.params);
  const std::vector<SequenceFrame> all = list_sequence(o.in, "");
  const std::vector<SequenceFrame> viewed = list_sequence(o.in, o.frames);
  const InputChannels inputs = method->inputs();
  SequenceShape shape;
  const size_t resident_at_start = resident_bytes();
  for (const SequenceFrame& f : all) {
    if (f.index > viewed.back().index) break;
    require_inside(o.in, f.path, "--in");
    const auto start = std::chrono::steady_clock::now();
    const Frame in = read_filter_input(f.path, shape, inputs);
    // The history of a viewed frame is built by every frame before it, as rtdr probe builds it.
    if (f.index < viewed.front().index) {
      method->filter(in);
      progress("frame " + std::to_string(f.index) + "  filtered for history");
      continue;
    }
    // The frame is filtered by a copy of the method, which the view keeps: its pass log, which the probe reads,
    // points at its own planes. The method goes on from a copy of it.
    FrameState& s = frames_.emplace_back();
    s.index = f.index;
    s.state = method->clone();
    s.golden = filter_with_dump(*s.state, in);
    method = s.state->clone();
    s.input = keep_channels(in, inputs);
    if (!o.port_dumps.empty()) {
      const std::string path = frame_path(o.port_dumps, f.index, "exr");
      if (!fs::exists(path)) throw Error("--port-dumps '" + o.port_dumps + "' has no " + frame_name(f.index, "exr"));
      require_inside(o.port_dumps, path, "--port-dumps");
      s.port = read_exr(path);
      require_same_size(s.port, in);
    }
    if (!o.ref.empty()) add_reference(s);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    char line[96];
    std::snprintf(line, sizeof line, "frame %d  %.0f ms", f.index, ms);
    progress(line);
    // After the first viewed frame: would all of them fit? Each keeps about as much as the first did.
    if (frames_.size() == 1) {
      const size_t per_frame = resident_bytes() > resident_at_start ? resident_bytes() - resident_at_start : 0;
      require_within_budget(saturating_product(per_frame, viewed.size() - 1),
                            "keeping " + std::to_string(viewed.size()) + " frames of " + std::to_string(in.width()) +
                                "x" + std::to_string(in.height()) + " (view fewer with --frames A-B)",
                            memory_budget());
    }
  }
  make_info();
}

void ViewSequence::add_reference(FrameState& s) const {
  const std::string path = frame_path(options_.ref, s.index, "exr");
  if (!fs::exists(path)) throw Error("--ref '" + options_.ref + "' has no " + frame_name(s.index, "exr"));
  require_inside(options_.ref, path, "--ref");
  const Frame ref = read_exr(path);
  require_same_size(ref, s.input);
  // As rtdr eval measures: colour against the reference's colour, display (TAA included) against the reference
  // tone mapped with the same operator (eval/experiment.h).
  const RgbPlane ref_colour = frame_colour(ref), ref_display = tonemap(ref_colour, options_.params.tonemap);
  const RgbPlane colour = rgb_plane(s.golden, "color"), display = rgb_plane(s.golden, "display");
  FlipResult flipped = flip(display, ref_display);
  s.reference = Frame(ref.width(), ref.height());
  set_rgb_plane(s.reference, "color", ref_colour);
  set_rgb_plane(s.reference, "display", ref_display);
  set_float_plane(s.reference, "error.flip", flipped.map);
  s.metrics = {{"rmse", rmse(colour, ref_colour)},
               {"relmse", relmse(colour, ref_colour)},
               {"ssim", ssim(display, ref_display)},
               {"flip", flipped.mean}};
}

void ViewSequence::make_info() {
  const FrameState& first = frames_.front();
  const std::vector<std::string> streams = log_streams(first.state->passes());
  info_ = {{"method", options_.method},
           {"in", options_.in},
           {"width", first.input.width()},
           {"height", first.input.height()},
           {"streams", streams},
           {"reference", !options_.ref.empty()},
           {"port", !options_.port_dumps.empty()},
           {"frames", nlohmann::json::array()}};
  for (const FrameState& f : frames_) info_["frames"].push_back(f.index);
  const auto stratum = first.input.attributes.find("rtdr.gradient.stratum_size");
  info_["stratum_size"] = stratum == first.input.attributes.end() ? 0 : std::atoi(stratum->second.c_str());
  // First what the method reads, then each pass it runs, in order, with the layers it wrote.
  nlohmann::json groups = nlohmann::json::array();
  groups.push_back({{"name", "input"},
                    {"source", "input"},
                    {"probe", false},
                    {"cite", ""},
                    {"description", "the layers the method reads from --in (docs/buffers.md)"},
                    {"layers", group_layers(first.state->inputs().floats)}});
  for (const std::string& name : first.state->probe_passes()) {
    const PassDecl& pass = find_pass(name);
    groups.push_back({{"name", name},
                      {"source", "golden"},
                      {"probe", true},
                      {"cite", pass.cite},
                      {"golden", pass.golden},
                      {"scope", scope_name(pass.scope)},
                      {"reads", pass.reads},
                      {"description", pass.probe},
                      {"layers", pass_layers(pass, first.golden, streams)}});
  }
  // What the passes probed do not list (trmv's colour and display, made by passes it does not probe): "output".
  std::set<std::string> listed;
  for (const nlohmann::json& group : groups)
    for (const nlohmann::json& layer : group.at("layers")) listed.insert(layer.at("name").get<std::string>());
  std::vector<std::string> unlisted;
  for (const auto& [channel, plane] : first.golden.float_channels()) {
    const size_t dot = channel.rfind('.');
    if (!listed.count(channel) && (dot == std::string::npos || !listed.count(channel.substr(0, dot))))
      unlisted.push_back(channel);
  }
  if (!unlisted.empty())
    groups.push_back({{"name", "output"},
                      {"source", "golden"},
                      {"probe", false},
                      {"cite", ""},
                      {"description", "the method's other output layers (docs/buffers.md)"},
                      {"layers", group_layers(unlisted)}});
  if (!options_.ref.empty())
    groups.push_back({{"name", "reference"},
                      {"source", "ref"},
                      {"probe", false},
                      {"cite", "[FLIP20]"},
                      {"description", "the reference (--ref) and the FLIP map of display against it (eval/metrics.h)"},
                      {"layers", nlohmann::json::array({{{"name", "color"}, {"kind", "rgb"}},
                                                        {{"name", "display"}, {"kind", "rgb"}, {"display_referred", true}},
                                                        {{"name", "error.flip"}, {"kind", "scalar"}}})}});
  info_["groups"] = std::move(groups);
}

const ViewSequence::FrameState* ViewSequence::find(int frame) const {
  for (const FrameState& f : frames_)
    if (f.index == frame) return &f;
  return nullptr;
}

std::optional<LayerPlanes> ViewSequence::layer(LayerSource source, int frame, const std::string& name) const {
  const FrameState* f = find(frame);
  if (!f) return std::nullopt;
  switch (source) {
    case LayerSource::Input: return layer_planes(f->input, name);
    case LayerSource::Golden: return layer_planes(f->golden, name);
    case LayerSource::Port: return layer_planes(f->port, name);
    case LayerSource::Reference: return layer_planes(f->reference, name);
  }
  return std::nullopt;
}

std::string ViewSequence::probe_json(int frame, int x, int y, const std::string& pass, const std::string& stream,
                                     int level) const {
  const FrameState* f = find(frame);
  if (!f)
    throw Error("frame " + std::to_string(frame) + " is not one of the frames viewed (" +
                std::to_string(frames_.front().index) + "-" + std::to_string(frames_.back().index) + ")");
  return probe_json_text({options_.method, frame, x, y, pass, stream, level}, f->state->probe(pass, x, y, stream, level));
}

nlohmann::json ViewSequence::metrics(int frame) const {
  const FrameState* f = find(frame);
  return f ? f->metrics : nlohmann::json();
}

}  // namespace rtdr
