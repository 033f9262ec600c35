// CHOLMOD's supernodal LL^T (cholmod_backend.h): its memory pool, its BLAS threads, the
// backend itself, and the METIS ordering the LDL^T backend borrows from its analysis.
#include "linalg/cholmod_backend.h"

#ifndef INVFREE_NO_CHOLMOD  // defined by the web build (app/web/CMakeLists.txt)
#include <cholmod.h>
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#endif

namespace invfree {

using SpMat = Eigen::SparseMatrix<double>;

#ifndef INVFREE_NO_CHOLMOD
namespace {

// ---- CHOLMOD's memory: a size-keyed recycling pool per factorisation -------------------
// CHOLMOD allocates its numeric workspace on every factorisation and frees it on return.
// The sizes depend on the symbolic analysis only, so after the first factorisation every
// request is served from blocks the previous one freed and CHOLMOD itself makes no call to
// the system allocator. Each backend owns a pool; its CHOLMOD calls run with that pool as
// the thread's current one (PoolScope). A block's 16-byte header records its size and
// pool, so it always returns to the pool it came from (or to the system when it came from
// there). The hooks are installed once, before the first CHOLMOD call; nothing else in
// the program uses CHOLMOD.
struct MemoryPool {
  struct Block {
    std::size_t size;
    char* raw;
  };
  static constexpr std::size_t kCapacity = 1024;
  std::mutex mutex;
  std::vector<Block> cached;  // capacity reserved up front: caching never allocates
  MemoryPool() { cached.reserve(kCapacity); }
  MemoryPool(const MemoryPool&) = delete;
  MemoryPool& operator=(const MemoryPool&) = delete;
  ~MemoryPool() {
    for (const Block& b : cached) std::free(b.raw);
  }
};

constexpr std::size_t kHeader = 16;
thread_local MemoryPool* t_pool = nullptr;

struct PoolScope {
  MemoryPool* previous;
  explicit PoolScope(MemoryPool& pool) : previous(t_pool) { t_pool = &pool; }
  ~PoolScope() { t_pool = previous; }
  PoolScope(const PoolScope&) = delete;
  PoolScope& operator=(const PoolScope&) = delete;
};

void* pool_malloc(std::size_t size) {
  if (size == 0) size = 1;
  MemoryPool* pool = t_pool;
  if (pool) {
    std::lock_guard<std::mutex> lock(pool->mutex);
    for (std::size_t k = pool->cached.size(); k-- > 0;)
      if (pool->cached[k].size == size) {
        char* raw = pool->cached[k].raw;
        pool->cached[k] = pool->cached.back();
        pool->cached.pop_back();
        return raw + kHeader;
      }
  }
  char* raw = static_cast<char*>(std::malloc(size + kHeader));
  if (!raw) return nullptr;
  std::memcpy(raw, &size, sizeof size);
  std::memcpy(raw + sizeof size, &pool, sizeof pool);
  return raw + kHeader;
}

void pool_free(void* p) {
  if (!p) return;
  char* raw = static_cast<char*>(p) - kHeader;
  std::size_t size;
  MemoryPool* pool;
  std::memcpy(&size, raw, sizeof size);
  std::memcpy(&pool, raw + sizeof size, sizeof pool);
  if (!pool) {
    std::free(raw);
    return;
  }
  std::lock_guard<std::mutex> lock(pool->mutex);
  if (pool->cached.size() == MemoryPool::kCapacity) {  // full: drop the oldest
    std::free(pool->cached.front().raw);
    pool->cached.erase(pool->cached.begin());
  }
  pool->cached.push_back({size, raw});
}

void* pool_calloc(std::size_t n, std::size_t each) {
  if (each != 0 && n > static_cast<std::size_t>(-1) / each) return nullptr;
  void* p = pool_malloc(n * each);
  if (p) std::memset(p, 0, n * each);
  return p;
}

void* pool_realloc(void* p, std::size_t size) {
  if (!p) return pool_malloc(size);
  std::size_t old;
  std::memcpy(&old, static_cast<char*>(p) - kHeader, sizeof old);
  if (size <= old) return p;
  void* q = pool_malloc(size);
  if (!q) return nullptr;
  std::memcpy(q, p, old);
  pool_free(p);
  return q;
}

void install_cholmod_pool() {
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = pool_malloc;
    SuiteSparse_config.calloc_func = pool_calloc;
    SuiteSparse_config.realloc_func = pool_realloc;
    SuiteSparse_config.free_func = pool_free;
  });
}

// ---- BLAS threads ------------------------------------------------------------------------
// CHOLMOD's BLAS calls run on one thread. OpenBLAS splits its level-3 calls and its
// parallel dense Cholesky by the number of BLAS threads, so with more than one the
// rounding, and the trajectory, would depend on the thread count (set_thread_count,
// parallel.h); on one thread the cholmod backend is bit-identical for any thread count,
// like the others. Looked up at run time: with another BLAS this is a no-op and that
// library's own threading applies.
using BlasThreadsFn = void (*)(int);
BlasThreadsFn blas_set_threads() {
  static const BlasThreadsFn fn =
      reinterpret_cast<BlasThreadsFn>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  return fn;
}
void set_blas_threads(int n) {
  static int current = -1;
  if (n == current) return;
  if (BlasThreadsFn fn = blas_set_threads()) fn(n);
  current = n;
}

// A CHOLMOD header over the matrix's own arrays (no copy): CHOLMOD reads its lower
// triangle.
cholmod_sparse cholmod_view(const SpMat& a) {
  cholmod_sparse s{};
  s.nrow = s.ncol = static_cast<std::size_t>(a.rows());
  s.nzmax = static_cast<std::size_t>(a.nonZeros());
  s.p = const_cast<int*>(a.outerIndexPtr());
  s.i = const_cast<int*>(a.innerIndexPtr());
  s.x = const_cast<double*>(a.valuePtr());
  s.stype = -1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

// The identity on `a`'s pattern.
SpMat identity_on(const SpMat& a) {
  SpMat identity = a;
  for (int col = 0; col < identity.outerSize(); ++col)
    for (int k = identity.outerIndexPtr()[col]; k < identity.outerIndexPtr()[col + 1]; ++k)
      identity.valuePtr()[k] = identity.innerIndexPtr()[k] == col ? 1.0 : 0.0;
  return identity;
}

}  // namespace

// ---- CHOLMOD supernodal LL^T -------------------------------------------------------------
struct CholmodBackend::State {
  MemoryPool pool;  // declared first: destroyed last, after CHOLMOD has returned its blocks
  cholmod_common common;
  bool started = false;
  cholmod_factor* factor = nullptr;
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;

  State() = default;
  State(const State&) = delete;
  State& operator=(const State&) = delete;
  ~State() {
    if (!started) return;
    PoolScope scope(pool);
    if (factor) cholmod_free_factor(&factor, &common);
    if (x) cholmod_free_dense(&x, &common);
    if (y) cholmod_free_dense(&y, &common);
    if (e) cholmod_free_dense(&e, &common);
    cholmod_finish(&common);
  }
};

CholmodBackend::CholmodBackend() = default;
CholmodBackend::~CholmodBackend() = default;

bool CholmodBackend::analyze(const SpMat& a) {
  install_cholmod_pool();
  state_ = std::make_unique<State>();
  State& s = *state_;
  {
    PoolScope scope(s.pool);
    cholmod_start(&s.common);
    s.started = true;
    s.common.print = 0;
    s.common.supernodal = CHOLMOD_SUPERNODAL;
    s.common.nmethods = 1;
    s.common.method[0].ordering = CHOLMOD_METIS;
    s.common.quick_return_if_not_posdef = 1;
    cholmod_sparse view = cholmod_view(a);
    s.factor = cholmod_analyze(&view, &s.common);
    if (!s.factor || s.common.status != CHOLMOD_OK) {
      // METIS unavailable or failed: CHOLMOD's default choice (AMD) instead.
      if (s.factor) cholmod_free_factor(&s.factor, &s.common);
      s.common.method[0].ordering = CHOLMOD_AMD;
      s.factor = cholmod_analyze(&view, &s.common);
      if (!s.factor) return false;
    }
  }
  // Warm the pool with one factorisation and one solve of the identity on this pattern,
  // so that the first real ones already find every workspace block (and the solve's
  // handles exist) and reach the steady allocate/free pattern.
  VecX ones = VecX::Ones(a.rows()), out(a.rows());
  return factorize(identity_on(a)) && solve(ones, out);
}

bool CholmodBackend::factorize(const SpMat& a) {
  State& s = *state_;
  PoolScope scope(s.pool);
  set_blas_threads(1);
  cholmod_sparse view = cholmod_view(a);
  cholmod_factorize(&view, s.factor, &s.common);
  return s.common.status == CHOLMOD_OK && s.factor->minor == s.factor->n;
}

bool CholmodBackend::solve(const VecX& b, VecX& out) {
  State& s = *state_;
  PoolScope scope(s.pool);
  set_blas_threads(1);
  cholmod_dense rhs{};
  rhs.nrow = rhs.d = rhs.nzmax = static_cast<std::size_t>(b.size());
  rhs.ncol = 1;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, s.factor, &rhs, nullptr, &s.x, nullptr, &s.y, &s.e, &s.common))
    return false;
  std::memcpy(out.data(), s.x->x, sizeof(double) * b.size());
  return true;
}

bool metis_ordering(const SpMat& a, std::vector<int>& new_to_old) {
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  c.postorder = 1;
  cholmod_sparse view = cholmod_view(a);
  cholmod_factor* f = cholmod_analyze(&view, &c);
  const bool ok = f && c.status == CHOLMOD_OK && c.selected == 0;  // METIS, not a fallback
  if (ok) {
    const int* perm = static_cast<const int*>(f->Perm);
    for (int k = 0; k < static_cast<int>(a.rows()); ++k) new_to_old[k] = perm[k];
  }
  if (f) cholmod_free_factor(&f, &c);
  cholmod_finish(&c);
  return ok;
}

#else  // INVFREE_NO_CHOLMOD: LinearSolver serves every request with its LDL^T.

struct CholmodBackend::State {};
CholmodBackend::CholmodBackend() = default;
CholmodBackend::~CholmodBackend() = default;
bool CholmodBackend::analyze(const SpMat&) {
  return false;
}
bool CholmodBackend::factorize(const SpMat&) {
  return false;
}
bool CholmodBackend::solve(const VecX&, VecX&) {
  return false;
}
bool metis_ordering(const SpMat&, std::vector<int>&) {
  return false;
}

#endif  // INVFREE_NO_CHOLMOD

}  // namespace invfree
