// Checks that the documentation cannot rot: README.md stays short, its C++ example is
// exactly examples/embed.cpp (which tests/examples/ builds and runs), and every relative
// link, heading anchor and repository path written in README.md and docs/*.md exists.
// Input: the source tree (tests/test_paths.h). Output: one failure per broken reference.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_paths.h"

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = ::invfree::test::source_dir();

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<fs::path> markdown_files() {
  std::vector<fs::path> files{kRoot / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "docs"))
    if (e.path().extension() == ".md") files.push_back(e.path());
  return files;
}

// GitHub's anchor for a heading: lower case, spaces to '-', ASCII punctuation other than
// '-' and '_' dropped (non-ASCII bytes kept).
std::string anchor_of(const std::string& heading) {
  std::string a;
  for (unsigned char c : heading) {
    if (c >= 0x80 || std::isalnum(c) || c == '-' || c == '_')
      a += static_cast<char>(c >= 0x80 ? c : std::tolower(c));
    else if (c == ' ')
      a += '-';
  }
  return a;
}

struct Markdown {
  std::set<std::string> anchors;
  std::vector<std::string> links;       // targets of [text](target)
  std::vector<std::string> code_spans;  // `...` outside fenced blocks
};

Markdown parse(const std::string& text) {
  Markdown md;
  std::istringstream lines(text);
  std::string line;
  bool fenced = false;
  static const std::regex link(R"(\]\(([^)\s]+)\))"), span("`([^`]+)`");
  while (std::getline(lines, line)) {
    if (line.rfind("```", 0) == 0) {
      fenced = !fenced;
      continue;
    }
    if (fenced) continue;
    if (line.rfind("#", 0) == 0) md.anchors.insert(anchor_of(line.substr(line.find(' ') + 1)));
    for (std::sregex_iterator it(line.begin(), line.end(), link), end; it != end; ++it)
      md.links.push_back((*it)[1]);
    for (std::sregex_iterator it(line.begin(), line.end(), span), end; it != end; ++it)
      md.code_spans.push_back((*it)[1]);
  }
  return md;
}

// A path written from the repository's root ("core/solver/newton.h", "app/render/",
// "core/simulation.*"): true when something matches it.
bool repo_path_exists(const std::string& written) {
  fs::path dir = kRoot;
  std::istringstream parts(written);
  std::string part;
  std::vector<std::string> components;
  while (std::getline(parts, part, '/'))
    if (!part.empty()) components.push_back(part);
  for (std::size_t k = 0; k < components.size(); ++k) {
    const std::string& c = components[k];
    if (c.find('*') == std::string::npos) {
      dir /= c;
      continue;
    }
    // Only a last component may hold a '*' (e.g. "simulation.*", "stress-*.toml").
    if (k + 1 != components.size()) return false;
    std::string pattern;
    for (char ch : c) pattern += ch == '*' ? ".*" : ch == '.' ? "\\." : std::string(1, ch);
    const std::regex re(pattern);
    if (!fs::is_directory(dir)) return false;
    for (const auto& e : fs::directory_iterator(dir))
      if (std::regex_match(e.path().filename().string(), re)) return true;
    return false;
  }
  return fs::exists(dir);
}

}  // namespace

TEST(Docs, ReadmeIsAtMost8000Characters) {
  const std::string readme = read_text(kRoot / "README.md");
  ASSERT_FALSE(readme.empty());
  EXPECT_LE(readme.size(), 8000u) << "README.md is " << readme.size()
                                  << " bytes; move detail to docs/";
}

TEST(Docs, ReadmeShowsExamplesEmbedCpp) {
  const std::string readme = read_text(kRoot / "README.md");
  const std::string open = "```cpp\n", close = "```\n";
  const std::size_t begin = readme.find(open);
  ASSERT_NE(begin, std::string::npos) << "README.md has no ```cpp block";
  const std::size_t body = begin + open.size();
  const std::size_t end = readme.find(close, body);
  ASSERT_NE(end, std::string::npos);
  EXPECT_EQ(readme.substr(body, end - body), read_text(kRoot / "examples/embed.cpp"))
      << "README.md's C++ block must be examples/embed.cpp exactly";
  EXPECT_EQ(readme.find(open, end), std::string::npos) << "README.md has a second ```cpp block";
}

TEST(Docs, LinksAnchorsAndPathsExist) {
  static const std::regex repo_path(
      R"((core|app|tests|shaders|assets|docs|scripts|examples|\.ci)(/[A-Za-z0-9_.*+-]+)*/?)");
  int checked = 0;
  for (const fs::path& file : markdown_files()) {
    const Markdown md = parse(read_text(file));
    const std::string name = fs::relative(file, kRoot).string();
    for (const std::string& target : md.links) {
      if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0) continue;
      const std::size_t hash = target.find('#');
      const std::string path = target.substr(0, hash);
      const std::string anchor = hash == std::string::npos ? "" : target.substr(hash + 1);
      const fs::path linked = path.empty() ? file : file.parent_path() / path;
      ++checked;
      EXPECT_TRUE(fs::exists(linked)) << name << ": link to missing " << target;
      if (!anchor.empty() && linked.extension() == ".md" && fs::exists(linked)) {
        EXPECT_TRUE(parse(read_text(linked)).anchors.count(anchor))
            << name << ": link to missing heading " << target;
      }
    }
    for (const std::string& span : md.code_spans) {
      if (!std::regex_match(span, repo_path)) continue;
      ++checked;
      EXPECT_TRUE(repo_path_exists(span)) << name << ": `" << span << "` does not exist";
    }
  }
  EXPECT_GT(checked, 20) << "suspiciously few links and paths found";
}
