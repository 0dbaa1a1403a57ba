// Hostile input, the defects that docs/reliability.md closed: what a careless or malicious user can hand `rtdr`,
// run through the real binary (RTDR_EXE) with an argument vector (no shell, so quotes and "$(...)" reach rtdr as
// they are). Our own further cases are app_hostile_cli_test.cpp; the outcomes every case must end in are in
// hostile_fixtures.h. Labelled `hostile`: `ctest -L hostile`. docs/reliability.md lists the promises they keep.
#include "hostile_fixtures.h"

using namespace hostile;

// ---- Defect 1: the shell injection in rtdr eval ----

TEST_CASE("eval: a quote, a semicolon and $(...) in --out and --scene are only names") {
  const fs::path dir = scratch("eval_quote");
  const fs::path scene = write_scene(dir, scene_json("cornell"), "it's; $(touch pwned_scene).gltf");
  const fs::path out = dir / "o'; touch pwned_out; echo '";
  const RunResult r = run_rtdr_args({"eval", "--scene", scene.string(), "--methods", "none", "--frames", "0-1",
                                     "--size", "16x12", "--ref-spp", "1", "--cache", "", "--out", out.string()}, dir);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(files_in(out) == std::set<std::string>{"error_over_frames.png", "metrics.csv", "speed_vs_accuracy.png",
                                               "strip.png", "temporal_error.png"});
  for (const fs::path& cwd : {dir, fs::current_path()}) {
    CHECK_FALSE(fs::exists(cwd / "pwned_out"));
    CHECK_FALSE(fs::exists(cwd / "pwned_scene"));
  }
}

TEST_CASE("eval: a chart step that fails (disk full) is one line and leaves no output, no 0-byte PNG") {
  const fs::path dir = scratch("eval_disk_full");
  // The real matplotlib, whose savefig starts the file and then fails as a full disk does: a sitecustomize on
  // PYTHONPATH patches Figure.savefig before charts.py runs.
  fs::create_directories(dir / "fake");
  std::ofstream(dir / "fake" / "sitecustomize.py")
      << "import errno\n"
         "import matplotlib\n"
         "matplotlib.use('Agg')\n"
         "import matplotlib.figure\n"
         "def _full_disk(self, fname, *a, **k):\n"
         "    open(fname, 'wb').close()\n"
         "    raise OSError(errno.ENOSPC, 'No space left on device')\n"
         "matplotlib.figure.Figure.savefig = _full_disk\n";
  const fs::path out = dir / "out";
  const RunResult r = run_rtdr_args({"eval", "--scene", "cornell", "--methods", "none", "--frames", "0-1", "--size",
                                     "16x12", "--ref-spp", "1", "--cache", "", "--out", out.string()},
                                    dir, {"PYTHONPATH=" + (dir / "fake").string()});
  require_refused(r, out, "No space left on device");
}

TEST_CASE("eval: a rerun that fails keeps the previous run's outputs as they were") {
  const fs::path dir = scratch("eval_rerun");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::ofstream(out / "metrics.csv") << "the previous run\n";
  const RunResult r = run_rtdr_args({"eval", "--scene", "cornell", "--methods", "svgf:alpha=2", "--frames", "0-1",
                                     "--size", "16x12", "--out", out.string()}, dir);
  CHECK(r.exit_code == 1);
  CHECK(read_text(out / "metrics.csv") == "the previous run\n");
  CHECK(files_in(out) == std::set<std::string>{"metrics.csv"});
}

// ---- Defect 2: frame ranges ----

TEST_CASE("render: --frames 2147483647 is refused before any frame is rendered") {
  const fs::path dir = scratch("frames_max");
  require_refused(render(dir, {"--scene", "cornell", "--frames", "2147483647", "--size", "8x8", "--out",
                               (dir / "out").string()}), dir / "out", "999999");
}

TEST_CASE("render: --frames 0-2147483647 and 999999-1000000 are refused") {
  const fs::path dir = scratch("frames_range");
  for (const char* frames : {"0-2147483647", "999999-1000000", "0-99999999999"}) {
    INFO(frames);
    require_refused(render(dir, {"--scene", "cornell", "--frames", frames, "--size", "8x8", "--out",
                                 (dir / "out").string()}), dir / "out");
  }
}

TEST_CASE("render: frame 999999, the largest, renders") {
  const fs::path dir = scratch("frames_last");
  const RunResult r = render(dir, {"--scene", "cornell", "--frames", "999999", "--size", "4x4", "--out",
                                   (dir / "out").string()});
  require_finite_frames(r, dir / "out", 1);
  CHECK(fs::exists(dir / "out" / "frame_999999.exr"));
}

TEST_CASE("render: malformed and reversed --frames are refused") {
  const fs::path dir = scratch("frames_bad");
  for (const char* frames : {"", "5-3", "-1", "1-2-3", "a-b", " 1", "1 ", "+1", "0x10"}) {
    INFO("'" << frames << "'");
    require_refused(render(dir, {"--scene", "cornell", "--frames", frames, "--size", "8x8", "--out",
                                 (dir / "out").string()}), dir / "out");
  }
}

// ---- Defect 3: a failed run leaves no output at all ----

TEST_CASE("filter: frame 2 without id.mesh fails before frames 0 and 1 are written") {
  const fs::path in = changed_sequence("no_id_mesh", [](Frame& f, int i) {
    if (i == 2) f = without(f, "id.mesh");
  });
  require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "id.mesh");
}

TEST_CASE("filter: an id channel stored as float is refused") {
  const fs::path in = changed_sequence("float_id", [](Frame& f, int i) {
    if (i != 1) return;
    const std::vector<uint32_t> ids = f.uint_channel("id.mesh").data;
    f = without(f, "id.mesh");
    rtdr::FloatPlane& plane = f.add_float("id.mesh");
    for (size_t k = 0; k < ids.size(); ++k) plane.data[k] = float(ids[k]);
  });
  require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "as float");
}

TEST_CASE("filter --method eaw: frame 2 without position fails before anything is written") {
  const fs::path in = changed_sequence("no_position", [](Frame& f, int i) {
    if (i == 2) f = without(f, "position.Y");
  });
  require_refused(filter(in, in.parent_path() / "out", {"--method", "eaw"}), in.parent_path() / "out", "position.Y");
}

TEST_CASE("filter: a failed rerun into an existing folder leaves its files as they were") {
  const fs::path in = changed_sequence("rerun", [](Frame& f, int i) {
    if (i == 2) f.float_channel("direct.G").data[3] = std::nanf("");
  });
  const fs::path out = in.parent_path() / "out";
  fs::create_directories(out);
  std::ofstream(out / "frame_0000.png") << "older";
  const RunResult r = filter(in, out);
  CHECK(r.exit_code == 1);
  CHECK(files_in(out) == std::set<std::string>{"frame_0000.png"});
  CHECK(read_text(out / "frame_0000.png") == "older");
  CHECK_FALSE(staging_left(in.parent_path()));
}

TEST_CASE("render: --out below a file is refused before any frame is rendered, and the file is kept") {
  const fs::path dir = scratch("render_into_file");
  std::ofstream(dir / "a_file") << "x";
  require_refused(render(dir, {"--scene", "cornell", "--frames", "0", "--size", "8x8", "--out",
                               (dir / "a_file" / "out").string()}), dir / "a_file" / "out");
  CHECK(read_text(dir / "a_file") == "x");
}

// ---- Defect 4: non-finite values in and out ----

TEST_CASE("filter --method eaw: NaN in position is refused, naming the channel and pixel") {
  const fs::path in = changed_sequence("nan_position", [](Frame& f, int i) {
    if (i == 1) f.float_channel("position.X").data[5] = std::nanf("");
  });
  require_refused(filter(in, in.parent_path() / "out", {"--method", "eaw"}), in.parent_path() / "out",
                  "position.X");
}

TEST_CASE("filter: a depth gradient of 1e38 gives finite output or a one-line error") {
  const fs::path in = changed_sequence("huge_gradient", [](Frame& f, int) {
    for (float& v : f.float_channel("depth.dX").data) v = 1e38f;
  });
  const fs::path out = in.parent_path() / "out";
  const RunResult r = filter(in, out);
  if (r.exit_code == 0)
    require_finite_frames(r, out, 3);
  else
    require_refused(r, out, "pixel");
}

TEST_CASE("filter: radiance of 3e38 gives finite output or a one-line error naming the pass") {
  const fs::path in = changed_sequence("huge_radiance", [](Frame& f, int i) {
    if (i == 1) f.float_channel("indirect.R").data[7] = 3e38f;
  });
  const fs::path out = in.parent_path() / "out";
  const RunResult r = filter(in, out);
  if (r.exit_code == 0)
    require_finite_frames(r, out, 3);
  else
    require_refused(r, out, "pass");
}

TEST_CASE("filter: NaN, +Inf and -Inf radiance are refused") {
  for (const float bad : {std::nanf(""), INFINITY, -INFINITY}) {
    const fs::path in = changed_sequence("bad_radiance", [bad](Frame& f, int i) {
      if (i == 0) f.float_channel("direct.B").data[0] = bad;
    });
    require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "direct.B");
  }
}

TEST_CASE("filter: NaN in motion, normal or albedo is refused") {
  for (const char* channel : {"motion.X", "normal.Z", "albedo.R", "emission.G", "depth.Z"}) {
    INFO(channel);
    const fs::path in = changed_sequence("bad_gbuffer", [channel](Frame& f, int i) {
      if (i == 2) f.float_channel(channel).data[1] = std::nanf("");
    });
    require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", channel);
  }
}

TEST_CASE("filter: motion vectors pointing far outside the image give finite output") {
  const fs::path in = changed_sequence("wild_motion", [](Frame& f, int) {
    for (float& v : f.float_channel("motion.X").data) v = 1e30f;
    for (float& v : f.float_channel("motion.Y").data) v = -1e30f;
  });
  require_finite_frames(filter(in, in.parent_path() / "out"), in.parent_path() / "out", 3);
}

TEST_CASE("filter: negative albedo and radiance give finite output") {
  const fs::path in = changed_sequence("negative", [](Frame& f, int) {
    for (float& v : f.float_channel("albedo.G").data) v = -1.0f;
    for (float& v : f.float_channel("indirect.B").data) v = -5.0f;
  });
  require_finite_frames(filter(in, in.parent_path() / "out"), in.parent_path() / "out", 3);
}

// ---- Defect 5: input that must be refused ----

TEST_CASE("render: a glTF whose asset.version is not 2.x is refused") {
  const fs::path dir = scratch("gltf_version");
  for (const char* version : {"1.0", "3.0", "2", "2.x", "", "20.0"}) {
    INFO("'" << version << "'");
    json scene = scene_json("cornell");
    scene["asset"]["version"] = version;
    require_refused(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                                 "--out", (dir / "out").string()}), dir / "out", "version");
  }
}

TEST_CASE("render: a glTF that needs a newer loader (minVersion 2.1) is refused") {
  const fs::path dir = scratch("gltf_min_version");
  json scene = scene_json("cornell");
  scene["asset"]["version"] = "2.1";
  scene["asset"]["minVersion"] = "2.1";
  require_refused(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                               "--out", (dir / "out").string()}), dir / "out", "minVersion");
}

TEST_CASE("render: asset.version 2.1 without minVersion renders") {
  const fs::path dir = scratch("gltf_2_1");
  json scene = scene_json("cornell");
  scene["asset"]["version"] = "2.1";
  require_finite_frames(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                                     "--out", (dir / "out").string()}), dir / "out", 1);
}

TEST_CASE("filter --in D --out D is refused and leaves the inputs as they were") {
  const fs::path in = changed_sequence("in_is_out", [](Frame&, int) {});
  const std::string before = read_text(in / "frame_0001.exr");
  const RunResult r = filter(in, in);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("overwrite") != std::string::npos);
  CHECK(read_text(in / "frame_0001.exr") == before);
  CHECK(files_in(in).size() == 3);
}

TEST_CASE("filter --in D --out D/. (the same folder, spelled otherwise) is refused") {
  const fs::path in = changed_sequence("in_is_out_dot", [](Frame&, int) {});
  const RunResult r = filter(in, in / "." / ".." / "in");
  CHECK(r.exit_code == 1);
  CHECK(files_in(in).size() == 3);
}

TEST_CASE("probe: --pixel with trailing text, overflow or one number is refused") {
  const fs::path dir = scratch("probe_pixel");
  for (const char* pixel : {"5,6junk", "99999999999,0", "5", "5,", ",5", "-", "5;6", " 5,6", "0x5,6"}) {
    INFO("'" << pixel << "'");
    require_refused(run_rtdr_args({"probe", "--in", sequence().string(), "--frame", "1", "--pixel", pixel}, dir),
                    dir / "out", "--pixel");
  }
}

TEST_CASE("probe: a pixel outside the image is refused") {
  const fs::path dir = scratch("probe_outside");
  for (const char* pixel : {"16,0", "0,9", "-1,0", "2147483647,2147483647"}) {
    INFO(pixel);
    require_refused(run_rtdr_args({"probe", "--in", sequence().string(), "--frame", "1", "--pixel", pixel}, dir),
                    dir / "out");
  }
}

TEST_CASE("eval: method spec values with trailing text, fractions for ints or out of range are refused") {
  const fs::path dir = scratch("spec_values");
  for (const char* spec : {"svgf:atrous_levels=2.9junk", "svgf:atrous_levels=1e30", "svgf:atrous_levels=2.9",
                           "svgf:atrous_levels=-1", "svgf:alpha=nan", "svgf:alpha=inf", "svgf:alpha=",
                           "svgf:alpha", "svgf:sigma_l= 4", "svgf:max_history=1e300", "svgf:kernel_size=4"}) {
    INFO(spec);
    require_refused(run_rtdr_args({"eval", "--scene", "cornell", "--methods", spec, "--frames", "0-1", "--size",
                                   "8x8", "--cache", "", "--out", (dir / "out").string()}, dir), dir / "out");
  }
}

TEST_CASE("filter: SVGF flags out of range or of the wrong type are refused") {
  const fs::path dir = scratch("svgf_flags");
  for (const std::vector<std::string>& flag : std::vector<std::vector<std::string>>{
           {"--atrous-levels", "1e30"}, {"--atrous-levels", "2.9"}, {"--alpha", "nan"}, {"--alpha", "-0.5"},
           {"--sigma-l", "inf"}, {"--kernel-size", "4"}}) {
    INFO(flag[0] << " " << flag[1]);
    require_refused(filter(sequence(), dir / "out", flag), dir / "out");
  }
}

TEST_CASE("render: rtdr_fps and znear that vanish as floats (1e-300) are refused") {
  const fs::path dir = scratch("tiny_floats");
  json fps = scene_json("cornell");
  fps["scenes"][0]["extras"]["rtdr_fps"] = 1e-300;
  require_refused(render(dir, {"--scene", write_scene(dir, fps).string(), "--frames", "0", "--size", "8x8", "--out",
                               (dir / "out").string()}), dir / "out", "rtdr_fps");
  json znear = scene_json("cornell");
  znear["cameras"][0]["perspective"]["znear"] = 1e-300;
  require_refused(render(dir, {"--scene", write_scene(dir, znear).string(), "--frames", "0", "--size", "8x8", "--out",
                               (dir / "out").string()}), dir / "out", "znear");
}

TEST_CASE("render: rtdr_fps of 1e300 (infinite as a float), a string, or 0 is refused") {
  const fs::path dir = scratch("bad_fps");
  for (const json& value : {json(1e300), json("30"), json(0), json(-30)}) {
    INFO(value.dump());
    json scene = scene_json("cornell");
    scene["scenes"][0]["extras"]["rtdr_fps"] = value;
    require_refused(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                                 "--out", (dir / "out").string()}), dir / "out", "rtdr_fps");
  }
}

TEST_CASE("render: yfov of 0, pi or 1e-300 and zfar before znear are refused") {
  const fs::path dir = scratch("bad_camera");
  for (const auto& [key, value] : std::vector<std::pair<std::string, double>>{
           {"yfov", 0.0}, {"yfov", 3.1415927}, {"yfov", 1e-300}, {"zfar", 1e-3}, {"znear", -1.0}}) {
    INFO(key << " = " << value);
    json scene = scene_json("cornell");
    scene["cameras"][0]["perspective"][key] = value;
    require_refused(render(dir, {"--scene", write_scene(dir, scene).string(), "--frames", "0", "--size", "8x8",
                                 "--out", (dir / "out").string()}), dir / "out", key);
  }
}

TEST_CASE("filter: duplicate frame indices (frame_001.exr beside frame_0001.exr) are refused") {
  const fs::path in = changed_sequence("duplicates", [](Frame&, int) {});
  fs::copy_file(in / "frame_0001.exr", in / "frame_001.exr");
  require_refused(filter(in, in.parent_path() / "out"), in.parent_path() / "out", "twice");
}
