// Output is never lost or corrupted: atomic writes, a full disk (a tiny tmpfs when the
// tests may mount one, and always a file-size limit), unwritable directories, an existing
// non-empty output directory, and Ctrl-C / SIGTERM in the middle of a run. After every
// failure each file under a final name is complete and no temporary file is left.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <string>

#include "app/exit_codes.h"
#include "app/output_files.h"
#include "tests/reliability/output_checks.h"
#include "tests/reliability/process.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using namespace test;

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
  EXPECT_NE(check_output_file(dir).message.find("is a directory"), std::string::npos);
  EXPECT_EQ(check_output_file(dir).exit_code, exit_code::kBadInput);
  OutputDirectory out;
  OutputError e = out.open(dir + "/a.txt", false);
  EXPECT_NE(e.message.find("exists and is not a directory"), std::string::npos) << e.message;
  EXPECT_EQ(e.exit_code, exit_code::kBadInput);
  e = out.open(dir, false);
  EXPECT_NE(e.message.find("not empty (use --force"), std::string::npos) << e.message;
  EXPECT_EQ(e.exit_code, exit_code::kBadInput);
  EXPECT_FALSE(fs::exists(dir + "/" + OutputDirectory::kLockFile))
      << "a refused directory gets no lock file";
  e = out.open(dir, true);
  EXPECT_FALSE(e) << e.message;
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
  // The table would be kept (see CsvOnAHealthyDiskIsKept), but this disk has no room
  // left for its last rows either: it is not left half-written, and the line says so.
  EXPECT_FALSE(fs::exists(dir + "/run.csv")) << "no room to complete the table";
  EXPECT_NE(r.err.find(dir + "/run.csv: write failed"), std::string::npos) << r.err;
  expect_only_complete_objs(dir, 25, 32);  // no temporary CSV either
}

TEST(FullDisk, FileSizeLimit) {
  const std::string dir = fresh_dir("fsize");
  // ulimit -f 8: no file may exceed 8 KiB; an n_seg 16 OBJ is ~20 kB, so the very
  // first one fails (EFBIG, reported like a full disk rather than killing the process).
  // The CSV, far below the limit, is kept complete for the steps kept: none.
  auto r = run_invfree({"simulate", "--steps", "5", "--set", "mesh.n_seg=16", "--obj", dir + "/obj",
                        "--csv", dir + "/kept.csv"},
                       {}, "ulimit -f 8;");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find(dir + "/obj/0.obj: write failed: File too large (file-size limit reached)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(expect_only_complete_objs(dir + "/obj", 289, 512), 0);
  EXPECT_EQ(
      slurp(dir + "/kept.csv"),
      "step,t,newton_iters,residual,incremental_potential,min_det_F,max_det_F,min_gap,ceiling_y,"
      "kinetic,elastic,gravitational,contact,min_self_gap,self_intersecting,wall_ms\n");
  // A CSV that outgrows the limit: no table under its final name, no temporary left.
  r = run_invfree({"simulate", "--steps", "2000", "--csv", dir + "/run.csv"}, {}, "ulimit -f 16;");
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_NE(r.err.find(dir + "/run.csv: write failed: File too large"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/run.csv"));
  expect_only_complete_objs(dir, 0, 0);
  fs::remove_all(dir);
}

// Issue 20: the OBJ directory's disk fills; the CSV, on a healthy disk, is kept complete
// for the steps whose OBJ was written (as after a failed step or Ctrl-C), not discarded.
TEST(FullDisk, CsvOnAHealthyDiskIsKept) {
  const std::string dir = fresh_dir("tmpfs_obj");
  TinyFilesystem tiny(dir + "/small", "size=48k");
  if (!tiny.mounted())
    GTEST_SKIP() << "cannot mount a tmpfs here (" << tiny.reason() << "); FileSizeLimit covers it";
  const auto r = run_invfree(
      {"simulate", "--steps", "300", "--obj", dir + "/small/obj", "--csv", dir + "/run.csv"});
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("No space left on device (disk full)"), std::string::npos) << r.err;
  const int objs = expect_only_complete_objs(dir + "/small/obj", 25, 32);
  ASSERT_GT(objs, 3);
  ASSERT_LT(objs, 300);
  EXPECT_NE(r.err.find("outputs hold steps 0.." + std::to_string(objs - 1)), std::string::npos)
      << r.err;
  // Header and one row per step 1..objs-1, the last one the step of the last OBJ.
  const std::string csv = slurp(dir + "/run.csv");
  EXPECT_EQ(count_lines_with_prefix(csv, ""), objs) << csv;
  EXPECT_NE(csv.find("\n" + std::to_string(objs - 1) + ","), std::string::npos) << csv;
  EXPECT_EQ(csv.find("\n" + std::to_string(objs) + ","), std::string::npos) << csv;
  expect_only_complete_objs(dir, 0, 0);  // no temporary CSV
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
  // An output path that is a file, or a CSV path that is a directory: the wrong kind of
  // target is bad input (docs/outputs.md).
  r = run_invfree({"simulate", "--steps", "3", "--obj", dir + "/keep.txt"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("keep.txt: exists and is not a directory"), std::string::npos) << r.err;
  r = run_invfree({"simulate", "--steps", "3", "--csv", dir});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(dir + ": is a directory"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// Starts a long run, waits for 40 OBJ files, sends `sig`, and checks that the run stops
// with `expected_code`, keeping complete outputs for the steps taken.
void interrupt_run(int sig, int expected_code) {
  const std::string dir = fresh_dir("interrupt_" + std::to_string(sig));
  test::Process p({::invfree::test::exe_path(), "simulate", "--steps", "100000000", "--obj", dir + "/obj", "--csv",
                   dir + "/run.csv"});
  ASSERT_GT(p.pid(), 0);
  wait_for_files(dir + "/obj", ".obj", 40);
  ASSERT_EQ(::kill(p.pid(), sig), 0);
  const test::ProcessResult r = p.wait();
  EXPECT_EQ(r.code, expected_code) << r.err;
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

TEST(Interrupt, CtrlCDuringARenderLeavesOnlyCompleteFrames) {
  const std::string dir = fresh_dir("render_interrupt");
  test::Process p(
      {::invfree::test::exe_path(), "render", "--frames", "100000", "--size", "160x120", "--out", dir + "/frames"});
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
  interrupt_run(SIGINT, 130);
}
TEST(Interrupt, SigtermKeepsOnlyCompleteOutput) {
  interrupt_run(SIGTERM, 130);
}
// A dropped SSH session: the run stops as for Ctrl-C, with exit code 129.
TEST(Interrupt, HangUpKeepsOnlyCompleteOutput) {
  interrupt_run(SIGHUP, 129);
}

}  // namespace
}  // namespace invfree
