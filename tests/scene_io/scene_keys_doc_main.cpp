// invfree_scene_keys_doc: prints the generated block of docs/scene-keys.md, or with paths
// rewrites the generated blocks of the files (the text around them is kept): a file ending
// in .dict gets the fuzz dictionary's block, any other the scene-keys table.
//   build/release/tests/invfree_scene_keys_doc docs/scene-keys.md tests/fuzz/scene.dict
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/scene_io/scene_keys_doc.h"

namespace {

int rewrite(const std::string& path) {
  using namespace invfree::test;
  const bool dict = path.size() > 5 && path.compare(path.size() - 5, 5, ".dict") == 0;
  const std::string block = dict ? fuzz_dictionary_block() : scene_keys_markdown();
  std::ifstream in(path, std::ios::binary);
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string old = dict ? generated_block(doc, kFuzzDictBegin, kFuzzDictEnd)
                               : generated_block(doc);
  if (old.empty()) {
    std::fprintf(stderr, "invfree_scene_keys_doc: %s has no generated block\n", path.c_str());
    return 1;
  }
  std::string out = doc;
  out.replace(doc.find(old), old.size(), block);
  std::ofstream(path, std::ios::binary) << out;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(invfree::test::scene_keys_markdown().c_str(), stdout);
    return 0;
  }
  int status = 0;
  for (int i = 1; i < argc; ++i) status |= rewrite(argv[i]);
  return status;
}
