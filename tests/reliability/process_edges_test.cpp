// What surrounds a command: an invalid INVFREE_THREADS is refused with one
// line (exit 2) instead of being silently ignored, and standard output that cannot be
// written (a full device, a file-size limit) fails the command with one line (exit 4)
// instead of exit 0 with the summary lost.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "tests/reliability/output_checks.h"
#include "tests/reliability/process.h"

namespace invfree {
namespace {

namespace fs = std::filesystem;
using namespace test;

TEST(Environment, InvalidThreadCountIsRefused) {
  for (const char* value : {"abc", "0", "257", "-1", "3x", " 2", "2.5", "1e2", "99999999999"}) {
    const ProcessResult r =
        run_invfree({"simulate", "--steps", "2"}, {std::string("INVFREE_THREADS=") + value});
    EXPECT_EQ(r.code, 2) << value << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << r.err;
    EXPECT_NE(r.err.find("INVFREE_THREADS=\"" + std::string(value) +
                         "\": expected a whole number from 1 to 256"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "") << value << ": no step may run";
  }
  for (const char* value : {"1", "2", "256", ""}) {
    const ProcessResult r =
        run_invfree({"simulate", "--steps", "2"}, {std::string("INVFREE_THREADS=") + value});
    EXPECT_EQ(r.code, 0) << value << ": " << r.err;
  }
  // --help still works: the variable is checked only when a command runs.
  const ProcessResult r = run_invfree({"simulate", "--help"}, {"INVFREE_THREADS=abc"});
  EXPECT_EQ(r.code, 0) << r.err;
}

void expect_summary_write_fails(const ProcessResult& r) {
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("invfree: standard output: write failed"), std::string::npos) << r.err;
}

// `ulimit -f 1`: no file may grow past 1 KiB. Standard output appends to a file that
// already holds 1 KiB, so the summary line fails with EFBIG, while the error line still
// fits into the (empty) stderr file. Works without root.
TEST(StandardOutput, FileSizeLimitFailsTheCommand) {
  const std::string dir = fresh_dir("stdout_fsize");
  { std::ofstream(dir + "/out.txt") << std::string(1024, '#'); }
  const ProcessResult r =
      run_invfree({"simulate", "--steps", "2"}, {}, "ulimit -f 1;", stdout_to(dir + "/out.txt"));
  expect_summary_write_fails(r);
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// A full device (root only: a node like /dev/full, made inside the temporary directory).
TEST(StandardOutput, FullDeviceFailsTheCommand) {
  if (::geteuid() != 0) GTEST_SKIP() << "making a device node needs root";
  const std::string dir = fresh_dir("stdout_full");
  const std::string full = dir + "/full";
  ASSERT_EQ(::mknod(full.c_str(), S_IFCHR | 0666, ::makedev(1, 7)), 0) << std::strerror(errno);
  const ProcessResult r = run_invfree({"simulate", "--steps", "2"}, {}, "", stdout_to(full));
  expect_summary_write_fails(r);
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  struct stat st {};
  ASSERT_EQ(::lstat(full.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace invfree
