// How the sums over triangles and nodes are cut into blocks for the thread pool. A block's
// size depends on the mesh alone, so the partial sums, and the results, are the same for any
// thread count. A block is large enough (tens of microseconds) to be worth handing to
// another thread: waking one costs microseconds, more on a loaded machine. Small meshes run
// inline.
#pragma once

#include "linalg/parallel.h"

namespace invfree {

constexpr int kMaxBlocks = 256;           // per-block partial sums live on the stack
constexpr int kTriangleBlock = 4096;      // energy: triangles per block (at least)
constexpr int kNodeBlock = 8192;          // nodes per block (at least)
constexpr int kParallelTriangles = 2048;  // assembly: below this, colours run inline

// Runs fn(b) for every block, on the pool when there are at least two.
template <class Fn>
void run_blocks(int blocks, Fn&& fn) {
  if (blocks >= 2) {
    thread_pool().run(blocks, fn);
  } else {
    for (int b = 0; b < blocks; ++b) fn(b);
  }
}

}  // namespace invfree
