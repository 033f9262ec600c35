#include "linalg/linear_solver.h"

#ifndef INVFREE_NO_CHOLMOD  // defined by the web build (app/web/CMakeLists.txt)
#include <cholmod.h>
#endif
#include <dlfcn.h>

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <vector>

#include "linalg/parallel.h"
#include "linalg/sparse_ldlt.h"
#include "linalg/submatrix_ldlt.h"

namespace invfree {

using SpMat = Eigen::SparseMatrix<double>;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

#ifndef INVFREE_NO_CHOLMOD
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

// A CHOLMOD header over H's own arrays (no copy): CHOLMOD reads its lower triangle.
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
#endif  // INVFREE_NO_CHOLMOD

// ---- LDL^T (core/linalg/sparse_ldlt.h) on a fill-reducing ordering -----------------------
struct LdltBackend {
  SparseLdlt ldlt;
  double factor_flops = 0.0, solve_flops = 0.0;

  void analyze(const SpMat& a) {
    analyze_like_the_solver(a, ldlt);
    factor_flops = ldlt.factor_flops();
    solve_flops = ldlt.solve_flops();
  }

  // `nested_dissection`: METIS's ordering (through CHOLMOD's analysis) instead of AMD:
  // less fill on larger meshes (256k against 279k entries of L at n_seg 64, 6.4M against
  // 8.1M at n_seg 256) and a balanced tree for the threads.
  static std::vector<int> ordering(const SpMat& a, bool nested_dissection) {
    const int n = static_cast<int>(a.rows());
    std::vector<int> new_to_old(n);
    if (!(nested_dissection && metis_order(a, new_to_old))) {
      Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
      Eigen::AMDOrdering<int> amd;
      amd(a, perm);
      for (int k = 0; k < n; ++k) new_to_old[k] = perm.indices()[k];
    }
    return new_to_old;
  }

#ifdef INVFREE_NO_CHOLMOD
  static bool metis_order(const SpMat&, std::vector<int>&) {
    return false;
  }
#else
  static bool metis_order(const SpMat& a, std::vector<int>& new_to_old) {
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
#endif

  bool factorize(const SpMat& a, bool positive_definite) {
    return ldlt.factorize(a, positive_definite);
  }
  // The float copy, when kept (keep_float_copy), only ever serves PCG.
  void solve(const VecX& b, VecX& x) {
    ldlt.solve_float(b, x);
  }
};

#ifndef INVFREE_NO_CHOLMOD
// ---- BLAS threads ------------------------------------------------------------------------
// CHOLMOD's BLAS calls run on one thread. OpenBLAS splits its level-3 calls and its
// parallel dense Cholesky by the number of BLAS threads, so with more than one the
// rounding, and the trajectory, would depend on the thread count (INVFREE_THREADS); on one
// thread the cholmod backend is bit-identical for any INVFREE_THREADS, like the others.
// One thread also suits the triangular solves PCG repeats, where waking BLAS threads for
// a small matrix-vector product is slower than doing it. Looked up at run time: with
// another BLAS this is a no-op and that library's own threading applies.
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

// ---- CHOLMOD supernodal LL^T -------------------------------------------------------------
struct CholmodBackend {
  MemoryPool pool;  // declared first: destroyed last, after CHOLMOD has returned its blocks
  cholmod_common common;
  bool started = false;
  cholmod_factor* factor = nullptr;
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
  double factor_flops = 0.0, solve_flops = 0.0;

  CholmodBackend() = default;
  CholmodBackend(const CholmodBackend&) = delete;
  CholmodBackend& operator=(const CholmodBackend&) = delete;
  ~CholmodBackend() {
    if (!started) return;
    PoolScope scope(pool);
    if (factor) cholmod_free_factor(&factor, &common);
    if (x) cholmod_free_dense(&x, &common);
    if (y) cholmod_free_dense(&y, &common);
    if (e) cholmod_free_dense(&e, &common);
    cholmod_finish(&common);
  }

  bool analyze(const SpMat& a) {
    install_cholmod_pool();
    PoolScope scope(pool);
    cholmod_start(&common);
    started = true;
    common.print = 0;
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_METIS;
    common.quick_return_if_not_posdef = 1;
    cholmod_sparse s = cholmod_view(a);
    factor = cholmod_analyze(&s, &common);
    if (!factor || common.status != CHOLMOD_OK) {
      // METIS unavailable or failed: CHOLMOD's default choice (AMD) instead.
      if (factor) cholmod_free_factor(&factor, &common);
      common.method[0].ordering = CHOLMOD_AMD;
      factor = cholmod_analyze(&s, &common);
      if (!factor) return false;
    }
    factor_flops = common.fl;
    solve_flops = 4.0 * common.lnz;
    // Warm the pool with one factorisation and one solve of the identity on this pattern,
    // so that the first real ones already find every workspace block (and the solve's
    // handles exist) and reach the steady allocate/free pattern.
    SpMat identity = a;
    for (int col = 0; col < identity.outerSize(); ++col)
      for (int k = identity.outerIndexPtr()[col]; k < identity.outerIndexPtr()[col + 1]; ++k)
        identity.valuePtr()[k] = identity.innerIndexPtr()[k] == col ? 1.0 : 0.0;
    VecX ones = VecX::Ones(a.rows()), out(a.rows());
    return factorize(identity) && solve(ones, out);
  }

  bool factorize(const SpMat& a) {
    PoolScope scope(pool);
    set_blas_threads(1);
    cholmod_sparse s = cholmod_view(a);
    cholmod_factorize(&s, factor, &common);
    return common.status == CHOLMOD_OK && factor->minor == factor->n;
  }

  bool solve(const VecX& b, VecX& out) {
    PoolScope scope(pool);
    set_blas_threads(1);
    cholmod_dense rhs{};
    rhs.nrow = rhs.d = rhs.nzmax = static_cast<std::size_t>(b.size());
    rhs.ncol = 1;
    rhs.x = const_cast<double*>(b.data());
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, factor, &rhs, nullptr, &x, nullptr, &y, &e, &common))
      return false;
    std::memcpy(out.data(), x->x, sizeof(double) * b.size());
    return true;
  }
};
#else
// Built without CHOLMOD (the web build, docs/web.md: SuiteSparse is not compiled to
// WebAssembly): the LDL^T backend serves every request, and orderings are AMD's.
struct CholmodBackend {
  double factor_flops = 0.0, solve_flops = 0.0;
  bool analyze(const SpMat&) { return false; }
  bool factorize(const SpMat&) { return false; }
  bool solve(const VecX&, VecX&) { return false; }
};
#endif  // INVFREE_NO_CHOLMOD

// y = H v (H in full symmetric storage, so column i is row i) and v.y, in fixed blocks.
double multiply(const SpMat& h, const VecX& v, VecX& y) {
  const int n = static_cast<int>(h.rows());
  const int* outer = h.outerIndexPtr();
  const int* inner = h.innerIndexPtr();
  const double* values = h.valuePtr();
  const BlockSplit blocks = split_blocks(n, 8192, 256);
  double partial[256];
  thread_pool().run(blocks.blocks, [&](int b) {
    double dot = 0.0;
    for (int i = blocks.begin(b), end = blocks.end(b, n); i < end; ++i) {
      double s = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) s += values[k] * v[inner[k]];
      y[i] = s;
      dot += s * v[i];
    }
    partial[b] = dot;
  });
  double dot = 0.0;
  for (int b = 0; b < blocks.blocks; ++b) dot += partial[b];
  return dot;
}

}  // namespace

void analyze_like_the_solver(const SpMat& pattern, SparseLdlt& ldlt) {
  ldlt.analyze(pattern,
               LdltBackend::ordering(pattern, pattern.rows() >= kNestedDissectionMinUnknowns),
               pattern.rows() >= kParallelLdltMinUnknowns ? kLdltBins : 1);
}

struct LinearSolver::Impl {
  bool pcg = false;
  bool positive_definite = true;
  bool cholmod = false;
  LdltBackend ldlt;
  CholmodBackend chol;
  // A factorisation stays valid across solves in PCG mode until it stops paying.
  bool have_factor = false;
  bool refresh = false;
  double factor_cost = 0.0;  // flops of one numeric factorisation
  double iter_cost = 0.0;    // flops of one PCG iteration (a solve, a product, vector work)
  VecX r, z, p, hp, t;
  // Diagonal correction of the reused factor (see prepare_correction).
  std::vector<int> diag_pos;     // position of H(i, i) in the value array
  VecX factored_diag;            // diag(H) when the factor was computed
  std::vector<int> changed;      // unknowns whose diagonal moved by more than 30% since
  std::vector<char> is_changed;  // 1 on `changed`, 2 on the rest of `block_set`
  std::vector<int> block_set;    // D: `changed` and its neighbours
  SubmatrixLdlt block;           // H_DD = L D L^T, when use_block
  bool use_block = false;
  VecX block_x;   // S r on `block_set` (or on `changed`, the fallback)
  VecX smoother;  // omega_i / H(i, i) on `changed` (the fallback)

  bool factorize(const SpMat& h, LinearSolveStats& stats) {
    const auto t0 = Clock::now();
    const bool ok = cholmod ? chol.factorize(h) : ldlt.factorize(h, positive_definite);
    stats.factor_ms += ms_since(t0);
    ++stats.factorizations;
    have_factor = ok;
    refresh = false;
    const double* v = h.valuePtr();
    for (std::size_t i = 0; i < diag_pos.size(); ++i) factored_diag[i] = v[diag_pos[i]];
    return ok;
  }

  bool apply_factor(const VecX& b, VecX& x) {
    if (cholmod) return chol.solve(b, x);
    ldlt.solve(b, x);
    return true;
  }

  // The reused factor B = A_old^-1 goes stale mostly through a few diagonal entries: the
  // contact barriers' and friction's stiffness on the nodes near a plane change by large
  // factors from one iteration to the next (friction's whenever a node starts or stops
  // sliding), the elasticity only slowly. Those unknowns C (diagonal moved by more than
  // kChangedDiagonal) and their neighbours in H's graph, the set D, get an exact block
  // solve S = H_DD^-1 (core/linalg/submatrix_ldlt.h) around B, the symmetric
  // multiplicative (Schwarz) combination
  //   z = S r;  z += B (r - H z);  z += S (r - H z)
  // i.e. M^-1 = (I - S H) B (I - H S) + S (2 S^-1 - H) S, symmetric positive definite
  // because 2 S^-1 - H_DD = H_DD is. D holds C's neighbours because where B treated a node
  // as held by friction that now slides (or the reverse), the block must carry the change
  // to the neighbours the node pulls on, which a diagonal smoother on C alone cannot.
  // `compress`, CG iterations per step at n_seg 32 / 64 / 128 / 256: 5.05 / 7.46 / 10.10 /
  // 19.19 (`build/release/app/invfree bench --sizes 32,64,128,256`).
  // A set D larger than the block's buffers (n / 8 unknowns, 32 envelope entries per
  // unknown) means the factor is too stale to be worth correcting: that solve falls back to
  // a Jacobi smoother S = W D_C^-1 on C and the next one refactorises. Its weights
  // w_i = min(1, 1.9 / (1 + R_i)), R_i the Gershgorin radius of row i of
  // D^-1/2 H_CC D^-1/2, make 2 S^-1 - H_CC diagonally dominant, so again positive definite.
  // The threshold: during compression the elasticity moves a fifth of the diagonal by
  // 10-30% within a few steps, which the factor absorbs; at 30% C is the contact rows
  // (about a hundred unknowns at n_seg 256), at 10% it would be tens of thousands.
  static constexpr double kChangedDiagonal = 0.3;
  void prepare_correction(const SpMat& h) {
    const int n = static_cast<int>(diag_pos.size());
    const double* v = h.valuePtr();
    const int* outer = h.outerIndexPtr();
    const int* inner = h.innerIndexPtr();
    for (int i : block_set) is_changed[i] = 0;
    block_set.clear();
    changed.clear();
    use_block = false;
    for (int i = 0; i < n; ++i) {
      const double d = v[diag_pos[i]];
      if (std::abs(d - factored_diag[i]) > kChangedDiagonal * factored_diag[i]) {
        changed.push_back(i);
        is_changed[i] = 1;
      }
    }
    if (changed.empty()) return;
    // D: C and its neighbours (is_changed 2), up to the block's capacity.
    block_set = changed;
    const std::size_t capacity = static_cast<std::size_t>(block.max_size());
    for (std::size_t a = 0; a < changed.size() && block_set.size() <= capacity; ++a) {
      const int i = changed[a];
      for (int k = outer[i]; k < outer[i + 1]; ++k)
        if (!is_changed[inner[k]]) {
          is_changed[inner[k]] = 2;
          block_set.push_back(inner[k]);
        }
    }
    use_block = block_set.size() <= capacity && block.factorize(h, block_set);
    if (use_block) return;
    refresh = true;  // too stale for the block: Jacobi on C now, a new factor next solve
    for (int i : changed) {
      const double di = v[diag_pos[i]];
      double radius = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) {
        const int j = inner[k];
        if (j != i && is_changed[j] == 1) radius += std::abs(v[k]) / std::sqrt(di * v[diag_pos[j]]);
      }
      smoother[i] = std::min(1.0, 1.9 / (1.0 + radius)) / di;
    }
  }

  // out = M^-1 in (see prepare_correction); `out` must not alias `in`.
  bool apply_preconditioner(const SpMat& h, const VecX& in, VecX& out) {
    if (changed.empty()) return apply_factor(in, out);
    const double* v = h.valuePtr();
    const int* outer = h.outerIndexPtr();
    const int* inner = h.innerIndexPtr();
    // S on the block (an exact solve on D) or, as the fallback, the Jacobi smoother on C;
    // block_x[a] = (S r)[set[a]].
    const std::vector<int>& set = use_block ? block_set : changed;
    const int m = static_cast<int>(set.size());
    auto smooth = [&](const VecX& r) {
      if (use_block) {
        block.solve(r, block_x);
      } else {
        for (int a = 0; a < m; ++a) block_x[a] = smoother[set[a]] * r[set[a]];
      }
    };
    smooth(in);  // z1 = S in; t = in - H z1 (z1 is nonzero on the set only: its columns)
    t = in;
    for (int a = 0; a < m; ++a) {
      const int i = set[a];
      for (int k = outer[i]; k < outer[i + 1]; ++k) t[inner[k]] -= v[k] * block_x[a];
    }
    if (!apply_factor(t, out)) return false;
    for (int a = 0; a < m; ++a) out[set[a]] += block_x[a];
    // out += S (in - H out), rows of the set only (H is symmetric: row i = column i).
    for (int a = 0; a < m; ++a) {
      const int i = set[a];
      double hz = 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) hz += v[k] * out[inner[k]];
      t[i] = in[i] - hz;
    }
    smooth(t);
    for (int a = 0; a < m; ++a) out[set[a]] += block_x[a];
    return true;
  }

  // PCG from x = 0, preconditioned by the stored factor; see linear_solver.h for the
  // stopping rules. Returns 1 converged, 0 not within max_iterations, -1 breakdown.
  int run_pcg(const SpMat& h, const VecX& b, VecX& x, const SolveRequest& req, int max_iterations,
              LinearSolveStats& stats) {
    x.setZero();
    const double b_norm = b.norm();
    if (b_norm == 0.0) return 1;
    r = b;
    prepare_correction(h);
    if (!apply_preconditioner(h, r, z)) return -1;
    p = z;
    double rz = r.dot(z);
    const bool decide = req.threshold > 0.0 && req.lambda_min > 0.0;
    double decrease = 0.0;
    for (int k = 1; k <= max_iterations; ++k) {
      const double php = multiply(h, p, hp);
      if (!(php > 0.0) || !std::isfinite(php)) return -1;
      const double alpha = rz / php;
      decrease += alpha * rz;  // twice the decrease of the quadratic model so far
      x += alpha * p;
      r -= alpha * hp;
      ++stats.pcg_iterations;
      const double r_norm = r.norm();
      if (r_norm <= 1e-13 * b_norm) return 1;  // as accurate as a direct solve
      if (decide && x.lpNorm<Eigen::Infinity>() < req.threshold) {
        // Newton would stop: only when the exact solution certainly would too.
        auto certain = [&](double residual_norm) {
          return x.lpNorm<Eigen::Infinity>() + residual_norm / req.lambda_min < req.threshold;
        };
        if (certain(r_norm)) {
          // Confirm with the true residual b - H x (CG's recurrence drifts by rounding).
          multiply(h, x, hp);
          z = b - hp;
          if (certain(z.norm())) return 1;
        }
      } else if (alpha * rz <= req.forcing * decrease) {
        return 1;  // Newton goes on with this direction (an inexact Newton step)
      }
      if (!apply_preconditioner(h, r, z)) return -1;
      const double rz_next = r.dot(z);
      if (!(rz_next > 0.0)) return -1;
      const double beta = rz_next / rz;
      rz = rz_next;
      p = z + beta * p;
    }
    return 0;
  }
};

LinearSolver::LinearSolver() = default;
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::setup(const SpMat& pattern, LinearSolverKind kind, bool positive_definite) {
  requested_ = kind;
  positive_definite_ = positive_definite;
  impl_ = std::make_unique<Impl>();
  Impl& s = *impl_;
  s.positive_definite = positive_definite;
  const int n = static_cast<int>(pattern.rows());
  switch (kind) {
    case LinearSolverKind::Ldlt:
      s.pcg = false;
      s.cholmod = false;
      break;
    case LinearSolverKind::Cholmod:
      s.pcg = false;
      s.cholmod = true;
      break;
    case LinearSolverKind::Pcg:
      s.pcg = true;
      s.cholmod = false;
      break;
    case LinearSolverKind::Auto:
    default:
      s.pcg = positive_definite;
      s.cholmod = false;
      break;
  }
  if (s.cholmod && !s.chol.analyze(pattern)) s.cholmod = false;
  if (!s.cholmod) s.ldlt.analyze(pattern);
  if (!s.cholmod && s.pcg && s.ldlt.ldlt.factor_nonzeros() >= kFloatPreconditionerMinEntries)
    s.ldlt.ldlt.keep_float_copy(true);
  const double factor_flops = s.cholmod ? s.chol.factor_flops : s.ldlt.factor_flops;
  const double solve_flops = s.cholmod ? s.chol.solve_flops : s.ldlt.solve_flops;
  s.factor_cost = factor_flops;
  s.iter_cost = solve_flops + 2.0 * pattern.nonZeros() + 12.0 * n;
  s.r.resize(n);
  s.z.resize(n);
  s.p.resize(n);
  s.hp.resize(n);
  s.t.resize(n);
  s.diag_pos.resize(n);
  for (int i = 0; i < n; ++i) {
    const int* begin = pattern.innerIndexPtr() + pattern.outerIndexPtr()[i];
    const int* end = pattern.innerIndexPtr() + pattern.outerIndexPtr()[i + 1];
    s.diag_pos[i] = static_cast<int>(std::lower_bound(begin, end, i) - pattern.innerIndexPtr());
  }
  s.factored_diag.resize(n);
  s.changed.reserve(n);
  s.is_changed.assign(n, 0);
  if (s.pcg) {
    s.block_set.reserve(n);
    const int block_size = std::max(64, n / 8);
    s.block.reserve(n, block_size, 32L * block_size);
    s.block_x.resize(n);  // S r on the block, or on C for the fallback
  }
  s.smoother.resize(n);
}

const char* LinearSolver::backend_name() const {
  if (!impl_) return "none";
  if (impl_->pcg) return impl_->cholmod ? "pcg+cholmod" : "pcg+ldlt";
  return impl_->cholmod ? "cholmod" : "ldlt";
}

void LinearSolver::invalidate() {
  if (impl_) impl_->have_factor = false;
}

bool LinearSolver::solve(const SpMat& h, const VecX& b, VecX& x, const SolveRequest& request,
                         LinearSolveStats& stats) {
  Impl& s = *impl_;
  const auto start = Clock::now();
  const double factor_ms_before = stats.factor_ms;
  ++stats.solves;
  if (x.size() != b.size()) x.resize(b.size());
  bool ok = true;
  if (!s.pcg) {
    ok = s.factorize(h, stats) && s.apply_factor(b, x);
  } else {
    // Do not spend more on PCG iterations than a fresh factorisation costs.
    const int max_iterations =
        std::max(2, static_cast<int>(std::ceil(s.factor_cost / s.iter_cost)));
    int outcome = 0;
    if (s.have_factor && !s.refresh) {
      const int before = stats.pcg_iterations;
      outcome = s.run_pcg(h, b, x, request, max_iterations, stats);
      // Renew the factor for the next solve once the iterations cost half a factorisation.
      if (outcome == 1 && (stats.pcg_iterations - before) * s.iter_cost > 0.5 * s.factor_cost)
        s.refresh = true;
    }
    if (outcome != 1) {
      ok = s.factorize(h, stats) && s.run_pcg(h, b, x, request, max_iterations, stats) == 1;
    }
  }
  ok = ok && x.allFinite();
  stats.solve_ms += ms_since(start) - (stats.factor_ms - factor_ms_before);
  return ok;
}

}  // namespace invfree
