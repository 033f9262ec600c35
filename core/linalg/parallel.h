// A small fork-join thread pool for the per-Newton-iteration loops (assembly, energy,
// sparse products). Inputs: a task count and a function of the task index. Output: every
// task run exactly once, on any of the pool's threads (the caller's thread works too);
// `run` returns when all are done. Results are deterministic as long as each task writes
// only its own outputs: callers split work into fixed-size tasks that do not depend on
// the thread count, so the answer is bit-identical for 1, 2 or N threads.
//
// Workers spin briefly (a few microseconds: Newton's parallel phases come in quick
// succession) and then sleep on a futex, so an idle pool costs no CPU. One process-wide
// pool is shared by every simulation; a run that finds it busy with another thread's run
// (two simulations stepping at once: render --compare, Python threads) does its tasks on
// its own thread, which gives the same bits, instead of waiting or racing for it. Its size is a setting, `set_thread_count`, never
// read from the environment: the program decides (the command line reads INVFREE_THREADS,
// app/main.cpp; tests and benchmarks set their own).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <type_traits>
#include <vector>

namespace invfree {

class ThreadPool {
 public:
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls fn(task) for every task in [0, tasks) (at most 65535 per run, else they run
  // inline). Safe to call from several threads at once: one run has the workers, the
  // others run inline. Not re-entrant: tasks must not call run.
  template <class Fn>
  void run(int tasks, Fn&& fn) {
    if (tasks <= 0) return;
    if (tasks > 1 && !workers_.empty() && tasks <= 0xffff) {
      using F = std::remove_reference_t<Fn>;
      if (try_run(
              tasks, [](void* ctx, int t) { (*static_cast<F*>(ctx))(t); },
              const_cast<void*>(static_cast<const void*>(&fn))))
        return;
    }
    for (int t = 0; t < tasks; ++t) fn(t);
  }

 private:
  using TaskFn = void (*)(void*, int);
  // The run on the workers, unless another thread's run has them (false: nothing ran).
  bool try_run(int tasks, TaskFn call, void* ctx);
  void run_impl(int tasks, TaskFn call, void* ctx);
  void worker_loop();
  // Claims and runs tasks of the current run until none is left.
  void work();

  // state_ packs the run's number (high 32 bits), its task count (next 16) and the next
  // unclaimed task (low 16): a task is claimed by a compare-and-swap that fails once the
  // run is over, so a worker that wakes late never touches a finished run and the caller
  // never waits for a worker that has not started: it waits only for claimed tasks.
  std::vector<std::thread> workers_;
  std::atomic<std::uint64_t> state_{0};
  std::atomic<std::uint32_t> wake_{0};  // futex word the idle workers sleep on
  std::atomic<int> done_{0};            // tasks finished in the current run
  TaskFn call_ = nullptr;
  void* ctx_ = nullptr;
  std::atomic<bool> stop_{false};
  std::atomic<bool> busy_{false};  // a run has the workers (try_run)
};

// Fixed split of n items into blocks of at least `min_block` and at most `max_blocks`
// blocks. It depends on n alone, never on the thread count, so per-block partial sums
// added in block order give the same bits on any number of threads.
struct BlockSplit {
  int blocks = 0;
  int size = 1;
  int begin(int b) const { return b * size; }
  int end(int b, int n) const { return b + 1 == blocks ? n : (b + 1) * size; }
};
inline BlockSplit split_blocks(int n, int min_block, int max_blocks) {
  if (n <= 0) return {0, 1};
  int size = std::max(min_block, (n + max_blocks - 1) / max_blocks);
  return {(n + size - 1) / size, size};
}

// The shared pool, created on first use with the thread count set last (the caller's
// thread included), or by default one thread per core.
ThreadPool& thread_pool();
int thread_count();
// Sets the shared pool's thread count: n threads, or with n <= 0 one per core (the
// default). A pool already created is resized at once. Not while a step runs.
void set_thread_count(int n);

}  // namespace invfree
