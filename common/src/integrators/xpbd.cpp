// XPBD, extended position-based dynamics, with small steps (integrator.hpp; handout/integrators.md,
// "XPBD"). Written from the method's equations for the kit's spring–damper model:
//
// Each step h is cut into N = xpbd.substeps substeps of length s = h/N. A substep
//   1. kicks and drifts with the forces that are not springs: v += s a_ext(r, v), x = r + s v
//      (gravity, wind, push; pinned particles have none and do not move);
//   2. projects every spring's constraint C = |x_p − x_q| − ℓ0 with compliance α = 1/k, in
//      xpbd.iterations Gauss–Seidel passes over the springs, each moving p and q at once:
//        Δλ = (−C − α̃ λ − γ ∇C·(x − r)) / ((1 + γ)(w_p + w_q) + α̃),  α̃ = α/s², γ = α̃ β s,
//        x_p += w_p Δλ n,  x_q −= w_q Δλ n,  λ += Δλ,
//      n the unit vector from q to p, w = 1/m (0 when pinned), β = b the damper's coefficient,
//      λ summed over the passes of one substep. Multiplied through by k s², the same update reads
//        Δλ = (−k s² C − λ − b s n·(Δ_p − Δ_q)) / ((k s² + b s)(w_p + w_q) + 1),
//      Δ_i = x_i − r_i the move of particle i in this substep so far: finite for k = 0 (a damper
//      alone) and tending to −C/(w_p + w_q), a rigid rod, as k → ∞; its denominator is at least 1.
//      The kit's damper, F = −b (v_p − v_q), also acts across the spring, where the constraint's
//      gradient has no component: that part is a second, damping-only constraint along
//      t = (−n_y, n_x), the same update with k = 0:
//        Δμ = (−μ − b s t·(Δ_p − Δ_q)) / (b s (w_p + w_q) + 1),  x_p += w_p Δμ t,  x_q −= w_q Δμ t;
//   3. takes the velocity from the move: v = (x − r)/s, and r = x.
//
// Converged (λ and μ settled), λ n + μ t = s² (−k C n − b (x_p − r_p − x_q + r_q)/s): the spring
// and damper forces at the end of the substep, so the substep is backward Euler on the springs and
// dampers (not linearised) and symplectic Euler on the rest. Every projection moves p and q by
// opposite momenta (m_p w_p = m_q w_q = 1), so the springs never change the total momentum.
//
// The order of a pass: springs are coloured so that no two of a colour share a particle (greedy,
// in list order: each takes the first colour free at both ends; about 20 on a fabric), and a pass
// goes colour by colour. Within a colour the order does not change the result, so a colour's
// springs are sorted by kind (below) and the projections, independent, are computed four at a
// time: with AVX2, each end's position and substep start in one load and four springs turned into
// vectors by a transpose (project_four); elsewhere, a chunk gathered into arrays, projected by one
// loop the compiler vectorises and scattered back (project_chunk). Both are the same operations in
// the same order as one at a time, without fused multiply-adds: the same bits. On large scenes
// (colours of 131072 springs or more) a colour is also split over threads (parallel.hpp), with
// the same result. A projection's denominators depend only on s, k, b and the ends' masses: they
// are computed once for each kind of spring, not per projection.
#include "integrators/integrators.hpp"
#include "springlab/avx2.hpp"
#include "springlab/parallel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <string_view>
#include <vector>

#if SPRINGLAB_AVX2_PATHS
#include <immintrin.h>
#endif

namespace springlab::detail {
namespace {

// One spring as a pass reads it: its two ends (8 bytes). Its coefficients are its kind's, shared
// with every spring of the same k, b, ℓ0 and ends' masses (a fabric has a few kinds: three
// families, free or pinned ends); a pass goes over runs of springs of one kind.
struct Ends {
  int p = 0, q = 0;
};

// Springs [begin, end) of the pass order, all of kind `kind` and of one group (see prepare).
struct Run {
  long begin = 0, end = 0;
  int kind = 0;
};

struct Kind {
  double rest = 0.0;          // ℓ0, m
  double ks2 = 0.0;           // k s²
  double bs = 0.0;            // b s
  double along = 0.0;         // 1 / ((k s² + b s)(w_p + w_q) + 1)
  double across = 0.0;        // 1 / (b s (w_p + w_q) + 1)
  double wp = 0.0, wq = 0.0;  // the ends' 1/m (0 when pinned), 1/kg
};

constexpr double infinity = std::numeric_limits<double>::infinity();

// A chunk of one colour's constraints of one kind, gathered: the ends' separation d = x_p − x_q
// and relative move m = Δ_p − Δ_q; the kernel writes the updates Δλ (along), Δμ (across) and the
// correction c = Δλ n + Δμ t, applied as x_p += w_p c, x_q −= w_q c. Arrays of a chunk's length,
// so that the kernel's loop is plain and vectorises.
constexpr int chunk_size = 128;
// λ and μ of a single pass: always 0 (read in place of the kept ones, which are in pass order).
constexpr double zeros[chunk_size] = {};
struct Chunk {
  alignas(32) double dx[chunk_size], dy[chunk_size], mx[chunk_size], my[chunk_size];
  alignas(32) double along[chunk_size], across[chunk_size];  // Δλ, Δμ
  alignas(32) double cx[chunk_size], cy[chunk_size];
};

// The file's step 2 for `count` gathered constraints of kind c, as project_range below writes it
// for one. At zero length there is no direction, as (1.1) says: dividing by infinity gives n = 0,
// so no move (c = 0), and the caller keeps λ and μ as they were.
SPRINGLAB_AVX2_CLONES void project_chunk(int count, const Kind c, const double* __restrict dx,
                                         const double* __restrict dy, const double* __restrict mx,
                                         const double* __restrict my,
                                         const double* __restrict lambda,
                                         const double* __restrict mu, double* __restrict along_out,
                                         double* __restrict across_out, double* __restrict cx,
                                         double* __restrict cy) {
  for (int j = 0; j < count; ++j) {
    const double length = std::sqrt(dx[j] * dx[j] + dy[j] * dy[j]);
    const double inverse_length = 1.0 / (length > 0.0 ? length : infinity);
    const double nx = dx[j] * inverse_length, ny = dy[j] * inverse_length;
    const double along =
        (-c.ks2 * (length - c.rest) - lambda[j] - c.bs * (nx * mx[j] + ny * my[j])) * c.along;
    const double across = (-mu[j] - c.bs * (nx * my[j] - ny * mx[j])) * c.across;
    along_out[j] = along;
    across_out[j] = across;
    cx[j] = along * nx - across * ny;
    cy[j] = along * ny + across * nx;
  }
}

#if SPRINGLAB_AVX2_PATHS
// Four projections of one colour and one kind at once, with AVX2 (the file's step 2, the same
// operations in the same order as project_range, so the same bits): each end's x, y, and substep
// start x0, y0 are one 32-byte load; four constraints' separations and relative moves are turned
// into a vector each (a 4×4 transpose), projected together, and each end's move added back with
// one 16-byte load and store. The four share no particle, so their writes never meet. `lambda`
// and `mu`: the kept λ and μ of the four (accumulated), or null for a single pass.
__attribute__((target("avx2"))) void project_four(double* x, const Ends* c, const Kind& k,
                                                  double* lambda, double* mu) {
  __m256d u[4];
  for (int i = 0; i < 4; ++i) {
    const __m256d p = _mm256_loadu_pd(x + 4L * c[i].p), q = _mm256_loadu_pd(x + 4L * c[i].q);
    // (x_p − x0_p) − (x_q − x0_q) in the low half of m, x_p − x_q in the low half of d.
    const __m256d d = _mm256_sub_pd(p, q);
    const __m256d m = _mm256_sub_pd(_mm256_sub_pd(p, _mm256_permute2f128_pd(p, p, 0x01)),
                                    _mm256_sub_pd(q, _mm256_permute2f128_pd(q, q, 0x01)));
    u[i] = _mm256_permute2f128_pd(d, m, 0x20);  // dx, dy, mx, my
  }
  const __m256d t0 = _mm256_unpacklo_pd(u[0], u[1]), t1 = _mm256_unpackhi_pd(u[0], u[1]);
  const __m256d t2 = _mm256_unpacklo_pd(u[2], u[3]), t3 = _mm256_unpackhi_pd(u[2], u[3]);
  const __m256d dx = _mm256_permute2f128_pd(t0, t2, 0x20),
                mx = _mm256_permute2f128_pd(t0, t2, 0x31);
  const __m256d dy = _mm256_permute2f128_pd(t1, t3, 0x20),
                my = _mm256_permute2f128_pd(t1, t3, 0x31);
  const __m256d length_squared = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
  const __m256d length = _mm256_sqrt_pd(length_squared);
  const __m256d has_direction = _mm256_cmp_pd(length_squared, _mm256_setzero_pd(), _CMP_GT_OQ);
  // At zero length, n = 0 (d divided by infinity): no move, and λ, μ are kept below.
  const __m256d inverse_length = _mm256_div_pd(
      _mm256_set1_pd(1.0), _mm256_blendv_pd(_mm256_set1_pd(infinity), length, has_direction));
  const __m256d nx = _mm256_mul_pd(dx, inverse_length), ny = _mm256_mul_pd(dy, inverse_length);
  const __m256d lambda_i = lambda ? _mm256_loadu_pd(lambda) : _mm256_setzero_pd();
  const __m256d mu_i = mu ? _mm256_loadu_pd(mu) : _mm256_setzero_pd();
  const __m256d bs = _mm256_set1_pd(k.bs);
  const __m256d stretch = _mm256_sub_pd(length, _mm256_set1_pd(k.rest));
  const __m256d along = _mm256_mul_pd(
      _mm256_sub_pd(_mm256_sub_pd(_mm256_mul_pd(_mm256_set1_pd(-k.ks2), stretch), lambda_i),
                    _mm256_mul_pd(bs, _mm256_add_pd(_mm256_mul_pd(nx, mx), _mm256_mul_pd(ny, my)))),
      _mm256_set1_pd(k.along));
  const __m256d across = _mm256_mul_pd(
      _mm256_sub_pd(_mm256_xor_pd(mu_i, _mm256_set1_pd(-0.0)),  // −μ, as the scalar −mu_i
                    _mm256_mul_pd(bs, _mm256_sub_pd(_mm256_mul_pd(nx, my), _mm256_mul_pd(ny, mx)))),
      _mm256_set1_pd(k.across));
  if (lambda) {
    _mm256_storeu_pd(lambda,
                     _mm256_blendv_pd(lambda_i, _mm256_add_pd(lambda_i, along), has_direction));
    _mm256_storeu_pd(mu, _mm256_blendv_pd(mu_i, _mm256_add_pd(mu_i, across), has_direction));
  }
  const __m256d cx = _mm256_sub_pd(_mm256_mul_pd(along, nx), _mm256_mul_pd(across, ny));
  const __m256d cy = _mm256_add_pd(_mm256_mul_pd(along, ny), _mm256_mul_pd(across, nx));
  const __m256d even = _mm256_unpacklo_pd(cx, cy), odd = _mm256_unpackhi_pd(cx, cy);
  const __m128d move[4] = {_mm256_castpd256_pd128(even), _mm256_castpd256_pd128(odd),
                           _mm256_extractf128_pd(even, 1), _mm256_extractf128_pd(odd, 1)};
  const __m128d wp = _mm_set1_pd(k.wp), wq = _mm_set1_pd(k.wq);
  for (int i = 0; i < 4; ++i) {
    double* xp = x + 4L * c[i].p;
    double* xq = x + 4L * c[i].q;
    _mm_storeu_pd(xp, _mm_add_pd(_mm_loadu_pd(xp), _mm_mul_pd(wp, move[i])));
    _mm_storeu_pd(xq, _mm_sub_pd(_mm_loadu_pd(xq), _mm_mul_pd(wq, move[i])));
  }
}
#endif

class Xpbd final : public Integrator {
 public:
  explicit Xpbd(const XpbdParameters& parameters) : parameters_(parameters) {}
  std::string_view name() const override { return "xpbd"; }
  SolverWork solver_work() const override { return work_; }
  void restart() override { springs_ = nullptr; }

  void step(const Model& model, double h, Vectors& r, Vectors& v) override {
    const long n = long(r.cols());
    const int substeps = std::max(1, parameters_.substeps);
    const int iterations = std::max(1, parameters_.iterations);
    const double s = h / substeps;
    prepare(model, n, s);
    state_.resize(4, n);
    const std::size_t springs = model.springs.size();
    for (int substep = 0; substep < substeps; ++substep) {
      if (model.external) {
        v += s * (*model.external)(r, v);
        ++work_.external;
      }
      // Each particle's x = r + s v and its substep start r side by side: a projection reads both
      // of an end from one cache line.
      double* state = state_.data();
      const double* position = r.data();
      const double* velocity = v.data();
      for (long i = 0; i < 2 * n; i += 2) {
        state[2 * i] = position[i] + s * velocity[i];
        state[2 * i + 1] = position[i + 1] + s * velocity[i + 1];
        state[2 * i + 2] = position[i];
        state[2 * i + 3] = position[i + 1];
      }
      if (iterations > 1) {
        std::fill(lambda_.begin(), lambda_.end(), 0.0);
        std::fill(mu_.begin(), mu_.end(), 0.0);
      }
      for (int pass = 0; pass < iterations; ++pass)
        project(iterations > 1);
      work_.projections += long(springs) * iterations;
      double* new_position = r.data();
      double* new_velocity = v.data();
      for (long i = 0; i < 2 * n; i += 2) {
        new_velocity[i] = (state[2 * i] - state[2 * i + 2]) / s;
        new_velocity[i + 1] = (state[2 * i + 1] - state[2 * i + 3]) / s;
        new_position[i] = state[2 * i];
        new_position[i + 1] = state[2 * i + 1];
      }
    }
  }

 private:
  // The colours, the kinds and the constraints in pass order, again whenever the springs, the
  // masses, the pins or the substep change.
  void prepare(const Model& model, long n, double s) {
    const std::vector<Spring>& springs = model.springs;
    Eigen::VectorXd w(n);
    for (long i = 0; i < n; ++i)
      w[i] = model.pinned[std::size_t(i)] ? 0.0 : 1.0 / model.mass[i];
    const bool same = springs_ == &springs && springs.size() == ends_.size() && s == s_ &&
                      w.size() == inverse_mass_.size() && w == inverse_mass_;
    if (same) return;
    springs_ = &springs;
    s_ = s;
    inverse_mass_ = std::move(w);
    // λ and μ only matter from a second pass on: with one pass they start at 0 and are not read
    // again, so they are not kept.
    const std::size_t kept = parameters_.iterations > 1 ? springs.size() : 0;
    lambda_.assign(kept, 0.0);
    mu_.assign(kept, 0.0);
    const std::vector<int> colour = colour_springs(springs, n);
    std::vector<long> next(group_start_.begin(), group_start_.end() - 1);
    struct Placed {
      Ends ends;
      int kind = 0;
    };
    std::vector<Placed> order(springs.size());  // pass order
    kinds_.clear();
    std::map<std::array<double, 5>, int> kind_of;  // (k, b, ℓ0, w_p, w_q) → kind
    const double s2 = s * s;
    for (std::size_t i = 0; i < springs.size(); ++i) {
      const Spring& spring = springs[i];
      const double wp = inverse_mass_[spring.p], wq = inverse_mass_[spring.q], sum = wp + wq;
      const auto [where, added] =
          kind_of.try_emplace({spring.k, spring.b, spring.rest_length, wp, wq}, int(kinds_.size()));
      if (added) {
        Kind kind;
        kind.wp = wp;
        kind.wq = wq;
        kind.rest = spring.rest_length;
        kind.ks2 = spring.k * s2;
        kind.bs = spring.b * s;
        kind.along = 1.0 / ((kind.ks2 + kind.bs) * sum + 1.0);
        kind.across = 1.0 / (kind.bs * sum + 1.0);
        kinds_.push_back(kind);
      }
      order[std::size_t(next[std::size_t(colour[i])]++)] = {{spring.p, spring.q}, where->second};
    }
    // Within a colour the order does not change the result: by kind, so that runs are long.
    const std::size_t groups = group_start_.size() - 1;
    const std::size_t independent = groups - (last_group_sequential_ ? 1 : 0);
    for (std::size_t g = 0; g < independent; ++g)
      std::stable_sort(order.begin() + group_start_[g], order.begin() + group_start_[g + 1],
                       [](const Placed& a, const Placed& b) { return a.kind < b.kind; });
    ends_.resize(order.size());
    runs_.clear();
    for (std::size_t g = 0; g < groups; ++g)
      for (long i = group_start_[g]; i < group_start_[g + 1]; ++i) {
        const Placed& placed = order[std::size_t(i)];
        ends_[std::size_t(i)] = placed.ends;
        if (i == group_start_[g] || placed.kind != runs_.back().kind)
          runs_.push_back({i, i, placed.kind});
        runs_.back().end = i + 1;
      }
  }

  // Each spring's colour, no two springs of a colour sharing a particle (but the last group's
  // when last_group_sequential_), and group_start_: where each colour's springs start in pass
  // order.
  std::vector<int> colour_springs(const std::vector<Spring>& springs, long n) {
    // Greedy colouring: a bit per colour used at each particle. A spring with every one of the
    // 64 colours taken at its ends (a particle with more than 63 springs) goes into a last group
    // that a pass visits in list order on one thread.
    std::vector<std::uint64_t> used(std::size_t(n), 0);
    std::vector<int> colour(springs.size());
    int colours = 0;
    for (std::size_t i = 0; i < springs.size(); ++i) {
      const auto p = std::size_t(springs[i].p), q = std::size_t(springs[i].q);
      const std::uint64_t taken = used[p] | used[q];
      const int c = taken == ~std::uint64_t(0) ? 64 : std::countr_one(taken);
      if (c < 64) used[p] |= std::uint64_t(1) << c, used[q] |= std::uint64_t(1) << c;
      colour[i] = c;
      colours = std::max(colours, c + 1);
    }
    group_start_.assign(std::size_t(colours) + 1, 0);
    for (int c : colour)
      ++group_start_[std::size_t(c) + 1];
    for (std::size_t c = 1; c < group_start_.size(); ++c)
      group_start_[c] += group_start_[c - 1];
    last_group_sequential_ = colours == 65;
    return colour;
  }

  // One Gauss–Seidel pass, colour by colour (the file's comment, step 2).
  void project(bool accumulate) {
    const std::size_t groups = group_start_.size() - 1;
    for (std::size_t g = 0; g < groups; ++g) {
      const long begin = group_start_[g], end = group_start_[g + 1];
      // Threads only for colours of many springs (grids from about 500×500): each colour is a
      // parallel region of its own, and smaller ones spent more time starting and waiting for
      // threads than projecting (two threads ran a 200×200 fabric 5 times slower than one on a
      // busy machine).
      const bool independent = !(g + 1 == groups && last_group_sequential_);
      const auto span = [&](long b, long e) {
        accumulate ? project_span<true>(b, e, independent) : project_span<false>(b, e, independent);
      };
      if (independent && end - begin >= 8 * parallel_items)
        for_blocks(end - begin, [&](long b, long e) { span(begin + b, begin + e); });
      else
        span(begin, end);
    }
  }

  // Projections [begin, end) of one group, run by run: four at a time (AVX2) or a chunk at a
  // time when they share no particle (`independent`), else one at a time.
  template <bool accumulate>
  void project_span(long begin, long end, bool independent) {
    auto run = std::partition_point(runs_.begin(), runs_.end(),
                                    [&](const Run& r) { return r.end <= begin; });
    for (; run != runs_.end() && run->begin < end; ++run) {
      const long b = std::max(begin, run->begin), e = std::min(end, run->end);
      const Kind& k = kinds_[std::size_t(run->kind)];
      if (!independent || path_ == Path::one)
        project_range<accumulate>(b, e, k);
      else if (path_ == Path::four)
        project_fours<accumulate>(b, e, k);
      else
        project_chunks<accumulate>(b, e, k);
    }
  }

  // Projections [begin, end) of one colour and kind, four at a time with AVX2 (project_four);
  // the last few one at a time.
  template <bool accumulate>
  void project_fours(long begin, long end, const Kind& k) {
    double* x = state_.data();
    long i = begin;
#if SPRINGLAB_AVX2_PATHS
    for (; i + 4 <= end; i += 4)
      project_four(x, ends_.data() + i, k, accumulate ? lambda_.data() + i : nullptr,
                   accumulate ? mu_.data() + i : nullptr);
#else
    (void)x;              // chosen_path() never picks this path here
#endif
    project_range<accumulate>(i, end, k);
  }

  // Projections [begin, end) of one colour and kind, which share no particle: gathered,
  // projected and scattered a chunk at a time (the file's comment).
  template <bool accumulate>
  void project_chunks(long begin, long end, const Kind& c) {
    double* x = state_.data();  // particle i: x at 4i, 4i + 1, its substep start at 4i + 2, 4i + 3
    Chunk ch;
    for (long first = begin; first < end; first += chunk_size) {
      const Ends* ends = ends_.data() + first;
      const int count = int(std::min<long>(chunk_size, end - first));
      for (int j = 0; j < count; ++j) {
        const long p = 4L * ends[j].p, q = 4L * ends[j].q;
        ch.dx[j] = x[p] - x[q];
        ch.dy[j] = x[p + 1] - x[q + 1];
        ch.mx[j] = (x[p] - x[p + 2]) - (x[q] - x[q + 2]);
        ch.my[j] = (x[p + 1] - x[p + 3]) - (x[q + 1] - x[q + 3]);
      }
      project_chunk(count, c, ch.dx, ch.dy, ch.mx, ch.my,
                    accumulate ? lambda_.data() + first : zeros,
                    accumulate ? mu_.data() + first : zeros, ch.along, ch.across, ch.cx, ch.cy);
      const double wp = c.wp, wq = c.wq;
      for (int j = 0; j < count; ++j) {
        const long p = 4L * ends[j].p, q = 4L * ends[j].q;
        x[p] += wp * ch.cx[j];
        x[p + 1] += wp * ch.cy[j];
        x[q] -= wq * ch.cx[j];
        x[q + 1] -= wq * ch.cy[j];
        if (accumulate && ch.dx[j] * ch.dx[j] + ch.dy[j] * ch.dy[j] > 0.0) {
          lambda_[std::size_t(first + j)] += ch.along[j];
          mu_[std::size_t(first + j)] += ch.across[j];
        }
      }
    }
  }

  // Projections [begin, end) of the pass order one at a time, all of kind c: the group whose
  // springs may share particles, and what is left of a run after project_fours.
  // `accumulate`: λ and μ are kept (several passes).
  template <bool accumulate>
  void project_range(long begin, long end, const Kind& c) {
    double* x = state_.data();  // as in project_chunks
    double* lambda = lambda_.data();
    double* mu = mu_.data();
    for (long i = begin; i < end; ++i) {
      const long p = 4L * ends_[std::size_t(i)].p, q = 4L * ends_[std::size_t(i)].q;
      const double dx = x[p] - x[q], dy = x[p + 1] - x[q + 1];
      const double length_squared = dx * dx + dy * dy;
      if (length_squared == 0.0) continue;  // no direction: no force, as (1.1) says
      const double length = std::sqrt(length_squared), inverse_length = 1.0 / length;
      const double nx = dx * inverse_length, ny = dy * inverse_length;
      // Δ_p − Δ_q, the ends' relative move in this substep so far.
      const double mx = (x[p] - x[p + 2]) - (x[q] - x[q + 2]);
      const double my = (x[p + 1] - x[p + 3]) - (x[q + 1] - x[q + 3]);
      const double lambda_i = accumulate ? lambda[i] : 0.0, mu_i = accumulate ? mu[i] : 0.0;
      const double along =
          (-c.ks2 * (length - c.rest) - lambda_i - c.bs * (nx * mx + ny * my)) * c.along;
      const double across = (-mu_i - c.bs * (nx * my - ny * mx)) * c.across;
      if (accumulate) lambda[i] += along, mu[i] += across;
      const double cx = along * nx - across * ny, cy = along * ny + across * nx;
      x[p] += c.wp * cx;
      x[p + 1] += c.wp * cy;
      x[q] -= c.wq * cx;
      x[q + 1] -= c.wq * cy;
    }
  }

  XpbdParameters parameters_;
  SolverWork work_;
  const std::vector<Spring>* springs_ = nullptr;  // the list prepare() last saw
  double s_ = 0.0;                                // the substep it prepared for, s
  Eigen::VectorXd inverse_mass_;                  // w_i = 1/m_i, 0 for pinned particles
  std::vector<Ends> ends_;                        // the springs in pass order: colour by colour
  std::vector<Run> runs_;                         // ends_ cut into runs of one kind
  std::vector<Kind> kinds_;                       // their coefficients
  // How a colour is projected: four at a time where the processor has AVX2, else a chunk at a
  // time; SPRINGLAB_XPBD_PATH=chunks or =one chooses another, for the test that all three give
  // the same bits (tests/xpbd.cpp).
  enum class Path { four, chunks, one };
  Path path_ = chosen_path();
  static Path chosen_path() {
    const char* asked = std::getenv("SPRINGLAB_XPBD_PATH");
    const std::string_view name = asked ? asked : "";
    if (name == "one") return Path::one;
#if SPRINGLAB_AVX2_PATHS
    if (name == "chunks" || !__builtin_cpu_supports("avx2")) return Path::chunks;
    return Path::four;
#else
    return Path::chunks;  // no four-at-a-time path on this processor or system (avx2.hpp)
#endif
  }
  std::vector<long> group_start_;       // colour c is [start[c], start[c + 1])
  bool last_group_sequential_ = false;  // the last group is not a colour (see prepare)
  std::vector<double> lambda_;  // λ of each constraint in this substep, kg·m, in pass order
  std::vector<double> mu_;      // μ of each damper's sideways constraint, kg·m, in pass order
  // Rows 0–1: the particles' positions x during a substep's projections; rows 2–3: r at its start.
  Eigen::Matrix<double, 4, Eigen::Dynamic> state_;  // m
};

}  // namespace

std::unique_ptr<Integrator> make_xpbd(const XpbdParameters& parameters) {
  return std::make_unique<Xpbd>(parameters);
}

}  // namespace springlab::detail
