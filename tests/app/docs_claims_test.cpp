// What docs/outputs.md says `render --mp4` refuses, it refuses (issue 31 item 11: the page
// said `--set time.h=1e-6 --mp4` is refused, but the automatic steps per frame render it at
// 30 frames/s). Every "`--set ... --mp4` ... is refused" of the page is run: exit 2 before
// the first frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <regex>
#include <string>

#include "tests/run_command.h"
#include "tests/test_paths.h"

namespace invfree {
namespace {

TEST(OutputsDoc, EveryRefusedMovieRateIsRefused) {
  const std::string page =
      test::slurp(std::string(::invfree::test::source_dir()) + "/docs/outputs.md");
  std::string flat = page;
  for (char& c : flat)
    if (c == '\n') c = ' ';
  const std::regex claim("`(--set [^`]*--mp4)`[^`]{0,40}? is refused");
  int claims = 0;
  for (std::sregex_iterator it(flat.begin(), flat.end(), claim), end; it != end; ++it) {
    ++claims;
    const std::string args = (*it)[1];
    const std::string dir =
        ::testing::TempDir() + "/docs_claims_" + std::to_string(::getpid()) + "_" +
        std::to_string(claims);
    const test::CommandResult r = test::run_command(
        ::invfree::test::exe_path(), "render " + args + " --frames 1 --out " + dir, true);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.out << r.err;
    std::filesystem::remove_all(dir);
  }
  EXPECT_GE(claims, 2) << "docs/outputs.md gives its refused examples";
}

}  // namespace
}  // namespace invfree
