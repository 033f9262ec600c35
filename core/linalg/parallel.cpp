#include "linalg/parallel.h"

#include <pthread.h>
#include <sys/resource.h>

#include <memory>
#include <mutex>
#include <new>
#include <system_error>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace invfree {

namespace {

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// About 10-30 microseconds of spinning before a worker (or the caller) sleeps.
constexpr int kSpinIterations = 2000;

int threads_per_core() {
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

std::mutex g_pool_mutex;
std::unique_ptr<ThreadPool> g_pool;
int g_thread_count = 0;  // set_thread_count's setting; 0: one per core

// Under an address-space limit (ulimit -v) the workers' stacks may take a quarter of it
// at most, so that a pool of many threads leaves room for the rest of the program (the
// offscreen renderer needs hundreds of MB).
int threads_within_address_space(int threads) {
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return threads;
  size_t stack = 8u << 20;
  pthread_attr_t attr;
  if (::pthread_attr_init(&attr) == 0) {
    ::pthread_attr_getstacksize(&attr, &stack);
    ::pthread_attr_destroy(&attr);
  }
  const rlim_t workers = limit.rlim_cur / 4 / std::max<size_t>(stack, 1);
  return static_cast<int>(std::min<rlim_t>(static_cast<rlim_t>(threads), workers + 1));
}

}  // namespace

// A thread that cannot be made (a process limit: ulimit -u, or an address-space limit
// too small for its stack) ends the pool's growth: it runs with the workers it has, the
// caller's thread at least. The results do not change (tasks never depend on the thread
// count: see parallel.h); only the speed does.
ThreadPool::ThreadPool(int threads) {
  threads = threads_within_address_space(threads);
  for (int i = 1; i < threads; ++i) {
    try {
      workers_.emplace_back([this] { worker_loop(); });
    } catch (const std::system_error&) {  // pthread_create failed (EAGAIN)
      break;
    } catch (const std::bad_alloc&) {  // the thread's state could not be allocated
      break;
    }
  }
}

ThreadPool::~ThreadPool() {
  stop_.store(true, std::memory_order_release);
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

void ThreadPool::work() {
  std::uint64_t s = state_.load(std::memory_order_acquire);
  while (true) {
    const std::uint32_t tasks = static_cast<std::uint32_t>(s >> 16) & 0xffff;
    const std::uint32_t next = static_cast<std::uint32_t>(s) & 0xffff;
    if (next >= tasks) return;
    if (!state_.compare_exchange_weak(s, s + 1, std::memory_order_acq_rel,
                                      std::memory_order_acquire))
      continue;
    // The run cannot end while this claimed task is pending, so call_/ctx_ are its own.
    call_(ctx_, static_cast<int>(next));
    if (done_.fetch_add(1, std::memory_order_acq_rel) + 1 == static_cast<int>(tasks))
      done_.notify_one();
    s = state_.load(std::memory_order_acquire);
  }
}

void ThreadPool::worker_loop() {
  std::uint32_t seen = 0;
  while (true) {
    for (int i = 0; i < kSpinIterations && wake_.load(std::memory_order_acquire) == seen; ++i)
      cpu_relax();
    wake_.wait(seen, std::memory_order_acquire);
    seen = wake_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_acquire)) return;
    work();
  }
}

bool ThreadPool::try_run(int tasks, TaskFn call, void* ctx) {
  if (busy_.exchange(true, std::memory_order_acquire)) return false;
  run_impl(tasks, call, ctx);
  busy_.store(false, std::memory_order_release);
  return true;
}

void ThreadPool::run_impl(int tasks, TaskFn call, void* ctx) {
  call_ = call;
  ctx_ = ctx;
  done_.store(0, std::memory_order_relaxed);
  const std::uint64_t run = (state_.load(std::memory_order_relaxed) >> 32) + 1;
  state_.store((run << 32) | (static_cast<std::uint64_t>(tasks) << 16), std::memory_order_release);
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_all();
  work();
  // Wait for the tasks other threads claimed (never for a worker that did not start).
  for (int i = 0; i < kSpinIterations; ++i) {
    if (done_.load(std::memory_order_acquire) == tasks) return;
    cpu_relax();
  }
  for (int d = done_.load(std::memory_order_acquire); d != tasks;
       d = done_.load(std::memory_order_acquire))
    done_.wait(d, std::memory_order_acquire);
}

ThreadPool& thread_pool() {
  std::lock_guard<std::mutex> lock(g_pool_mutex);
  if (!g_pool)
    g_pool = std::make_unique<ThreadPool>(g_thread_count > 0 ? g_thread_count : threads_per_core());
  return *g_pool;
}

int thread_count() {
  return thread_pool().size();
}

void set_thread_count(int n) {
  std::lock_guard<std::mutex> lock(g_pool_mutex);
  g_thread_count = std::max(n, 0);
  if (g_pool) g_pool = std::make_unique<ThreadPool>(n > 0 ? n : threads_per_core());
}

}  // namespace invfree
