// Issue 31, the third reliability round: a movie ffmpeg could not finish is never left as
// the movie (file-size limit, full disk); the lock file is never written through a hard
// link; threads that cannot be made mean fewer threads, not an abort; a process under an
// address-space limit exits (OpenBLAS); outputs that would collide are refused before the
// first step; a signal stops one long step; an output directory swapped for a symbolic
// link mid-run keeps getting the files; --ui-scale nan is bad input. Resource limits are
// set in the child (bash's ulimit) and a tmpfs is mounted only where the test may.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

#include "app/movie.h"
#include "tests/reliability/output_checks.h"
#include "tests/reliability/process.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using namespace test;

bool have_ffmpeg() {
  return fs::exists("/usr/bin/ffmpeg");
}

// AddressSanitizer reserves terabytes of address space and runs threads of its own (the
// leak check at exit), so the program built with it cannot run under ulimit -v or -u.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif
#define SKIP_UNDER_ASAN() \
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v or -u"

// The last line of `text` (without its newline).
std::string last_line(const std::string& text) {
  std::string t = text;
  if (!t.empty() && t.back() == '\n') t.pop_back();
  const size_t nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

int count_with_extension(const std::string& dir, const std::string& extension) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) n += e.path().extension() == extension;
  return n;
}

// ---- 1. The movie is checked before it is renamed into place ---------------------------

// 40 frames of 64x64 (each under 2 KiB) fit a 4 KiB file-size limit; the movie (about
// 6 KiB of MP4, 13 KiB of GIF) does not. ffmpeg 5.1 exits 0 all the same.
TEST(MovieCheck, FileSizeLimitLeavesNoMovie) {
  if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed";
  for (const bool gif : {false, true}) {
    const std::string dir = fresh_dir(gif ? "movie_fsize_gif" : "movie_fsize_mp4") + "/f";
    const std::string movie = gif ? "movie.gif" : "movie.mp4";
    const ProcessResult r = run_invfree(
        {"render", "--frames", "40", "--size", "64x64", gif ? "--gif" : "--mp4", "--out", dir}, {},
        "ulimit -f 4;");
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_EQ(last_line(r.err).rfind("invfree: " + dir + "/" + movie +
                                         ": write failed: File too large (file-size limit "
                                         "reached); what ffmpeg wrote is no complete movie",
                                     0),
              0u)
        << r.err;
    EXPECT_FALSE(fs::exists(dir + "/" + movie)) << "a truncated movie under its final name";
    EXPECT_EQ(expect_only_complete_pngs(dir), 40);  // and no temporary left
    fs::remove_all(fs::path(dir).parent_path());
  }
}

// A disk with room for the frames and one more page: the movie does not fit.
TEST(MovieCheck, FullDiskLeavesNoMovie) {
  if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed";
  const std::string base = fresh_dir("movie_full");
  const std::vector<std::string> args = {"render", "--frames", "40", "--size", "64x64"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> all = args;
    all.insert(all.end(), extra.begin(), extra.end());
    return all;
  };
  ProcessResult r = run_invfree(with({"--out", base + "/measure"}));
  ASSERT_EQ(r.code, 0) << r.err;
  long pages = 0;  // the frames' pages on a tmpfs
  for (const auto& e : fs::directory_iterator(base + "/measure"))
    pages += (static_cast<long>(fs::file_size(e.path())) + 4095) / 4096;
  for (const bool gif : {false, true}) {
    const std::string mount = base + (gif ? "/disk_gif" : "/disk_mp4");
    TinyFilesystem disk(mount, "size=" + std::to_string((pages + 1) * 4) + "k");
    if (!disk.mounted())
      GTEST_SKIP() << "cannot mount a tmpfs here (" << disk.reason() << "): needs root";
    const std::string movie = gif ? "movie.gif" : "movie.mp4";
    r = run_invfree(with({gif ? "--gif" : "--mp4", "--out", mount + "/f"}));
    EXPECT_EQ(r.code, 4) << r.err;
    // ffmpeg fails by itself (exit 1) or exits 0 with what it could write: exit 4 either way.
    EXPECT_NE(last_line(r.err).find(mount + "/f/" + movie), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(mount + "/f/" + movie));
    EXPECT_EQ(expect_only_complete_pngs(mount + "/f"), 40);
  }
  fs::remove_all(base);
}

// The check itself: a complete movie passes; every cut of it is refused.
TEST(MovieCheck, EveryTruncationIsRefused) {
  if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed";
  const std::string dir = fresh_dir("movie_cut") + "/f";
  const ProcessResult r =
      run_invfree({"render", "--frames", "12", "--size", "64x64", "--mp4", "--gif", "--out", dir});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const bool gif : {false, true}) {
    const std::string movie = dir + (gif ? "/movie.gif" : "/movie.mp4");
    EXPECT_EQ(check_movie_file(movie, gif, 12), "");
    if (!gif) {
      EXPECT_NE(check_movie_file(movie, gif, 13), "") << "frame count";
    }
    const std::string bytes = slurp(movie);
    const std::string cut = dir + "/cut";
    for (size_t n = 0; n < bytes.size(); n += 1 + n / 16) {
      std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), n);
      EXPECT_NE(check_movie_file(cut, gif, 12), "") << movie << " cut at " << n << " bytes";
    }
  }
  fs::remove_all(fs::path(dir).parent_path());
}

// ---- 2. The lock file is never written through a hard link ----------------------------

TEST(LockFile, AHardLinkOrAForeignFileIsRefusedAndLeftAsItWas) {
  const std::string dir = fresh_dir("lock_link");
  const std::string scene = dir + "/scene.toml";
  fs::copy_file(std::string(source_dir()) + "/assets/scenes/compress.toml", scene);
  const std::string text = slurp(scene);
  fs::create_directory(dir + "/obj");
  fs::create_hard_link(scene, dir + "/obj/.invfree.lock");
  for (const bool force : {false, true}) {
    std::vector<std::string> args = {"simulate", "--scene", scene,       "--steps",
                                     "1",        "--obj",   dir + "/obj"};
    if (force) args.push_back("--force");
    const ProcessResult r = run_invfree(args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find(".invfree.lock: is a hard link"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(scene), text) << "the scene file was written through the lock's link";
    EXPECT_FALSE(fs::exists(dir + "/obj/0.obj"));
  }
  // A file of one link that is no lock file (other content) is not written into either.
  fs::remove(dir + "/obj/.invfree.lock");
  { std::ofstream(dir + "/obj/.invfree.lock") << "notes\n"; }
  ProcessResult r = run_invfree({"simulate", "--steps", "1", "--obj", dir + "/obj"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(slurp(dir + "/obj/.invfree.lock"), "notes\n");
  // What a killed run leaves (its pid) is still taken over, and removed at the end.
  { std::ofstream(dir + "/obj/.invfree.lock", std::ios::trunc) << "4194303\n"; }
  r = run_invfree({"simulate", "--steps", "1", "--obj", dir + "/obj"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/obj/.invfree.lock"));
  fs::remove_all(dir);
}

// ---- 3, 4. Resource limits ------------------------------------------------------------

// 256 worker threads asked for under a 1.5 GB address-space limit: most cannot be made
// (each reserves a stack and a malloc arena). The pool runs with those it could make, and
// the answer is the one of any thread count. In render the pool is made inside the
// simulation thread, where a thrown std::system_error used to abort the process.
TEST(ResourceLimits, ThreadsThatCannotBeMadeMeanFewerThreads) {
  SKIP_UNDER_ASAN();
  const std::string dir = fresh_dir("threads_limit");
  ProcessResult r =
      run_invfree({"simulate", "--steps", "30", "--obj", dir + "/one"}, {"INVFREE_THREADS=1"});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_invfree({"simulate", "--steps", "30", "--obj", dir + "/many"}, {"INVFREE_THREADS=256"},
                  "ulimit -v 1500000;");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(slurp(dir + "/many/30.obj"), slurp(dir + "/one/30.obj"));
  r = run_invfree({"render", "--frames", "3", "--size", "64x64", "--out", dir + "/frames"},
                  {"INVFREE_THREADS=256"}, "ulimit -v 1500000;");
  EXPECT_TRUE(r.code == 0 || ((r.code == 3 || r.code == 4) && one_line(r.err))) << r.err;
  fs::remove_all(dir);
}

// A process-count limit (ulimit -u) that leaves room for one more thread, as an
// unprivileged user (root is not held to it: as root the test runs the program as
// nobody). The pool asked for 8 threads gets 2 and computes the same bits; before, the
// thread that could not be made ended the run (exit 3 "internal error", or an abort where
// the pool is made inside render's simulation thread). Another thread that cannot be
// made (render's PNG writers) is one line and exit 3.
TEST(ResourceLimits, AProcessCountLimitMeansFewerThreads) {
  SKIP_UNDER_ASAN();
  const std::string dir = fresh_dir("nproc_limit");
  fs::permissions(dir, fs::perms::all);
  ProcessResult r =
      run_invfree({"simulate", "--steps", "30", "--obj", dir + "/one"}, {"INVFREE_THREADS=1"});
  ASSERT_EQ(r.code, 0) << r.err;
  auto limited = [&](const std::vector<std::string>& args) {
    std::vector<std::string> full;
    if (::geteuid() == 0) {
      if (!fs::exists("/usr/bin/setpriv")) return ProcessResult{-1, "", "no setpriv"};
      full = {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"};
    }
    for (const char* a : {"/bin/bash", "-c", "ulimit -u 2; exec \"$0\" \"$@\""}) full.push_back(a);
    full.push_back(exe_path());
    full.insert(full.end(), args.begin(), args.end());
    return Process(full, {"INVFREE_THREADS=8"}).wait();
  };
  if (::geteuid() == 0 && !fs::exists("/usr/bin/setpriv"))
    GTEST_SKIP() << "running as root without setpriv (util-linux) to drop to nobody";
  r = limited({"simulate", "--steps", "30", "--obj", dir + "/few"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/few/30.obj"), slurp(dir + "/one/30.obj"));
  r = limited({"render", "--frames", "2", "--size", "64x64", "--out", dir + "/frames"});
  EXPECT_TRUE(r.code == 0 || (r.code == 3 && one_line(r.err))) << r.code << ": " << r.err;
  fs::remove_all(dir);
}

// OSMesa's shader compiler crashes (SIGSEGV) when an allocation fails under ulimit -v
// 300-500 MB (Mesa 22.3; at 300 and 500 MB with OpenBLAS on one thread, as here, where it
// does not restart the program). That is reported: one line, exit 3 ("out of memory", the
// limit); a context OSMesa refuses is exit 4 (the frames cannot be made).
TEST(ResourceLimits, OffscreenRenderingUnderAMemoryLimitEndsInOneLine) {
  SKIP_UNDER_ASAN();
  const std::string dir = fresh_dir("osmesa_limit");
  for (const char* limit : {"300000", "500000"}) {
    const ProcessResult r = run_invfree(
        {"render", "--frames", "2", "--size", "64x64", "--force", "--out", dir},
        {"INVFREE_THREADS=1", "OPENBLAS_NUM_THREADS=1"}, std::string("ulimit -v ") + limit + ";");
    EXPECT_TRUE(r.code == 0 || r.code == 3 || r.code == 4)
        << limit << ": exit " << r.code << ": " << r.err;
    if (r.code != 0) {
      EXPECT_TRUE(one_line(r.err)) << r.err;
    }
    if (r.code == 3) {
      EXPECT_EQ(r.err.rfind("invfree: out of memory", 0), 0u) << r.err;
    }
  }
  fs::remove_all(dir);
}

// OpenBLAS starts its threads when it is loaded; under ulimit -v 200 MB each retried its
// 128 MiB buffer forever and every command, even --version, printed its output and never
// exited (the test gives it 60 s, far more than it needs).
TEST(ResourceLimits, ExitsUnderASmallAddressSpaceLimit) {
  SKIP_UNDER_ASAN();
  const std::string dir = fresh_dir("blas_limit");
  const std::vector<std::vector<std::string>> commands = {
      {"--version"}, {"simulate", "--steps", "5", "--csv", dir + "/run.csv"}};
  for (const auto& args : commands) {
    std::vector<std::string> full = {exe_path()};
    full.insert(full.end(), args.begin(), args.end());
    Process p(full, {}, "unset OPENBLAS_NUM_THREADS; ulimit -v 200000;");
    ASSERT_TRUE(p.exits_within(60)) << args[0] << " did not exit under ulimit -v 200000";
    const ProcessResult r = p.wait();
    EXPECT_EQ(r.code, 0) << args[0] << ": " << r.err;
  }
  EXPECT_EQ(count_lines_with_prefix(slurp(dir + "/run.csv"), ""), 6);
  fs::remove_all(dir);
}

// ---- 7. Outputs that would collide are refused before the first step -----------------

TEST(OutputConflicts, ACsvThatIsTheObjDirectoryIsRefusedFirst) {
  const std::string dir = fresh_dir("conflict");
  for (const auto& [obj, csv] : std::vector<std::pair<std::string, std::string>>{
           {dir + "/d", dir + "/d"}, {dir + "/d/", dir + "/./d"}, {dir + "/e/sub", dir + "/e"}}) {
    const ProcessResult r =
        run_invfree({"simulate", "--steps", "3000", "--obj", obj, "--csv", csv});
    EXPECT_EQ(r.code, 2) << obj << " " << csv << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("give them different paths"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(obj + "/0.obj")) << "refused only after a run";
  }
  // live checks its outputs before the window opens: exit 2, not 4 for want of a display.
  const ProcessResult r =
      run_invfree({"live", "--frames", "1", "--record", dir + "/r", "--screenshot", dir + "/r"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--screenshot"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(OutputConflicts, ACsvInsideANewObjDirectoryIsFine) {
  const std::string dir = fresh_dir("csv_inside") + "/new";
  const ProcessResult r =
      run_invfree({"simulate", "--steps", "3", "--obj", dir, "--csv", dir + "/run.csv"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(expect_only_complete_objs(dir, 25, 32), 4);
  EXPECT_EQ(count_lines_with_prefix(slurp(dir + "/run.csv"), ""), 4);
  fs::remove_all(fs::path(dir).parent_path());
}

// ---- 9. A signal stops one long step ---------------------------------------------------

long cpu_ticks(pid_t pid) {
  std::istringstream in(slurp("/proc/" + std::to_string(pid) + "/stat"));
  std::string field;
  long ticks = 0;
  for (int i = 1; in >> field && i <= 15; ++i)
    if (i == 14 || i == 15) ticks += std::atol(field.c_str());  // utime, stime
  return ticks;
}

TEST(Signals, SigtermStopsOneLongStep) {
  const std::string dir = fresh_dir("long_step");
  // A tolerance no step reaches and a cap of 100,000 iterations on 2,401 nodes: step 1
  // would run for minutes.
  Process p({exe_path(), "simulate", "--steps", "3", "--set", "mesh.n_seg=48", "--set",
             "time.tol=1e-300", "--set", "time.max_newton=100000", "--obj", dir + "/obj", "--csv",
             dir + "/run.csv"});
  ASSERT_GT(p.pid(), 0);
  wait_for_files(dir + "/obj", ".obj", 1);
  // Inside step 1 for sure: a quarter of a second of CPU time after step 0 was written.
  const long start = cpu_ticks(p.pid());
  for (int i = 0; i < 20000 && cpu_ticks(p.pid()) < start + sysconf(_SC_CLK_TCK) / 4; ++i)
    ::usleep(1000);
  ASSERT_EQ(::kill(p.pid(), SIGTERM), 0);
  ASSERT_TRUE(p.exits_within(60)) << "one SIGTERM did not stop the step";
  const ProcessResult r = p.wait();
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_EQ(last_line(r.err), "invfree: interrupted after step 0; outputs hold steps 0..0");
  EXPECT_EQ(expect_only_complete_objs(dir + "/obj", 49 * 49, 2 * 48 * 48), 1);
  EXPECT_EQ(count_lines_with_prefix(slurp(dir + "/run.csv"), ""), 1);  // the header
  fs::remove_all(dir);
}

// ---- 11. An output directory swapped for a symbolic link mid-run ------------------------

TEST(OutputDirectory, SwappedForALinkMidRunTheRunKeepsItsDirectory) {
  const std::string dir = fresh_dir("swap");
  Process p({exe_path(), "simulate", "--steps", "1000", "--obj", dir + "/obj"});
  ASSERT_GT(p.pid(), 0);
  wait_for_files(dir + "/obj", ".obj", 3);
  ASSERT_EQ(::kill(p.pid(), SIGSTOP), 0);
  ASSERT_LT(count_with_extension(dir + "/obj", ".obj"), 1001) << "the run ended too soon";
  fs::rename(dir + "/obj", dir + "/moved");
  fs::create_directory(dir + "/elsewhere");
  fs::create_directory_symlink(dir + "/elsewhere", dir + "/obj");
  ASSERT_EQ(::kill(p.pid(), SIGCONT), 0);
  const ProcessResult r = p.wait();
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_empty(dir + "/elsewhere")) << "files went through the planted link";
  EXPECT_EQ(expect_only_complete_objs(dir + "/moved", 25, 32), 1001);
  EXPECT_FALSE(fs::exists(dir + "/moved/.invfree.lock"));
  fs::remove_all(dir);
}

// ---- 11. --ui-scale nan ----------------------------------------------------------------

TEST(LiveOptions, UiScaleMustBeAFiniteNumber) {
  for (const char* scale : {"nan", "NaN", "inf", "-inf", "0.5", "4"}) {
    const ProcessResult r = run_invfree({"live", "--frames", "1", "--ui-scale", scale});
    EXPECT_EQ(r.code, 2) << scale << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("--ui-scale"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace invfree
