// The fixture of the hostile-input tests (app_hostile_input_test.cpp: the defects of docs/reliability.md;
// app_hostile_cli_test.cpp: our own scenes, options and inputs). Every case ends one of two ways:
// - refused: exit status 1 or 2 (never a crash), exactly one line on stderr starting "rtdr: error: ", and no
//   output at all: the --out folder is not created (or keeps what it held), and no staging folder is left;
// - accepted: exit status 0 and every float channel of every frame written is finite.
#pragma once

#include "core/exr_io.h"
#include "core/frame.h"
#include "core/subprocess.h"

#include "cli_fixtures.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <functional>
#include <string>
#include <vector>

namespace hostile {

namespace fs = std::filesystem;
using nlohmann::json;
using rtdr::Frame;

using namespace rtdr::cli;

inline fs::path scratch(const std::string& name) { return rtdr::cli::scratch("rtdr_hostile_test", name); }

// The input sequence every filter case starts from: frames 0-2 of cornell at 16x9, rendered once per process.
inline const fs::path& sequence() {
  static const fs::path dir = [] {
    const fs::path d = scratch("sequence");
    const RunResult r = run_rtdr_args({"render", "--scene", "cornell", "--frames", "0-2", "--size", "16x9", "--out",
                                       (d / "in").string()}, d);
    REQUIRE(r.exit_code == 0);
    return d / "in";
  }();
  return dir;
}

// A copy of the sequence in scratch folder `name`/in, each frame changed by `change(frame, index)`.
inline fs::path changed_sequence(const std::string& name, const std::function<void(Frame&, int)>& change) {
  const fs::path in = scratch(name) / "in";
  fs::create_directories(in);
  for (int f = 0; f < 3; ++f) {
    const std::string file = "frame_000" + std::to_string(f) + ".exr";
    Frame frame = rtdr::read_exr((sequence() / file).string());
    change(frame, f);
    rtdr::write_exr((in / file).string(), frame);
  }
  return in;
}

// A shipped scene's glTF, as JSON to edit, and a place to write the edited copy.
inline json scene_json(const std::string& name) {
  return json::parse(read_text(fs::path(RTDR_SOURCE_DIR) / "scenes" / (name + ".gltf")));
}
inline fs::path write_scene(const fs::path& dir, const json& scene, const std::string& file = "scene.gltf") {
  const fs::path path = dir / file;
  std::ofstream(path) << scene.dump();
  return path;
}

// Staging folders (core/atomic_file.h) left anywhere below `dir`, or below its deepest existing folder.
inline bool staging_left(fs::path dir) {
  while (!fs::is_directory(dir)) dir = dir.parent_path();
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().rfind(".rtdr-staging-", 0) == 0) return true;
  return false;
}

// The refused outcome: a one-line error, a non-zero exit that is not a crash, and no output at `out`.
inline void require_refused(const RunResult& r, const fs::path& out, const std::string& says = "") {
  INFO("stderr: " << r.err);
  CHECK((r.exit_code == 1 || r.exit_code == 2));
  // The error is one line, the last; lines before it can only be progress ("eval cornell  67% ...", printed
  // to stderr when it is not a terminal), never a second error or a traceback.
  const std::string last = rtdr::last_line(r.err);
  CHECK(last.rfind("rtdr: error: ", 0) == 0);
  std::istringstream lines(r.err.substr(0, r.err.size() - std::min(r.err.size(), last.size() + 1)));
  for (std::string line; std::getline(lines, line);) CHECK(line.find("% ") != std::string::npos);
  if (!says.empty()) CHECK(last.find(says) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(staging_left(out.parent_path()));
}

// The accepted outcome: exit 0, and every frame_*.exr in `out` holds only finite floats.
inline void require_finite_frames(const RunResult& r, const fs::path& out, size_t frames) {
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  size_t seen = 0;
  for (const std::string& name : files_in(out)) {
    if (name.size() < 4 || name.substr(name.size() - 4) != ".exr") continue;
    ++seen;
    const Frame f = rtdr::read_exr((out / name).string());
    for (const auto& [channel, plane] : f.float_channels())
      for (float v : plane.data) REQUIRE(std::isfinite(v));
  }
  CHECK(seen == frames);
  CHECK_FALSE(staging_left(out.parent_path()));
}

inline RunResult filter(const fs::path& in, const fs::path& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"filter", "--in", in.string(), "--out", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_rtdr_args(args, out.parent_path());
}

inline RunResult render(const fs::path& dir, std::vector<std::string> args) {
  args.insert(args.begin(), "render");
  return run_rtdr_args(args, dir);
}

}  // namespace hostile
