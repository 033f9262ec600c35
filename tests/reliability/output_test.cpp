// Output is never lost or corrupted: atomic writes, a full disk (a tiny tmpfs when the
// tests may mount one, and always a file-size limit), unwritable directories, an existing
// non-empty output directory, and Ctrl-C / SIGTERM in the middle of a run. After every
// failure each file under a final name is complete and no temporary file is left.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "app/output_files.h"
#include "tests/reliability/process.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using test::run_invfree;
using test::slurp;

std::string fresh_dir(const std::string& name) {
  const std::string dir =
      ::testing::TempDir() + "/output_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int count_lines_with_prefix(const std::string& text, const char* prefix) {
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

// Every file under `dir`: .obj files are complete meshes of `nodes` nodes and
// `triangles` triangles, and no temporary file is left. Returns the number of .obj files.
int expect_only_complete_objs(const std::string& dir, int nodes, int triangles) {
  int objs = 0;
  if (!fs::exists(dir)) return 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary file left behind: " << name;
    if (entry.path().extension() != ".obj") continue;
    ++objs;
    const std::string text = slurp(entry.path().string());
    EXPECT_FALSE(text.empty()) << name;
    EXPECT_EQ(text.back(), '\n') << name << " is truncated";
    EXPECT_EQ(count_lines_with_prefix(text, "v "), nodes) << name << " is truncated";
    EXPECT_EQ(count_lines_with_prefix(text, "f "), triangles) << name << " is truncated";
  }
  return objs;
}

bool one_line(const std::string& err) {
  return std::count(err.begin(), err.end(), '\n') == 1;
}

// A tmpfs of `size` mounted at `dir` for the scope's lifetime, when this process may.
class TinyFilesystem {
 public:
  TinyFilesystem(const std::string& dir, const std::string& options) : dir_(dir) {
    fs::create_directories(dir);
    mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
    if (!mounted_) reason_ = std::strerror(errno);
  }
  ~TinyFilesystem() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  void remount_read_only() {
    ASSERT_EQ(::mount("tmpfs", dir_.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, nullptr), 0)
        << std::strerror(errno);
  }

 private:
  std::string dir_, reason_;
  bool mounted_ = false;
};

TEST(AtomicFiles, WriteReplaceAndAbandon) {
  const std::string dir = fresh_dir("atomic");
  EXPECT_EQ(write_file_atomically(dir + "/a.txt", "first\n"), "");
  EXPECT_EQ(write_file_atomically(dir + "/a.txt", "second\n"), "");
  EXPECT_EQ(slurp(dir + "/a.txt"), "second\n");
  {
    AtomicFileWriter w;
    ASSERT_EQ(w.open(dir + "/b.csv"), "");
    EXPECT_EQ(w.append("x,y\n"), "");
    EXPECT_FALSE(fs::exists(dir + "/b.csv")) << "visible under its final name before commit";
  }  // destroyed without commit: nothing may remain
  {
    AtomicFileWriter w;
    ASSERT_EQ(w.open(dir + "/c.csv"), "");
    EXPECT_EQ(w.append("x,y\n"), "");
    EXPECT_EQ(w.append("1,2\n"), "");
    EXPECT_EQ(w.commit(), "");
  }
  EXPECT_EQ(slurp(dir + "/c.csv"), "x,y\n1,2\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"a.txt", "c.csv"}));
  // Errors name the path and leave nothing.
  const std::string e1 = write_file_atomically(dir + "/missing/x.txt", "x");
  EXPECT_NE(e1.find(dir + "/missing/x.txt: cannot create file: No such file or directory"),
            std::string::npos)
      << e1;
  EXPECT_NE(check_output_file(dir).find("is a directory"), std::string::npos);
  EXPECT_NE(
      prepare_output_directory(dir + "/a.txt", false, false).find("exists and is not a directory"),
      std::string::npos);
  bool refused = false;
  EXPECT_NE(prepare_output_directory(dir, true, false, &refused).find("not empty (use --force"),
            std::string::npos);
  EXPECT_TRUE(refused);
  EXPECT_EQ(prepare_output_directory(dir, true, true, &refused), "");
  EXPECT_FALSE(refused);
  fs::remove_all(dir);
}

TEST(FullDisk, TinyTmpfsGivesAClearErrorAndNoTruncatedFile) {
  const std::string dir = fresh_dir("tmpfs");
  TinyFilesystem tiny(dir, "size=48k");
  if (!tiny.mounted())
    GTEST_SKIP() << "cannot mount a tmpfs here (" << tiny.reason() << "); FileSizeLimit covers it";
  // n_seg 4: 25 nodes, 32 triangles, ~1.8 kB per OBJ: the disk fills after a few dozen.
  const auto r =
      run_invfree({"simulate", "--steps", "300", "--obj", dir + "/obj", "--csv", dir + "/run.csv"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("No space left on device (disk full)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(dir + "/obj/"), std::string::npos)
      << "the error must name the file: " << r.err;
  const int objs = expect_only_complete_objs(dir + "/obj", 25, 32);
  EXPECT_GT(objs, 3);
  EXPECT_LT(objs, 300);
  EXPECT_FALSE(fs::exists(dir + "/run.csv")) << "the run failed: no table under its final name";
  expect_only_complete_objs(dir, 25, 32);  // no temporary CSV either
}

TEST(FullDisk, FileSizeLimit) {
  const std::string dir = fresh_dir("fsize");
  // ulimit -f 8: no file may exceed 8 KiB; an n_seg 16 OBJ is ~20 kB, so the very
  // first one fails (EFBIG, reported like a full disk rather than killing the process).
  auto r =
      run_invfree({"simulate", "--steps", "5", "--set", "mesh.n_seg=16", "--obj", dir + "/obj"}, {},
                  "ulimit -f 8;");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find(dir + "/obj/0.obj: write failed: File too large (file-size limit reached)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(expect_only_complete_objs(dir + "/obj", 289, 512), 0);
  // A CSV that outgrows the limit: no table under its final name, no temporary left.
  r = run_invfree({"simulate", "--steps", "2000", "--csv", dir + "/run.csv"}, {}, "ulimit -f 16;");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find(dir + "/run.csv: write failed: File too large"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/run.csv"));
  expect_only_complete_objs(dir, 0, 0);
  fs::remove_all(dir);
}

TEST(UnwritableOutput, ClearErrorBeforeAnyStep) {
  // /proc accepts no new files, even from root.
  auto r = run_invfree({"simulate", "--steps", "5", "--obj", "/proc/invfree_no/obj"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("/proc/invfree_no/obj: cannot create directory"), std::string::npos)
      << r.err;
  r = run_invfree({"simulate", "--steps", "5", "--csv", "/proc/invfree.csv"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("/proc/invfree.csv: /proc: cannot create files in this directory"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out, "") << "the error comes before any step";

  // A read-only directory: a read-only tmpfs for root (who ignores permission bits),
  // permission bits otherwise.
  const std::string dir = fresh_dir("readonly");
  TinyFilesystem ro(dir + "/ro", "size=64k");
  if (::geteuid() == 0) {
    if (!ro.mounted()) GTEST_SKIP() << "root but cannot mount a tmpfs (" << ro.reason() << ")";
    ro.remount_read_only();
  } else {
    fs::permissions(dir + "/ro", fs::perms::owner_read | fs::perms::owner_exec);
  }
  r = run_invfree({"simulate", "--steps", "5", "--obj", dir + "/ro"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find(dir + "/ro: cannot create files in this directory"), std::string::npos)
      << r.err;
  r = run_invfree({"simulate", "--steps", "5", "--obj", dir + "/ro/sub"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find(dir + "/ro/sub: cannot create directory"), std::string::npos) << r.err;
  r = run_invfree({"simulate", "--steps", "5", "--csv", dir + "/ro/run.csv"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("cannot create files in this directory"), std::string::npos) << r.err;
  if (::geteuid() != 0) fs::permissions(dir + "/ro", fs::perms::owner_all);
}

TEST(ExistingOutput, NonEmptyDirectoryRefusedUnlessForce) {
  const std::string dir = fresh_dir("nonempty");
  { std::ofstream(dir + "/keep.txt") << "precious\n"; }
  auto r = run_invfree({"simulate", "--steps", "3", "--obj", dir});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find(dir + ": directory is not empty (use --force to write into it anyway)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/0.obj"));
  r = run_invfree({"simulate", "--steps", "3", "--obj", dir, "--force"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(expect_only_complete_objs(dir, 25, 32), 4);
  EXPECT_EQ(slurp(dir + "/keep.txt"), "precious\n");
  // An output path that is a file, or a CSV path that is a directory.
  r = run_invfree({"simulate", "--steps", "3", "--obj", dir + "/keep.txt"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find("keep.txt: exists and is not a directory"), std::string::npos) << r.err;
  r = run_invfree({"simulate", "--steps", "3", "--csv", dir});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find(dir + ": is a directory"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// Starts a long run, waits for `min_objs` OBJ files, sends `sig`, and checks the result.
// Waits (at most 120 s) until `dir` holds at least `count` files ending in `extension`.
void wait_for_files(const std::string& dir, const std::string& extension, int count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  auto files = [&] {
    int n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) n += e.path().extension() == extension;
    return n;
  };
  while (files() < count && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

void interrupt_run(int sig) {
  const std::string dir = fresh_dir("interrupt_" + std::to_string(sig));
  test::Process p({INVFREE_EXE, "simulate", "--steps", "100000000", "--obj", dir + "/obj", "--csv",
                   dir + "/run.csv"});
  ASSERT_GT(p.pid(), 0);
  wait_for_files(dir + "/obj", ".obj", 40);
  ASSERT_EQ(::kill(p.pid(), sig), 0);
  const test::ProcessResult r = p.wait();
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  long last = -1;
  ASSERT_EQ(std::sscanf(r.err.c_str(), "invfree: interrupted after step %ld", &last), 1) << r.err;
  EXPECT_GE(last, 39);
  // Exactly the steps 0..last, each complete; the table has one row per step taken.
  EXPECT_EQ(expect_only_complete_objs(dir + "/obj", 25, 32), last + 1);
  EXPECT_TRUE(fs::exists(dir + "/obj/" + std::to_string(last) + ".obj"));
  const std::string csv = slurp(dir + "/run.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), last + 1) << "header + one row per step";
  EXPECT_NE(csv.find("\n" + std::to_string(last) + ","), std::string::npos);
  EXPECT_NE(r.out.find(std::to_string(last) + " steps"), std::string::npos)
      << "the summary still prints";
  expect_only_complete_objs(dir, 0, 0);  // no temporary CSV
  fs::remove_all(dir);
}

// Every PNG under `dir` is whole (signature first, IEND chunk last) and no temporary is
// left; returns the number of frames.
int expect_only_complete_pngs(const std::string& dir) {
  int frames = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary file left behind: " << name;
    if (entry.path().extension() != ".png") continue;
    ++frames;
    const std::string png = slurp(entry.path().string());
    EXPECT_GT(png.size(), 20u) << name;
    if (png.size() <= 20u) continue;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << name;
    EXPECT_EQ(png.substr(png.size() - 8), std::string("IEND\xae\x42\x60\x82", 8))
        << name << " is truncated";
  }
  return frames;
}

TEST(Interrupt, CtrlCDuringARenderLeavesOnlyCompleteFrames) {
  const std::string dir = fresh_dir("render_interrupt");
  test::Process p(
      {INVFREE_EXE, "render", "--frames", "100000", "--size", "160x120", "--out", dir + "/frames"});
  ASSERT_GT(p.pid(), 0);
  wait_for_files(dir + "/frames", ".png", 10);
  ASSERT_EQ(::kill(p.pid(), SIGINT), 0);
  const test::ProcessResult r = p.wait();
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
  const int frames = expect_only_complete_pngs(dir + "/frames");
  EXPECT_GE(frames, 10);
  // Frames 0..n-1, no gap: a movie made from them is whole.
  for (int i = 0; i < frames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06d.png", i);
    EXPECT_TRUE(fs::exists(dir + "/frames" + name)) << name;
  }
  fs::remove_all(dir);
}

TEST(FullDisk, RenderOnATinyTmpfs) {
  const std::string dir = fresh_dir("render_tmpfs");
  TinyFilesystem tiny(dir, "size=256k");
  if (!tiny.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (" << tiny.reason() << ")";
  const auto r =
      run_invfree({"render", "--frames", "400", "--size", "320x240", "--out", dir + "/frames"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("No space left on device (disk full)"), std::string::npos) << r.err;
  EXPECT_GT(expect_only_complete_pngs(dir + "/frames"), 0);
}

TEST(Interrupt, CtrlCKeepsOnlyCompleteOutput) {
  interrupt_run(SIGINT);
}
TEST(Interrupt, SigtermKeepsOnlyCompleteOutput) {
  interrupt_run(SIGTERM);
}

}  // namespace
}  // namespace invfree
