// What an output may be (docs/outputs.md): a regular file or nothing yet — a
// FIFO, a device node, a directory, a link to a device, `-` or the command's own stdout
// are refused with exit 2 before the first step and left as they were; an output that is
// one of the inputs (same path, a hard or symbolic link, another spelling) likewise; a
// missing parent directory is created. And one writer per output directory: a second
// run into a directory another run is filling is refused (exit 2, naming the holder's
// pid), also with --force; the lock file is removed at the end of a run, and one left by
// a run killed with SIGKILL does not block.
// Device nodes are made inside a temporary directory, never under /dev.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <string>
#include <vector>

#include "app/exit_codes.h"
#include "app/output_files.h"
#include "tests/reliability/output_checks.h"
#include "tests/reliability/process.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using namespace test;

bool is_fifo(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

// `invfree simulate --csv target ...` is refused before the first step: exit 2, one line
// naming the target and containing `why`, nothing on stdout (the summary of a run).
void expect_csv_refused(const std::string& target, const std::string& why,
                        const std::vector<std::string>& extra = {},
                        const SpawnOptions& options = {}) {
  std::vector<std::string> args = {"simulate", "--steps", "3", "--csv", target};
  args.insert(args.end(), extra.begin(), extra.end());
  const ProcessResult r = run_invfree(args, {}, "", options);
  EXPECT_EQ(r.code, 2) << target << ": " << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("invfree: " + target + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
  if (options.stdout_path.empty()) {
    EXPECT_EQ(r.out, "") << "no step may run";
  }
}

TEST(OutputTargets, NonRegularFilesAreRefusedAndLeftAsTheyWere) {
  const std::string dir = fresh_dir("targets");
  const std::string fifo = dir + "/fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  expect_csv_refused(fifo, "is a FIFO (named pipe); an output must be a regular file");
  EXPECT_TRUE(is_fifo(fifo)) << "the FIFO was replaced";

  // A link to a device is judged by the device (it is refused; nothing is written, so
  // pointing it at the real /dev/null is safe).
  const std::string link = dir + "/null-link";
  fs::create_symlink("/dev/null", link);
  expect_csv_refused(link, "is a character device");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(fs::read_symlink(link), "/dev/null");

  expect_csv_refused(dir, "is a directory");
  expect_csv_refused("-", "cannot be standard output");

  // The command's own standard output, by its name or through a link like /dev/stdout
  // (made here: a command that got this wrong would replace the link, so never /dev's).
  const std::string log = dir + "/log.txt";
  expect_csv_refused(log, "is this command's standard output", {}, stdout_to(log));
  fs::create_symlink("/proc/self/fd/1", dir + "/stdout");
  expect_csv_refused(dir + "/stdout", "is this command's standard output", {}, stdout_to(log));

  // A real device node (root only): a null device made inside the temporary directory.
  if (::geteuid() == 0) {
    const std::string node = dir + "/null-device";
    ASSERT_EQ(::mknod(node.c_str(), S_IFCHR | 0666, ::makedev(1, 3)), 0) << std::strerror(errno);
    expect_csv_refused(node, "is a character device");
    struct stat st {};
    ASSERT_EQ(::lstat(node.c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  }

  // The fixed-name outputs of bench (and study, stability) follow the same rule.
  const std::string bench = dir + "/bench";
  fs::create_directories(bench);
  ASSERT_EQ(::mkfifo((bench + "/bench.csv").c_str(), 0644), 0);
  const ProcessResult r = run_invfree({"bench", "--sizes", "4", "--steps", "1", "--out", bench});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(bench + "/bench.csv: is a FIFO"), std::string::npos) << r.err;
  EXPECT_TRUE(is_fifo(bench + "/bench.csv"));
  fs::remove_all(dir);
}

TEST(OutputTargets, AnOutputThatIsAnInputIsRefused) {
  const std::string dir = fresh_dir("alias");
  const std::string scene = dir + "/scene.toml";
  fs::copy_file(std::string(::invfree::test::source_dir()) + "/assets/scenes/compress.toml", scene);
  const std::string original = slurp(scene);
  fs::create_hard_link(scene, dir + "/hard.csv");
  fs::create_symlink(scene, dir + "/soft.csv");
  fs::create_directories(dir + "/sub");
  for (const std::string& target :
       {scene, dir + "/hard.csv", dir + "/soft.csv", dir + "/sub/../scene.toml"}) {
    expect_csv_refused(target, "is the input file " + scene, {"--scene", scene});
    EXPECT_EQ(slurp(scene), original) << "the scene was overwritten through " << target;
  }
  EXPECT_TRUE(fs::is_symlink(dir + "/soft.csv"));
  // study names its outputs inside --out: a scene there called study.csv is refused too.
  fs::copy_file(scene, dir + "/study.csv");
  const ProcessResult r =
      run_invfree({"study", "--quick", "--scene", dir + "/study.csv", "--out", dir});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(dir + "/study.csv: is the input file"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir + "/study.csv"), original);
  fs::remove_all(dir);
}

// A missing parent directory of an output (and an output directory's missing parents)
// is created, as docs/outputs.md says.
TEST(OutputTargets, MissingParentDirectoriesAreCreated) {
  const std::string dir = fresh_dir("parents");
  const ProcessResult r = run_invfree(
      {"simulate", "--steps", "2", "--csv", dir + "/a/b/run.csv", "--obj", dir + "/c/d/obj"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir + "/a/b/run.csv"));
  EXPECT_EQ(expect_only_complete_objs(dir + "/c/d/obj", 25, 32), 3);
  fs::remove_all(dir);
}

TEST(OutputLock, OneRunPerDirectoryInOneProcess) {
  const std::string dir = fresh_dir("lock_unit");
  OutputDirectory first, second;
  ASSERT_FALSE(first.open(dir, false));
  EXPECT_TRUE(fs::exists(dir + "/" + OutputDirectory::kLockFile));
  // flock belongs to the open file, so a second open in the same process conflicts too.
  OutputError e = second.open(dir, true);
  EXPECT_EQ(e.exit_code, exit_code::kBadInput);
  EXPECT_NE(e.message.find(dir + ": another invfree run is writing into this directory (pid " +
                           std::to_string(::getpid()) + ")"),
            std::string::npos)
      << e.message;
  first.close();
  EXPECT_FALSE(fs::exists(dir + "/" + OutputDirectory::kLockFile)) << "removed when released";
  e = second.open(dir, false);
  EXPECT_FALSE(e) << e.message;
  second.close();
  // The lock file a killed run left behind: held by nobody, and not counted as content.
  { std::ofstream(dir + "/" + OutputDirectory::kLockFile) << "12345\n"; }
  e = first.open(dir, false);
  EXPECT_FALSE(e) << e.message;
  EXPECT_EQ(slurp(dir + "/" + OutputDirectory::kLockFile), std::to_string(::getpid()) + "\n");
  first.close();
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

// Two renders into one directory: without a lock both would pass the emptiness check and
// the second would overwrite the first's frames. The second is refused, with and without --force,
// and so is a simulate --obj into it; the first finishes undisturbed.
TEST(OutputLock, ASecondWriterIsRefused) {
  const std::string dir = fresh_dir("lock_two") + "/frames";
  Process first({::invfree::test::exe_path(), "render", "--frames", "100000", "--size", "96x64", "--out", dir});
  ASSERT_GT(first.pid(), 0);
  wait_for_files(dir, ".png", 3);
  const std::string holder = "another invfree run is writing into this directory (pid " +
                             std::to_string(first.pid()) + ")";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", "--frames", "2", "--size", "96x64", "--out", dir},
        std::vector<std::string>{"render", "--frames", "2", "--size", "96x64", "--out", dir,
                                 "--force"},
        std::vector<std::string>{"simulate", "--steps", "2", "--obj", dir, "--force"}}) {
    const ProcessResult r = run_invfree(args);
    EXPECT_EQ(r.code, 2) << args[0] << " " << args.back() << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find(dir + ": " + holder), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir + "/0.obj")) << "the refused simulate wrote into the directory";
  ASSERT_EQ(::kill(first.pid(), SIGINT), 0);
  const ProcessResult r = first.wait();
  EXPECT_EQ(r.code, 130) << r.err;
  const int frames = expect_only_complete_pngs(dir);
  int n = -1;
  ASSERT_EQ(std::sscanf(r.err.c_str(), "invfree: interrupted after frame %d", &n), 1) << r.err;
  EXPECT_EQ(frames, n) << "a frame of the first run was overwritten or removed";
  // The run is over: the lock (its file stays) no longer blocks.
  const ProcessResult later =
      run_invfree({"render", "--frames", "2", "--size", "96x64", "--out", dir, "--force"});
  EXPECT_EQ(later.code, 0) << later.err;
  EXPECT_FALSE(fs::exists(dir + "/" + OutputDirectory::kLockFile)) << "removed at the end";
  fs::remove_all(fs::path(dir).parent_path());
}

// The lock dies with its process: a run killed with SIGKILL never blocks a later one.
TEST(OutputLock, AKilledRunDoesNotBlockTheNext) {
  const std::string dir = fresh_dir("lock_killed") + "/obj";
  {
    Process killed({::invfree::test::exe_path(), "simulate", "--steps", "100000000", "--obj", dir});
    ASSERT_GT(killed.pid(), 0);
    wait_for_files(dir, ".obj", 5);
    ASSERT_EQ(::kill(killed.pid(), SIGKILL), 0);
    EXPECT_EQ(killed.wait().code, -SIGKILL);
  }
  EXPECT_TRUE(fs::exists(dir + "/" + OutputDirectory::kLockFile));
  const ProcessResult r = run_invfree({"simulate", "--steps", "2", "--obj", dir, "--force"});
  EXPECT_EQ(r.code, 0) << r.err;
  fs::remove_all(fs::path(dir).parent_path());
}

}  // namespace
}  // namespace invfree
