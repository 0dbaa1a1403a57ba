// What rtdr view keeps of a sequence (app/view_sequence.h): a layer's planes as the page gets them, and the copy of
// the method per frame, which must probe exactly as `rtdr probe` does after filtering frames 0 to F.
#include "app/backend.h"
#include "app/probe_report.h"
#include "app/sequence.h"
#include "app/view_sequence.h"
#include "cli_fixtures.h"
#include "core/error.h"
#include "core/exr_io.h"

#include <catch2/catch.hpp>

#include <cstring>

namespace fs = std::filesystem;
using namespace rtdr;

namespace {

std::vector<float> floats_of(const std::string& bytes) {
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

// A rendered cornell sequence, 3 frames at 32x18, made once.
const fs::path& sequence() {
  static const fs::path dir = [] {
    const fs::path d = cli::scratch("rtdr_view_sequence_test", "sequence");
    const cli::RunResult r = cli::run_rtdr("render --scene cornell --frames 0-2 --size 32x18 --out " + (d / "in").string(), d);
    REQUIRE(r.exit_code == 0);
    return d / "in";
  }();
  return dir;
}

}  // namespace

TEST_CASE("layer_planes: RGB, vector and scalar layers as planar float32, channel by channel") {
  Frame f(2, 1);
  f.add_float("a.R", 1.0f);
  f.add_float("a.G", 2.0f);
  f.add_float("a.B", 3.0f);
  f.add_float("m.X", -1.5f);
  f.add_float("m.Y", 0.25f);
  f.add_float("depth.Z", 7.0f);
  f.add_float("s", 0.5f).data[1] = 4.0f;
  f.add_uint("id.mesh", 3);

  const auto a = layer_planes(f, "a");
  REQUIRE(a);
  CHECK(a->channels == std::vector<std::string>{"R", "G", "B"});
  CHECK(floats_of(a->bytes) == std::vector<float>{1, 1, 2, 2, 3, 3});
  const auto m = layer_planes(f, "m");
  REQUIRE(m);
  CHECK(m->channels == std::vector<std::string>{"X", "Y"});
  CHECK(floats_of(m->bytes) == std::vector<float>{-1.5f, -1.5f, 0.25f, 0.25f});
  const auto s = layer_planes(f, "s");
  REQUIRE(s);
  CHECK(s->channels == std::vector<std::string>{""});
  CHECK(floats_of(s->bytes) == std::vector<float>{0.5f, 4.0f});
  CHECK(layer_planes(f, "depth.Z"));   // a lone channel is a scalar layer of its own name
  CHECK_FALSE(layer_planes(f, "depth"));  // one component is not a vector
  CHECK_FALSE(layer_planes(f, "id.mesh"));  // uint channels are not layers the page draws
  CHECK_FALSE(layer_planes(f, "nothing"));
}

TEST_CASE("rtdr view's copy of the method after frame F probes as rtdr probe does after filtering frames 0 to F") {
  ViewOptions o;
  o.method = "svgf";
  o.in = sequence().string();
  o.params = method_defaults("svgf");
  const ViewSequence view(o, [](const std::string&) {});
  REQUIRE(view.frame_count() == 3);

  // rtdr probe's way: one method, frames 0 to 2 filtered in order, then the probe. The view's copies were made
  // after frames 1 and 2 while the method went on: each must still hold its own frame.
  for (int frame : {1, 2}) {
    const std::unique_ptr<Method> method = make_method("svgf", o.params);
    SequenceShape shape;
    Frame last;
    for (const SequenceFrame& f : list_sequence(o.in, "0-" + std::to_string(frame)))
      last = filter_with_dump(*method, read_filter_input(f.path, shape, method->inputs()));
    for (const auto& [pass, level] : std::vector<std::pair<std::string, int>>{{"temporal", 0}, {"atrous", 2}, {"taa", 0}}) {
      INFO("frame " << frame << ", pass " << pass);
      const Probe probe = method->probe(pass, 16, 9, "direct", level);
      CHECK(view.probe_json(frame, 16, 9, pass, "direct", level) ==
            probe_json_text({"svgf", frame, 16, 9, pass, "direct", level}, probe));
    }
    // And its layers are that frame's.
    const auto level1 = view.layer(LayerSource::Golden, frame, "filter.direct.level1");
    REQUIRE(level1);
    std::vector<float> expected;
    for (const char* c : {".R", ".G", ".B"}) {
      const std::vector<float>& d = last.float_channel(std::string("filter.direct.level1") + c).data;
      expected.insert(expected.end(), d.begin(), d.end());
    }
    CHECK(floats_of(level1->bytes) == expected);
  }
  CHECK_FALSE(view.layer(LayerSource::Golden, 7, "color"));
  CHECK_FALSE(view.layer(LayerSource::Port, 1, "color"));  // no --port-dumps
  CHECK_THROWS_WITH(view.probe_json(7, 16, 9, "atrous", "direct", 0), Catch::Contains("not one of the frames viewed"));
  CHECK(view.metrics(1).is_null());  // no --ref

  // The info lists the passes in the method's order, each with its layers.
  const nlohmann::json& groups = view.info().at("groups");
  std::vector<std::string> names;
  for (const nlohmann::json& g : groups) names.push_back(g.at("name"));
  std::vector<std::string> expected_names{"input"};
  for (const std::string& p : make_method("svgf")->probe_passes()) expected_names.push_back(p);
  CHECK(names == expected_names);
}

TEST_CASE("rtdr view refuses a --ref or --port-dumps without the frame, and --frames outside --in") {
  ViewOptions o;
  o.in = sequence().string();
  const fs::path dir = cli::scratch("rtdr_view_sequence_test", "refuse");
  fs::create_directories(dir / "ref");
  fs::copy_file(sequence() / "frame_0000.exr", dir / "ref" / "frame_0000.exr");
  o.ref = (dir / "ref").string();
  CHECK_THROWS_WITH(ViewSequence(o, [](const std::string&) {}), Catch::Contains("has no frame_0001.exr"));
  o.ref.clear();
  o.port_dumps = (dir / "ref").string();
  CHECK_THROWS_WITH(ViewSequence(o, [](const std::string&) {}), Catch::Contains("--port-dumps"));
  o.port_dumps.clear();
  o.frames = "2-5";
  CHECK_THROWS_AS(ViewSequence(o, [](const std::string&) {}), Error);
}
