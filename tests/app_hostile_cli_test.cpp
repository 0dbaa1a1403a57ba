// Hostile input, our own cases: what a careless or malicious user can hand `rtdr` in scenes, options, filter
// inputs, probe, compare, eval and bench, run through the real binary (RTDR_EXE) with an argument vector (no
// shell). The defects that docs/reliability.md closed are app_hostile_input_test.cpp; the outcomes every case
// must end in are in hostile_fixtures.h. Labelled `hostile`: `ctest -L hostile`.
#include "hostile_fixtures.h"

using namespace hostile;

// ---- Our own: scenes ----

TEST_CASE("render: a missing scene, a folder, an empty file and binary garbage are refused") {
  const fs::path dir = scratch("bad_scenes");
  fs::create_directories(dir / "folder.gltf");
  std::ofstream(dir / "empty.gltf").close();
  std::ofstream(dir / "garbage.glb", std::ios::binary) << std::string("glTF\x02\0\0\0\xff\xff\xff\x7f", 12);
  std::ofstream(dir / "garbage.gltf", std::ios::binary) << std::string("\0\x01\x02\xff", 4);
  for (const fs::path& scene : {dir / "missing.gltf", dir / "folder.gltf", dir / "empty.gltf", dir / "garbage.glb",
                               dir / "garbage.gltf"}) {
    INFO(scene);
    require_refused(render(dir, {"--scene", scene.string(), "--frames", "0", "--size", "8x8", "--out",
                                 (dir / "out").string()}), dir / "out");
  }
}

TEST_CASE("render: a scene whose accessor points past its buffer is refused") {
  const fs::path dir = scratch("bad_accessor");
  json scene = scene_json("cornell");
  scene["accessors"][0]["count"] = 1 << 30;
  require_refused(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                               "--out", (dir / "out").string()}), dir / "out");
}

TEST_CASE("render: a scene with a NaN-free but absurd transform (scale 1e30) renders finite frames or is refused") {
  const fs::path dir = scratch("huge_scale");
  json scene = scene_json("cornell");
  scene["nodes"][1]["scale"] = {1e30, 1e30, 1e30};
  const RunResult r = render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                                   "--out", (dir / "out").string()});
  if (r.exit_code == 0)
    require_finite_frames(r, dir / "out", 1);
  else
    require_refused(r, dir / "out");
}

TEST_CASE("render: a scene without a camera is refused") {
  const fs::path dir = scratch("no_camera");
  json scene = scene_json("cornell");
  scene.erase("cameras");
  for (json& node : scene["nodes"]) node.erase("camera");
  require_refused(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                               "--out", (dir / "out").string()}), dir / "out", "camera");
}

// ---- Our own: render options ----

TEST_CASE("render: malformed and out-of-range --size is refused") {
  const fs::path dir = scratch("bad_size");
  for (const char* size : {"0x0", "-5x5", "100000x10", "10x", "x10", " 10x10", "10X10", "10x10x10", "1e3x10"}) {
    INFO("'" << size << "'");
    require_refused(render(dir, {"--scene", "cornell", "--frames", "0", "--size", size, "--out",
                                 (dir / "out").string()}), dir / "out", "--size");
  }
}

TEST_CASE("render: odd resolutions (1x1, 33x17, 7x1) render finite frames") {
  for (const char* size : {"1x1", "33x17", "7x1"}) {
    INFO(size);
    const fs::path dir = scratch("odd_size");
    require_finite_frames(render(dir, {"--scene", "cornell", "--frames", "0", "--size", size, "--out",
                                       (dir / "out").string()}), dir / "out", 1);
  }
}

TEST_CASE("render: --spp 0, --max-bounces -1 and --threads -1 are refused") {
  const fs::path dir = scratch("bad_numbers");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"render", "--spp", "0"}, {"render", "--max-bounces", "-1"}, {"--threads", "-1", "render"},
           {"render", "--spp", "1.5"}, {"render", "--seed", "-1"}}) {
    std::vector<std::string> full = args;
    for (const char* a : {"--scene", "cornell", "--frames", "0", "--size", "8x8", "--out"}) full.push_back(a);
    full.push_back((dir / "out").string());
    INFO(full[0] << " " << full[1] << " " << full[2]);
    require_refused(run_rtdr_args(full, dir), dir / "out");
  }
}

TEST_CASE("rtdr: an unknown subcommand, an unknown flag and no subcommand are refused") {
  const fs::path dir = scratch("bad_cli");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"paint"}, {"render", "--colour", "red"}, {}, {"render", "--out"}}) {
    require_refused(run_rtdr_args(args, dir), dir / "out");
  }
}

// ---- Our own: filter inputs ----

TEST_CASE("filter: a missing --in, an empty folder and a folder of non-frames are refused") {
  const fs::path dir = scratch("bad_in");
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "other");
  std::ofstream(dir / "other" / "frame_a.exr") << "x";
  std::ofstream(dir / "other" / "notes.txt") << "x";
  for (const fs::path& in : {dir / "missing", dir / "empty", dir / "other"}) {
    INFO(in);
    require_refused(filter(in, dir / "out"), dir / "out", "--in");
  }
}

TEST_CASE("filter: a truncated EXR and a text file named frame_0001.exr are refused") {
  const fs::path in = changed_sequence("truncated", [](Frame&, int) {});
  const std::string bytes = read_text(in / "frame_0001.exr");
  std::ofstream(in / "frame_0001.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "frame_0001.exr");
  std::ofstream(in / "frame_0001.exr") << "not an EXR\n";
  require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "frame_0001.exr");
}

TEST_CASE("filter: frames of different sizes are refused") {
  const fs::path in = changed_sequence("sizes", [](Frame& f, int i) {
    if (i != 2) return;
    Frame smaller(f.width() - 1, f.height());
    for (const auto& [name, plane] : f.float_channels()) smaller.add_float(name);
    for (const auto& [name, plane] : f.uint_channels()) smaller.add_uint(name);
    f = smaller;
  });
  require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "same size");
}

TEST_CASE("filter: an unknown method, back end or --frames outside the sequence is refused") {
  const fs::path dir = scratch("bad_filter_flags");
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"--method", "magic"}, {"--backend", "metal"}, {"--frames", "1-5"}, {"--frames", "7"}}) {
    INFO(extra[0] << " " << extra[1]);
    require_refused(filter(sequence(), dir / "out", extra), dir / "out");
  }
}

TEST_CASE("filter: --out naming an existing file is refused and the file is kept") {
  const fs::path dir = scratch("out_is_file");
  std::ofstream(dir / "out.txt") << "keep";
  const RunResult r = filter(sequence(), dir / "out.txt");
  CHECK(r.exit_code == 1);
  CHECK(read_text(dir / "out.txt") == "keep");
  CHECK_FALSE(staging_left(dir));
}

TEST_CASE("filter: every method on a sequence of odd size (33x17) gives finite frames") {
  const fs::path dir = scratch("odd_filter");
  REQUIRE(render(dir, {"--scene", "pillars", "--frames", "0-1", "--size", "33x17", "--out", (dir / "in").string()})
              .exit_code == 0);
  for (const char* method : {"svgf", "accum", "eaw", "eaw-accum", "none"}) {
    INFO(method);
    fs::remove_all(dir / "out");
    require_finite_frames(filter(dir / "in", dir / "out", {"--method", method}), dir / "out", 2);
  }
}

TEST_CASE("filter: frames of zero radiance, albedo and emission give finite frames (no 0/0)") {
  const fs::path in = changed_sequence("zeros", [](Frame& f, int) {
    for (const char* layer : {"direct", "indirect", "albedo", "emission"})
      for (const char* c : {".R", ".G", ".B"})
        for (float& v : f.float_channel(std::string(layer) + c).data) v = 0.0f;
  });
  require_finite_frames(filter(in, in.parent_path() / "out"), in.parent_path() / "out", 3);
}

// ---- Our own: probe and compare ----

TEST_CASE("probe: an unknown pass, stream, level or frame is refused") {
  const fs::path dir = scratch("bad_probe");
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"--pass", "magic"}, {"--stream", "sideways"}, {"--level", "99"}, {"--level", "-1"}, {"--frame", "9"}}) {
    INFO(extra[0] << " " << extra[1]);
    std::vector<std::string> args = {"probe", "--in", sequence().string(), "--pixel", "3,3"};
    if (extra[0] != "--frame") args.insert(args.end(), {"--frame", "1"});
    args.insert(args.end(), extra.begin(), extra.end());
    require_refused(run_rtdr_args(args, dir), dir / "out");
  }
}

TEST_CASE("compare: --rel-floor 0 or negative and --max-rel-error -1 are refused") {
  const fs::path dir = scratch("bad_compare");
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"--rel-floor", "0"}, {"--rel-floor", "-1"}, {"--max-rel-error", "-1"}}) {
    INFO(extra[0] << " " << extra[1]);
    std::vector<std::string> args = {"compare", "--in", sequence().string(), "--csv", (dir / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    require_refused(run_rtdr_args(args, dir), dir / "out");
  }
}

TEST_CASE("eval: a size smaller than the SSIM window is refused before anything is rendered") {
  const fs::path dir = scratch("eval_small");
  const RunResult r = run_rtdr_args({"eval", "--scene", "cornell", "--methods", "none", "--frames", "0-1", "--size",
                                     "16x9", "--cache", (dir / "cache").string(), "--out", (dir / "out").string()}, dir);
  require_refused(r, dir / "out", "11x11");
  CHECK(r.err.find("%") == std::string::npos);  // no progress: nothing was rendered
  CHECK_FALSE(fs::exists(dir / "cache"));
}

TEST_CASE("bench: an unknown stage or back end is refused") {
  const fs::path dir = scratch("bad_bench");
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"--stage", "paint"}, {"--backend", "metal"}, {"--size", "0x0"}}) {
    INFO(extra[0] << " " << extra[1]);
    std::vector<std::string> args = {"bench", "--csv", (dir / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    require_refused(run_rtdr_args(args, dir), dir / "out");
  }
}
