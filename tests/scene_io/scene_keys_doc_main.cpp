// invfree_scene_keys_doc: prints the generated block of docs/scene-keys.md, or with a path
// rewrites that block in the file (the text around it is kept):
//   build/release/tests/invfree_scene_keys_doc docs/scene-keys.md
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/scene_io/scene_keys_doc.h"

int main(int argc, char** argv) {
  const std::string block = invfree::test::scene_keys_markdown();
  if (argc < 2) {
    std::fputs(block.c_str(), stdout);
    return 0;
  }
  std::ifstream in(argv[1], std::ios::binary);
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string old = invfree::test::generated_block(doc);
  if (old.empty()) {
    std::fprintf(stderr, "invfree_scene_keys_doc: %s has no generated block\n", argv[1]);
    return 1;
  }
  std::string out = doc;
  out.replace(doc.find(old), old.size(), block);
  std::ofstream(argv[1], std::ios::binary) << out;
  return 0;
}
