#include "tests/test_paths.h"

namespace invfree::test {

const char* source_dir() {
  return INVFREE_TEST_SOURCE_DIR;
}
const char* exe_path() {
  return INVFREE_TEST_EXE;
}
const char* golden_dir() {
  return INVFREE_TEST_SOURCE_DIR "/tests/render/goldens";
}
const char* golden_failure_dir() {
  return INVFREE_TEST_BINARY_DIR "/tests/render/golden_failures";
}

}  // namespace invfree::test
