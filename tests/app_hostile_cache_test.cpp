// Hostile input against the frame cache and the output folders, as a user hits them through the real binary:
// the cache's integrity (eval/frame_cache.h), all-or-nothing commits and staging folders (core/atomic_file.h),
// and a gradient sequence continued with other settings (trace/render_key.h). Labelled `hostile`; the outcomes
// are hostile_fixtures.h's. docs/reliability.md, "The frame cache", lists the promises these keep.
#include "hostile_fixtures.h"

#include "core/atomic_file.h"
#include "trace/render_key.h"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

using namespace hostile;

namespace {

// The `rmse` column of each row of metrics.csv (no quoting: cells hold no commas).
std::vector<double> rmse_column(const fs::path& csv) {
  std::istringstream lines(read_text(csv));
  std::string header;
  std::getline(lines, header);
  const std::vector<std::string> names = csv_cells(header);
  const size_t column = size_t(std::find(names.begin(), names.end(), "rmse") - names.begin());
  REQUIRE(column < names.size());
  std::vector<double> values;
  for (std::string line; std::getline(lines, line);) values.push_back(std::stod(csv_cells(line).at(column)));
  return values;
}

std::vector<std::string> eval_args(const std::string& scene, const fs::path& cache, const fs::path& out) {
  return {"eval", "--scene", scene, "--methods", "none", "--frames", "0-1", "--size", "16x12", "--ref-spp", "4",
          "--cache", cache.string(), "--out", out.string()};
}

// The cache's entries (frame_*.exr below it, outside staging folders), and whether a staging folder or a temporary
// file is left in it. Both read a folder another process may be changing.
std::vector<fs::path> entries(const fs::path& cache) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(cache, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".exr" && it->path().parent_path().filename().string()[0] != '.')
      found.push_back(it->path());
  return found;
}
bool leftovers(const fs::path& cache) {
  std::error_code ec;
  for (fs::recursive_directory_iterator it(cache, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(".rtdr-cache-staging-", 0) == 0 || name.find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("eval: a scene named by 200 characters keeps its references apart from its inputs") {
  const fs::path dir = scratch("cache_long_name");
  const fs::path scene = write_scene(dir, scene_json("cornell"), std::string(200, 'n') + ".gltf");
  const RunResult r = run_rtdr_args(eval_args(scene.string(), dir / "cache", dir / "out"), dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  // The unfiltered input against 4-spp references: never 0, as when the inputs were found as the references.
  for (const double rmse : rmse_column(dir / "out" / "metrics.csv")) CHECK(rmse > 1e-3);
  CHECK(entries(dir / "cache").size() == 4);  // two inputs, two references
}

TEST_CASE("eval: a NaN written into a cached frame is found, the frame rendered again, and the metrics finite") {
  const fs::path dir = scratch("cache_nan");
  REQUIRE(run_rtdr_args(eval_args("cornell", dir / "cache", dir / "first"), dir).exit_code == 0);
  const std::vector<double> first = rmse_column(dir / "first" / "metrics.csv");
  for (const fs::path& entry : entries(dir / "cache")) {
    Frame f = rtdr::read_exr(entry.string());
    f.float_channel("direct.R").data[0] = std::nanf("");
    rtdr::write_exr(entry.string(), f);
  }
  const RunResult r = run_rtdr_args(eval_args("cornell", dir / "cache", dir / "second"), dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.err, Catch::Contains("is not the frame asked for") && Catch::Contains("rendering it again"));
  CHECK(rmse_column(dir / "second" / "metrics.csv") == first);  // the same frames, rendered again
  for (const fs::path& entry : entries(dir / "cache")) CHECK(rtdr::checksum_mismatch(rtdr::read_exr(entry.string())).empty());
}

TEST_CASE("render and filter: a file whose name is taken by a folder fails the commit, and --out keeps all it held") {
  const fs::path dir = scratch("commit_taken");
  const fs::path out = dir / "out";
  REQUIRE(render(dir, {"--scene", "cornell", "--frames", "0-2", "--size", "16x9", "--out", out.string()}).exit_code == 0);
  const std::string old_frame = read_text(out / "frame_0000.exr");
  fs::remove(out / "frame_0001.exr");
  fs::create_directories(out / "frame_0001.exr");
  const RunResult r =
      render(dir, {"--scene", "cornell", "--frames", "0-2", "--size", "16x9", "--seed", "5", "--out", out.string()});
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK_THAT(rtdr::last_line(r.err), Catch::Contains("frame_0001.exr': it is a folder"));
  CHECK(read_text(out / "frame_0000.exr") == old_frame);  // not replaced by the new frame 0
  CHECK(fs::is_directory(out / "frame_0001.exr"));
  CHECK_FALSE(staging_left(out));

  const fs::path filtered = dir / "filtered";
  fs::remove(out / "frame_0001.exr");
  REQUIRE(render(dir, {"--scene", "cornell", "--frames", "1", "--size", "16x9", "--out", out.string()}).exit_code == 0);
  REQUIRE(filter(out, filtered).exit_code == 0);
  const std::string old_filtered = read_text(filtered / "frame_0000.exr");
  fs::remove(filtered / "frame_0002.exr");
  fs::create_directories(filtered / "frame_0002.exr");
  const RunResult f = filter(out, filtered, {"--alpha", "0.5"});
  CHECK(f.exit_code == 1);
  CHECK_THAT(rtdr::last_line(f.err), Catch::Contains("it is a folder"));
  CHECK(read_text(filtered / "frame_0000.exr") == old_filtered);
  CHECK_FALSE(staging_left(filtered));
}

TEST_CASE("render --gradients: a sequence continues only with the settings and the scene it began with") {
  const fs::path dir = scratch("gradients_continue");
  const fs::path out = dir / "out";
  const auto gradients = [&](const std::string& scene, const std::string& frames, std::vector<std::string> extra) {
    std::vector<std::string> args = {"--scene", scene, "--frames", frames, "--size", "18x12", "--gradients",
                                     "--out", out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return render(dir, args);
  };
  REQUIRE(gradients("cornell", "0-1", {}).exit_code == 0);
  // The defect: continued with no bounce, every indirect delta became the whole previous indirect light.
  RunResult r = gradients("cornell", "2-3", {"--max-bounces", "0"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(rtdr::last_line(r.err), Catch::Contains("frame_0001.exr") && Catch::Contains("rtdr.max_bounces is 1, not 0"));
  r = gradients("cornell", "2-3", {"--shading-samples", "4"});
  CHECK_THAT(rtdr::last_line(r.err), Catch::Contains("rtdr.shading_samples is 0, not 4"));
  // Another room.gltf of the same stem, in another folder: another scene, refused before it could crash.
  fs::create_directories(dir / "elsewhere");
  json other = scene_json("cornell");
  other["nodes"][0]["name"] = "a changed node";
  const fs::path copy = write_scene(dir / "elsewhere", other, "cornell.gltf");
  r = gradients(copy.string(), "2-3", {});
  CHECK(r.exit_code == 1);
  CHECK_THAT(rtdr::last_line(r.err), Catch::Contains("rtdr.scene.hash is"));
  CHECK(files_in(out).size() == 4);  // frames 0-1, their previews; nothing else written
  // The control: the same scene and settings continue.
  r = gradients("cornell", "2-3", {});
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("continuing from frame 1"));
}

TEST_CASE("eval: a run killed while it writes the cache leaves no partial entry, and the next run cleans up") {
  const fs::path dir = scratch("cache_killed");
  const fs::path cache = dir / "cache";
  std::vector<std::string> args = {RTDR_EXE, "eval", "--scene", "pillars", "--methods", "none", "--frames", "0-5",
                                   "--size", "64x36", "--ref-spp", "16", "--cache", cache.string(),
                                   "--out", (dir / "out").string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0);
  posix_spawn_file_actions_destroy(&actions);
  // Killed (SIGKILL: no handler runs) once it has stored a frame, i.e. while its staging folder exists.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (entries(cache).empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFSIGNALED(status));
  CHECK(leftovers(cache));  // the dead run's staging folder is still there, its lock free
  for (const fs::path& entry : entries(cache)) CHECK(rtdr::checksum_mismatch(rtdr::read_exr(entry.string())).empty());
  // A run of another size stores into the same cache: the dead run's staging folder goes.
  const RunResult r = run_rtdr_args({"eval", "--scene", "pillars", "--methods", "none", "--frames", "0", "--size",
                                     "16x12", "--ref-spp", "2", "--cache", cache.string(), "--out",
                                     (dir / "out2").string()}, dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_FALSE(leftovers(cache));
}

TEST_CASE("render: a staging folder a dead run left in --out, with this run's pid in its name, blocks nothing") {
  // The defect: staging names were made from the pid, and in a container every run has the same pid, so the
  // rerun after a Ctrl-C was refused ("staging folder exists").
  const fs::path dir = scratch("staging_dead");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  // What the previous scheme left, and what a killed run of this one leaves (its lock file free).
  fs::create_directories(out / ".rtdr-staging-1-0");
  fs::create_directories(out / ".rtdr-staging-00000000deadbeef-0");
  std::ofstream(out / ".rtdr-staging-00000000deadbeef-0" / "frame_0000.exr") << "partial";
  std::ofstream(out / ".rtdr-staging-00000000deadbeef-0.lock");
  const RunResult r = render(dir, {"--scene", "cornell", "--frames", "0", "--size", "16x9", "--out", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(files_in(out) == std::set<std::string>{".rtdr-staging-1-0", "frame_0000.exr", "frame_0000.png"});
}

TEST_CASE("eval: a read-only cache is read, and what it lacks is rendered without being stored, with one warning") {
  const fs::path dir = scratch("cache_read_only");
  const fs::path cache = dir / "cache";
  REQUIRE(run_rtdr_args(eval_args("cornell", cache, dir / "first"), dir).exit_code == 0);
  fs::remove(entries(cache).front());  // one frame missing
  const size_t stored = entries(cache).size();
  // Read-only to the run: as root, the run drops to user nobody (root writes anywhere); else the folders' modes.
  std::vector<std::string> as_nobody;
  if (::geteuid() == 0) {
    as_nobody = {"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--"};
    fs::permissions(dir, fs::perms::all);  // nobody writes --out here, and reads the cache
  }
  for (const auto& e : fs::recursive_directory_iterator(cache))
    if (e.is_directory()) fs::permissions(e.path(), fs::perms::owner_write | fs::perms::group_write |
                                                        fs::perms::others_write, fs::perm_options::remove);
  fs::permissions(cache, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  const RunResult r = run_rtdr_args(eval_args("cornell", cache, dir / "second"), dir, {}, as_nobody);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  size_t warnings = 0;
  for (size_t at = r.err.find("cannot be written"); at != std::string::npos; at = r.err.find("cannot be written", at + 1))
    ++warnings;
  CHECK(warnings == 1);
  CHECK_THAT(r.err, Catch::Contains("frames rendered now are not stored"));
  CHECK(rmse_column(dir / "second" / "metrics.csv") == rmse_column(dir / "first" / "metrics.csv"));
  CHECK(entries(cache).size() == stored);
  fs::permissions(cache, fs::perms::owner_all, fs::perm_options::add);
}

TEST_CASE("eval: a cache write that fails (the file size limit, as a full disk) fails the run with the reason") {
  const fs::path dir = scratch("cache_full");
  const fs::path cache = dir / "cache";
  // bash ignores SIGXFSZ (ignored signals stay ignored across exec) and limits files to 64 KB: a 64x36 frame of
  // 76 planes is larger, so the first cache write fails with "File too large", as a full disk fails with ENOSPC.
  const RunResult r = run_rtdr_args(
      {"eval", "--scene", "cornell", "--methods", "none", "--frames", "0", "--size", "64x36", "--ref-spp", "1",
       "--cache", cache.string(), "--out", (dir / "out").string()},
      dir, {}, {"bash", "-c", "trap '' XFSZ; ulimit -f 64; exec \"$@\"", "bash"});
  require_refused(r, dir / "out", "File too large");
  CHECK(entries(cache).empty());
  CHECK_FALSE(leftovers(cache));
}
