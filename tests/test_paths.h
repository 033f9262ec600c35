// Where the tests find the source tree, the invfree program and the render goldens. The
// paths are compiled into one small library (test_paths.cpp), so every other test file
// compiles to the same object in any checkout: a clone in another folder (CI's) gets them
// from the compile cache.
#pragma once

namespace invfree::test {

const char* source_dir();          // the repository's root
const char* exe_path();            // the invfree program under test
const char* golden_dir();          // tests/render/goldens
const char* golden_failure_dir();  // where a failing golden comparison writes its images

}  // namespace invfree::test
