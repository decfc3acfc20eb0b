// Issue 14, items 4-8 and 10: the output folder is one whole run or visibly unfinished, output
// failures are exit 3 naming the file (never a Crash verdict), no false greens, no partial output
// on bad input, image folders unique and confined, strict --shard, stdout flushed per record.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/errors.h"
#include "shadowcts/image_file.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"
#include "tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::read_file;
using testing::run_shell;
using testing::run_tool;

fs::path fresh_dir(const std::string& name) {
  return testing::fresh_dir("output_integrity_" + name);
}

const std::string tool = SHADOWCTS_TOOL;

std::string err_of(const fs::path& dir) {
  return read_file(dir / "stderr.txt");
}

// Every file under `root` with its bytes, by relative path.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  if (!fs::exists(root)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), root).string()] = read_file(entry.path());
  return files;
}

// Names in `dir` that start with `prefix` (the partial folders of a run into dir/<prefix>...).
std::vector<std::string> entries_starting(const fs::path& dir, const std::string& prefix) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().rfind(prefix, 0) == 0)
      names.push_back(entry.path().filename().string());
  return names;
}

const std::string small_run = "run --fixture ground_blockers.2k --algorithm embree --repeat 1";

// A previous complete run in dir/out, for the tests that must leave it untouched.
std::map<std::string, std::string> previous_run(const fs::path& dir) {
  EXPECT_EQ(run_tool(small_run + " --out out", dir), exit_pass) << err_of(dir);
  const auto files = snapshot(dir / "out");
  EXPECT_TRUE(files.count("results.json"));
  EXPECT_TRUE(files.count("junit.xml"));
  EXPECT_TRUE(files.count("report.html"));
  return files;
}

// Item 4: a second run replaces the first as a whole; nothing partial is left beside it.
TEST(OutputIntegrity, ARunReplacesThePreviousRunAsAWhole) {
  const fs::path dir = fresh_dir("replace");
  previous_run(dir);
  // Files of the first run that the second does not write must not survive beside it.
  ASSERT_EQ(run_tool("run --fixture shared_edges.1k --algorithm embree --repeat 1 --out out", dir),
            exit_pass)
      << err_of(dir);
  const auto results = json::parse(read_file(dir / "out" / "results.json"));
  ASSERT_EQ(results["cases"].size(), 1u);
  EXPECT_EQ(results["cases"][0]["name"], "shared_edges.1k");
  EXPECT_FALSE(fs::exists(dir / "out" / "images" / "ground_blockers.2k"));
  EXPECT_EQ(entries_starting(dir, "out."), std::vector<std::string>{});
  EXPECT_EQ(read_file(dir / "out" / "report.html").find(".partial-"), std::string::npos);
}

// How the tool ended when sent `signal` (a kill option: -9, -TERM) once the shell test `ready`
// held ($pid is the tool's); stdout goes to run.txt, stderr to tool_stderr.txt.
struct Signalled {
  std::string status, pid;
};
Signalled signal_tool_once_ready(const fs::path& dir, const std::string& arguments,
                                 const std::string& ready, const std::string& signal) {
  const int code = run_shell("'" + tool + "' " + arguments +
                                 " > run.txt 2> tool_stderr.txt &\n"
                                 "pid=$!\n"
                                 "for i in $(seq 1 6000); do\n"
                                 "  if " +
                                 ready +
                                 "; then break; fi\n"
                                 "  sleep 0.005\n"
                                 "done\n"
                                 "kill " +
                                 signal +
                                 " $pid\n"
                                 "wait $pid\n"
                                 "echo $? > status.txt\n"
                                 "echo $pid > pid.txt\n",
                             dir);
  EXPECT_EQ(code, 0) << err_of(dir);
  Signalled ended{read_file(dir / "status.txt"), read_file(dir / "pid.txt")};
  for (std::string* text : {&ended.status, &ended.pid})
    while (!text->empty() && text->back() == '\n') text->pop_back();
  return ended;
}

// Several cases and algorithms: seconds of work, signalled once its first case's images are
// being written.
const std::string long_run =
    "run --fixture ground_blockers.2k --fixture shared_edges.1k --fixture closed_shapes.1k "
    "--algorithm ptsv --algorithm psv --algorithm bruteforce --repeat 3 --out out";
const std::string writing_images = "[ -n \"$(ls out.partial-$pid/images 2>/dev/null)\" ]";

// Item 4: killed in the middle, the folder still holds the previous complete run, and the new
// run's folder says it is unfinished.
TEST(OutputIntegrity, AKilledRunLeavesThePreviousRunAndAVisiblyUnfinishedFolder) {
  const fs::path dir = fresh_dir("killed");
  const auto before = previous_run(dir);
  const Signalled ended = signal_tool_once_ready(dir, long_run, writing_images, "-9");
  ASSERT_EQ(ended.status, "137") << "the run ended before it was killed";
  EXPECT_EQ(snapshot(dir / "out"), before) << "the previous run was changed";
  EXPECT_TRUE(fs::is_directory(dir / ("out.partial-" + ended.pid)));
  EXPECT_FALSE(fs::exists(dir / ("out.partial-" + ended.pid) / "results.json"));
}

// Interrupted (SIGTERM: a CI job's timeout; SIGINT and SIGHUP alike) while its images are being
// written, the run removes its unfinished folder, says so, and ends with the signal's status; the
// previous run stays whole.
TEST(OutputIntegrity, AnInterruptedRunRemovesItsUnfinishedFolderAndKeepsThePreviousRun) {
  const fs::path dir = fresh_dir("interrupted");
  const auto before = previous_run(dir);
  const Signalled ended = signal_tool_once_ready(dir, long_run, writing_images, "-TERM");
  ASSERT_EQ(ended.status, "143") << "the run ended before it was interrupted";
  EXPECT_EQ(snapshot(dir / "out"), before) << "the previous run was changed";
  EXPECT_EQ(entries_starting(dir, "out."), std::vector<std::string>{});
  const std::string said = read_file(dir / "tool_stderr.txt");
  EXPECT_NE(said.find("interrupted (SIGTERM); removed the unfinished"), std::string::npos) << said;
}

// `export` writes its folder in place: interrupted once scene.glb is there (the G-buffer and the
// check that case.json loads back, about 0.7 s, still to come), it removes the folder.
TEST(OutputIntegrity, AnInterruptedExportLeavesNoFolder) {
  const fs::path dir = fresh_dir("interrupted_export");
  const Signalled ended = signal_tool_once_ready(
      dir, "export --fixture foliage.100k --out exported", "[ -e exported/scene.glb ]", "-HUP");
  ASSERT_EQ(ended.status, "129") << "the export ended before it was interrupted";
  EXPECT_FALSE(fs::exists(dir / "exported"));
  const std::string said = read_file(dir / "tool_stderr.txt");
  EXPECT_NE(said.find("interrupted (SIGHUP); removed the unfinished"), std::string::npos) << said;
}

// Item 4: a full disk (a real ENOSPC, on a small tmpfs in a user namespace) while an algorithm's
// images are written: exit 3 naming the PNG, no Crash verdict, the previous run untouched and no
// partial folder left.
TEST(OutputIntegrity, AFullDiskIsExitThreeNamingTheFileNeverACrash) {
  const fs::path dir = fresh_dir("full_disk");
  const std::string mount = (dir / "disk").string();
  fs::create_directories(mount);
  // Room for the first run; then the disk is filled so that the new run's oracle images fit
  // (pages of the previous run's oracle PNG and EXR) and the algorithm's first image does not.
  const std::string script =
      "set -e\n"
      "unshare -rm bash -c '\n"
      "  set -e\n"
      "  mount -t tmpfs -o size=2m tmpfs " +
      mount +
      " || exit 77\n"
      "  cd " +
      mount +
      "\n"
      "  \"" +
      tool + "\" " + small_run +
      " --out out > /dev/null\n"
      "  cp -r out " +
      (dir / "before").string() +
      "\n"
      "  pages() { echo $(( ($(stat -c %s \"$1\") + 4095) / 4096 )); }\n"
      "  keep=$(( $(pages out/images/ground_blockers.2k/oracle.mask.png) + "
      "$(pages out/images/ground_blockers.2k/oracle.mask.exr) ))\n"
      "  free=$(df --output=avail -B4096 . | tail -1)\n"
      "  dd if=/dev/zero of=fill bs=4096 count=$(( free - keep )) 2> /dev/null\n"
      "  set +e\n"
      "  \"" +
      tool + "\" " + small_run + " --out out > " + (dir / "run.txt").string() + " 2> " +
      (dir / "run_err.txt").string() +
      "\n"
      "  echo $? > " +
      (dir / "code.txt").string() +
      "\n"
      "  cp -r out " +
      (dir / "after").string() +
      "\n"
      "  ls > " +
      (dir / "listing.txt").string() +
      "\n"
      "'\n";
  const int code = run_shell(script, dir);
  if (code == 77 || (code != 0 && err_of(dir).find("unshare") != std::string::npos))
    GTEST_SKIP() << "no user namespace with tmpfs here: " << err_of(dir);
  ASSERT_EQ(code, 0) << err_of(dir);
  EXPECT_EQ(read_file(dir / "code.txt"), "3\n");
  const std::string message = read_file(dir / "run_err.txt");
  EXPECT_NE(message.find("cannot write output"), std::string::npos) << message;
  EXPECT_NE(message.find("embree.robust.embree.mask.png"), std::string::npos) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  EXPECT_EQ(read_file(dir / "run.txt").find("Crash"), std::string::npos);
  EXPECT_EQ(snapshot(dir / "after"), snapshot(dir / "before"));
  EXPECT_EQ(read_file(dir / "listing.txt"), "fill\nout\n") << "a partial folder was left";
}

// Item 4, without a mount: a file size limit makes every large enough write fail (EFBIG), the
// same checked path as ENOSPC; results and images alike.
TEST(OutputIntegrity, AWriteErrorIsExitThreeAndKeepsThePreviousRun) {
  const fs::path dir = fresh_dir("file_size_limit");
  const auto before = previous_run(dir);
  // SIGXFSZ ignored: the write fails with EFBIG instead of killing the process.
  EXPECT_EQ(
      run_shell("trap '' XFSZ\nulimit -f 1\nexec '" + tool + "' " + small_run + " --out out\n",
                dir),
      exit_internal_error);
  const std::string message = err_of(dir);
  EXPECT_NE(message.find("cannot write output"), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_NE(message.find("images/ground_blockers.2k/oracle.mask."), std::string::npos) << message;
  EXPECT_EQ(read_file(dir / "stdout.txt").find("Crash"), std::string::npos);
  EXPECT_EQ(snapshot(dir / "out"), before);
  EXPECT_EQ(entries_starting(dir, "out."), std::vector<std::string>{});
}

// Item 4: the PNG writer itself (the zero-byte PNGs of the report came from it): a failed write
// is an OutputError naming the file, and nothing is left at the path.
TEST(OutputIntegrity, APngThatCannotBeWrittenThrowsOutputError) {
  const fs::path dir = fresh_dir("png");
  const fs::path png = dir / "image.png";
  RgbImage image{64, 64, std::vector<std::uint8_t>(64 * 64 * 3)};
  std::uint32_t state = 1;  // noise: it does not compress below the limit
  for (std::uint8_t& byte : image.rgb)
    byte = std::uint8_t((state = state * 1664525u + 1013904223u) >> 24);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // the limit only in a child: the test process keeps writing freely
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1000, 1000};
    setrlimit(RLIMIT_FSIZE, &limit);
    try {
      write_image(png.string(), image);
    } catch (const OutputError& e) {
      const std::string what = e.what();
      _exit(what.find(png.string()) != std::string::npos &&
                    what.find("File too large") != std::string::npos
                ? 0
                : 1);
    } catch (...) {
      _exit(2);
    }
    _exit(3);  // written although it cannot fit
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_FALSE(fs::exists(png));
  EXPECT_TRUE(fs::is_empty(dir)) << "a temporary was left";
  // Without the limit it is written and readable.
  write_image(png.string(), image);
  EXPECT_GT(fs::file_size(png), 100u);
}

// Item 4: a folder that holds anything but a previous run is not replaced.
TEST(OutputIntegrity, AFolderWithOtherFilesIsNotReplaced) {
  const fs::path dir = fresh_dir("foreign");
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out" / "notes.txt") << "mine";
  EXPECT_EQ(run_tool(small_run + " --out out", dir), exit_bad_input);
  EXPECT_NE(err_of(dir).find("notes.txt"), std::string::npos) << err_of(dir);
  EXPECT_EQ(snapshot(dir / "out"), (std::map<std::string, std::string>{{"notes.txt", "mine"}}));
  EXPECT_EQ(entries_starting(dir, "out."), std::vector<std::string>{});
}

// Item 5: an unknown backend, and a selection of no case, are usage errors, not empty greens.
TEST(OutputIntegrity, AnUnknownBackendOrAnEmptySelectionIsExitTwo) {
  const fs::path dir = fresh_dir("empty_selection");
  EXPECT_EQ(run_tool("run --backend vulkan --out out", dir), exit_bad_input);
  std::string message = err_of(dir);
  EXPECT_NE(message.find("--backend vulkan: unknown backend"), std::string::npos) << message;
  EXPECT_NE(message.find("reference"), std::string::npos) << message;
  EXPECT_NE(message.find("embree"), std::string::npos) << message;

  EXPECT_EQ(run_tool("run --fixture ground_blockers.2k --shard 3/4 --out out", dir),
            exit_bad_input);
  message = err_of(dir);
  EXPECT_NE(message.find("matches no case in shard 3/4"), std::string::npos) << message;

  EXPECT_EQ(run_tool("run --algorithm embree:exact --out out", dir), exit_bad_input);
  message = err_of(dir);
  EXPECT_NE(message.find("embree:exact"), std::string::npos) << message;
  EXPECT_NE(message.find("variants of embree: robust"), std::string::npos) << message;

  EXPECT_EQ(run_tool("run --algorithm vulkanrt --out out", dir), exit_bad_input);
  message = err_of(dir);
  EXPECT_NE(message.find("--algorithm vulkanrt"), std::string::npos) << message;
  EXPECT_NE(message.find("known: bruteforce, embree"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// --backend is repeatable: a timing run keeps the backends it names and leaves the others (the
// emulated kernels) out; one unknown name among known ones is still a usage error.
TEST(OutputIntegrity, RepeatedBackendsSelectExactlyThoseBackends) {
  const fs::path dir = fresh_dir("repeated_backends");
  ASSERT_EQ(run_tool("run --fixture ground_blockers.2k --algorithm bruteforce --algorithm embree "
                     "--backend reference --backend embree --repeat 1 --out out",
                     dir),
            exit_pass)
      << err_of(dir);
  const auto results = json::parse(read_file(dir / "out" / "results.json"));
  std::set<std::string> backends;
  for (const auto& r : results["results"]) backends.insert(r["backend"].get<std::string>());
  EXPECT_EQ(backends, (std::set<std::string>{"reference", "embree"}));

  EXPECT_EQ(run_tool("run --backend reference --backend vulkan --out out2", dir), exit_bad_input);
  EXPECT_NE(err_of(dir).find("--backend vulkan: unknown backend"), std::string::npos)
      << err_of(dir);
  EXPECT_FALSE(fs::exists(dir / "out2"));
}

// Item 5: a case whose samples are all sky has nothing to judge: hard, soft and light-list
// records are NotSupported with the reason, never "right on all 0 robust samples".
TEST(OutputIntegrity, ACaseWithNothingToJudgeIsNotSupportedNeverPass) {
  const fs::path dir = fresh_dir("nothing_to_judge");
  std::ofstream(dir / "sky.json") << R"({"name": "sky",
      "scene": {"generator": "ground_blockers", "triangles": 1000},
      "camera": {"position": [0, 100, 0], "target": [0, 200, 0], "up": [0, 0, 1],
                 "width": 16, "height": 12},
      "light": {"type": "sun", "direction": [0.3, 1, 0.2], "angular_radius_degrees": 0.27},
      "ranged_lights": [{"type": "sphere", "centre": [0, 1, 0], "range": 2}]})";
  ASSERT_EQ(run_tool("run --case sky.json --algorithm embree --algorithm softtile:grid16 "
                     "--algorithm lightassign:tiled --repeat 1 --out out",
                     dir),
            exit_pass)
      << err_of(dir);
  const auto results = json::parse(read_file(dir / "out" / "results.json"));
  std::set<std::string> outputs;
  for (const auto& r : results["results"]) {
    EXPECT_EQ(r["verdict"], "NotSupported") << r.dump();
    const std::string reason = r["reason"];
    // A device backend without a device says so first.
    if (r["backend"] == "cuda" && reason.find("no CUDA device") == 0) continue;
    EXPECT_EQ(reason.find("no robust sample to judge: 0 ambiguous, 192 sky, 0 back-facing"), 0u)
        << reason;
    outputs.insert(r["output"].get<std::string>());
  }
  EXPECT_EQ(outputs, (std::set<std::string>{"hard", "soft", "lights"}));
  const std::string junit = read_file(dir / "out" / "junit.xml");
  // One record per registered backend of embree, softtile and lightassign (one variant each).
  int records = 0;
  for (const auto& a : builtin_registry().algorithms()) {
    const std::string& id = a->info().id;
    records += id == "embree" || id == "softtile" || id == "lightassign" ? 1 : 0;
  }
  std::ostringstream tests, skipped;
  tests << "tests=\"" << records << '"';
  skipped << "skipped=\"" << records << '"';
  EXPECT_NE(junit.find(tests.str()), std::string::npos) << junit;
  EXPECT_NE(junit.find(skipped.str()), std::string::npos) << junit;
  EXPECT_NE(read_file(dir / "stdout.txt").find("NotSupported"), std::string::npos);
}

// A scene file scaled by 2^k (k = -60, 60, 90; dyadic coordinates, so the scaling is exact) runs
// to the verdicts of the unscaled one on every record: same verdicts, same compared and robust
// samples. Before EmbreeScene normalized such cases, 2^60 aborted the whole run (Embree's
// ray.valid() assertion, exit 134) and 2^-60 and 2^90 saw only sky (every record NotSupported).
TEST(OutputIntegrity, ScenesFarOutsideEmbreesRangeRunToTheUnscaledVerdicts) {
  const fs::path dir = fresh_dir("embree_range");
  const auto verdicts = [&](int k) {
    const std::string name = "scaled_" + std::to_string(k + 100);
    std::ofstream obj(dir / (name + ".obj"));
    const auto vertex = [&](double x, double y, double z) {
      char line[160];
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", std::ldexp(x, k), std::ldexp(y, k),
                    std::ldexp(z, k));
      obj << line;
    };
    // A floor of two triangles and two floating quads above it.
    for (const auto& [x, z] : {std::pair{-6.0, -6.0}, {6.0, -6.0}, {6.0, 6.0}, {-6.0, 6.0}})
      vertex(x, 0.0, z);
    for (const double h : {1.0, 1.75})
      for (const auto& [x, z] : {std::pair{-1.0, -0.5}, {0.5, -1.0}, {1.0, 0.75}, {-0.75, 1.0}})
        vertex(x + h - 1.375, h, z);
    obj << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 9 10 11\nf 9 11 12\n";
    obj.close();
    const auto at = [k](double v) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", std::ldexp(v, k));
      return std::string(text);
    };
    std::ofstream(dir / (name + ".json")) << R"({"scenes": [{"file": ")" << name << R"(.obj"}],
      "camera": {"position": [)" << at(1) << ", "
                                          << at(5) << ", " << at(3) << R"(],
                 "target": [0, 0, 0], "up": [0, 1, 0], "near": )"
                                          << at(0.125) << R"(,
                 "far": )" << at(64) << R"(, "width": 48, "height": 32},
      "light": {"type": "sun", "direction": [0.3, 1, 0.2], "angular_radius_degrees": 2},
      "ranged_lights": [{"type": "sphere", "centre": [0, )"
                                          << at(1) << R"(, 0], "range": )" << at(2) << "}]}";
    EXPECT_EQ(run_tool("run --case " + name + ".json --algorithm ptsv:twopass --algorithm " +
                           "psv:stackless --algorithm softtile:grid16 --algorithm " +
                           "lightassign:clustered --backend reference --backend simd --repeat 1 " +
                           "--no-images --out out_" + name,
                       dir),
              exit_pass)
        << "2^" << k << ": " << err_of(dir);
    std::map<std::string, std::string> by_record;
    const auto results = json::parse(read_file(dir / ("out_" + name) / "results.json"));
    for (const auto& r : results["results"])
      by_record[r["algorithm"].get<std::string>() + ":" + r["variant"].get<std::string>() + " [" +
                r["backend"].get<std::string>() + "]"] =
          r["verdict"].get<std::string>() + " " + r["error"].value("compared", json()).dump() +
          " " + r["error"].value("robust", json()).dump();
    return by_record;
  };
  const auto unscaled = verdicts(0);
  ASSERT_EQ(unscaled.size(), 8u);
  for (const auto& [record, verdict] : unscaled)
    EXPECT_EQ(verdict.rfind("Pass", 0), 0u) << record << ": " << verdict;
  for (const int k : {-60, 60, 90}) EXPECT_EQ(verdicts(k), unscaled) << "2^" << k;
}

// Item 6: a bad G-buffer (the second case's) is exit 2 before the output folder is touched.
TEST(OutputIntegrity, ABadGbufferIsExitTwoBeforeAnythingIsWritten) {
  const fs::path dir = fresh_dir("bad_gbuffer");
  std::ofstream(dir / "good.json")
      << R"({"name": "good", "scene": {"generator": "ground_blockers", "triangles": 1000}})";
  std::ofstream(dir / "bad.json") << R"({"name": "bad",
      "scene": {"generator": "ground_blockers", "triangles": 1000}, "gbuffer": "bad.exr"})";
  std::ofstream(dir / "bad.exr") << "not an EXR file";
  EXPECT_EQ(run_tool("run --case good.json --case bad.json --algorithm embree --out out", dir),
            exit_bad_input);
  EXPECT_NE(err_of(dir).find("bad.exr"), std::string::npos) << err_of(dir);
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_EQ(entries_starting(dir, "out."), std::vector<std::string>{});
}

// Item 6: an empty --out is a usage error and writes nothing into the current folder.
TEST(OutputIntegrity, AnEmptyOutIsAUsageError) {
  const fs::path dir = fresh_dir("empty_out");
  EXPECT_EQ(run_tool(small_run + " --out ''", dir), exit_bad_input);
  EXPECT_NE(err_of(dir).find("--out ''"), std::string::npos) << err_of(dir);
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
  EXPECT_EQ(names, (std::set<std::string>{"script.sh", "stdout.txt", "stderr.txt"}));

  // The current folder, even empty, would be replaced under the user's feet.
  fs::create_directories(dir / "empty");
  EXPECT_EQ(run_shell("cd empty && exec '" + tool + "' " + small_run + " --out .\n", dir),
            exit_bad_input);
  EXPECT_NE(err_of(dir).find("not the current folder"), std::string::npos) << err_of(dir);
  EXPECT_TRUE(fs::is_empty(dir / "empty"));
  EXPECT_EQ(entries_starting(dir, "empty."), std::vector<std::string>{});

  std::ofstream(dir / "a_file") << "x";
  EXPECT_EQ(run_tool(small_run + " --out a_file", dir), exit_bad_input);
  EXPECT_NE(err_of(dir).find("not a folder"), std::string::npos) << err_of(dir);
}

// Item 7: names that map to one folder, and names that would leave images/, get folders of
// their own inside images/.
TEST(OutputIntegrity, ImageFoldersAreUniqueAndStayInsideTheOutputFolder) {
  const fs::path dir = fresh_dir("image_folders");
  const std::vector<std::string> names = {"a b", "a_b", "..", ".", "A_B", "a_b-2"};
  std::string cases;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string file = "case" + std::to_string(i) + ".json";
    std::ofstream(dir / file) << json{
        {"name", names[i]},
        {"scene", {{"generator", "ground_blockers"}, {"triangles", 1000}}},
        {"camera",
         {{"width", 16},
          {"height", 12}}}}.dump();
    cases += " --case " + file;
  }
  ASSERT_EQ(run_tool("run" + cases + " --algorithm embree --repeat 1 --out out", dir), exit_pass)
      << err_of(dir);
  std::set<std::string> top;
  for (const auto& entry : fs::directory_iterator(dir / "out")) top.insert(entry.path().filename());
  EXPECT_EQ(top, (std::set<std::string>{"images", "junit.xml", "report.html", "results.json"}));
  const auto results = json::parse(read_file(dir / "out" / "results.json"));
  std::set<std::string> folders, images;
  for (const auto& c : results["cases"]) {
    const fs::path mask = c["oracles"]["hard"]["mask_image"].get<std::string>();
    ASSERT_EQ(mask.begin()->string(), "images") << mask;
    const std::string folder = std::next(mask.begin())->string();
    EXPECT_FALSE(folder.empty() || folder.front() == '.') << folder;
    EXPECT_EQ(mask.lexically_normal(), mask);
    folders.insert(folder);
    EXPECT_TRUE(fs::is_regular_file(dir / "out" / mask)) << mask;
  }
  EXPECT_EQ(folders.size(), names.size());
  for (const auto& r : results["results"])
    for (const auto& image : r["images"]) {
      EXPECT_TRUE(images.insert(image.get<std::string>()).second) << image << " written twice";
      EXPECT_TRUE(fs::is_regular_file(dir / "out" / image.get<std::string>())) << image;
    }
  EXPECT_EQ(images.size(), 2 * names.size());
}

// Item 8: --shard values are range-checked, never wrapped; each error names the value.
TEST(OutputIntegrity, BadShardValuesAreExitTwoNamingTheValue) {
  const fs::path dir = fresh_dir("shard");
  for (const std::string shard : {"0/99999999999", "99999999999/1", "-1/4", "1/0", "4/4", "a/b",
                                  "0/4x", " 0/4", "0/", "/4", "0", "1/2/3", "+0/4"}) {
    EXPECT_EQ(run_tool(small_run + " --shard '" + shard + "' --out out", dir), exit_bad_input)
        << shard;
    EXPECT_NE(err_of(dir).find("--shard '" + shard + "'"), std::string::npos) << err_of(dir);
  }
  run_tool(small_run + " --shard 0/99999999999 --out out", dir);
  EXPECT_NE(err_of(dir).find("N 99999999999 is out of range"), std::string::npos) << err_of(dir);
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_EQ(run_tool(small_run + " --shard 0/4294967295 --out out", dir), exit_pass) << err_of(dir);
}

// Item 10: the plan and every record line reach the stream (flushed) as they are printed, so a
// log that is not a terminal shows progress.
class FlushRecorder : public std::stringbuf {
 public:
  std::set<std::size_t> flushed_at;  // text length at each flush

 protected:
  int sync() override {
    flushed_at.insert(str().size());
    return 0;
  }
};

TEST(OutputIntegrity, ThePlanAndEachRecordLineAreFlushed) {
  const fs::path dir = fresh_dir("flush");
  RunOptions options;
  options.fixtures = {"ground_blockers.2k", "shared_edges.1k"};
  options.algorithms = {{"embree", ""}, {"ptsv", "twopass"}};
  options.backends = {"embree", "reference", "simd"};
  options.repeats = 1;
  options.out_dir = (dir / "out").string();
  FlushRecorder buffer;
  std::ostream out(&buffer);
  std::ostringstream err;
  ASSERT_EQ(run_suite(options, builtin_registry(), out, err), exit_pass);
  const std::string all = buffer.str();
  const std::string text = all.substr(0, all.find("\nsummary"));  // the per-case part
  std::size_t records = 0, plans = 0, start = 0;
  bool in_plan = false;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start) + 1;
    const std::string line = text.substr(start, end - start);
    const bool record = line.rfind("  Pass ", 0) == 0;
    const bool plan = line.rfind("case ", 0) == 0 || line.rfind("  oracle:", 0) == 0 ||
                      line.rfind("  run:", 0) == 0 || line.rfind("  left out:", 0) == 0;
    if (in_plan && !plan) {  // the plan ended at `start`
      EXPECT_TRUE(buffer.flushed_at.count(start)) << "plan not flushed before: " << line;
      ++plans;
    }
    if (record) {
      EXPECT_TRUE(buffer.flushed_at.count(end)) << "not flushed: " << line;
      ++records;
    }
    in_plan = plan;
    start = end;
  }
  EXPECT_EQ(records, 6u) << text;  // per case: embree, ptsv:twopass reference and simd
  EXPECT_EQ(plans, 2u) << text;
}

}  // namespace
}  // namespace shadowcts
