#include "springlab/grid_forces.hpp"

#include "springlab/errors.hpp"
#include "springlab/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace springlab {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// The forces on the first ends of `count` springs of one row of a link: spring j joins the
// particle p = first + j to q = p + offset. Written as s (r_q − r_p) + b (v_q − v_p) with
// s = k (L − ℓ0) / L, which is (1.1) + (1.2) for particle p; q receives the opposite (2.4).
// Restrict pointers and plain arrays: what GCC needs to vectorise the loop; a clone for AVX2
// (four doubles a vector, chosen at load time on processors that have it) beside the SSE2 one.
// Neither contracts to fused multiply-adds, so both give the same bits.
__attribute__((target_clones("avx2", "default"))) void link_row(
    double k, double b, double rest_length, const double* __restrict r, const double* __restrict v,
    long first, long offset, int count, double* __restrict f) {
  const double* rp = r + 2 * first;
  const double* rq = rp + 2 * offset;
  const double* vp = v + 2 * first;
  const double* vq = vp + 2 * offset;
  for (int j = 0; j < count; ++j) {
    const double dx = rq[2 * j] - rp[2 * j];
    const double dy = rq[2 * j + 1] - rp[2 * j + 1];
    const double length = std::sqrt(dx * dx + dy * dy);
    // At zero length there is no direction to push along: like (1.1) in the solutions, no
    // force. Dividing by infinity instead of 0 gives that without a branch.
    const double s = k * (length - rest_length) / (length > 0.0 ? length : infinity);
    f[2 * j] = s * dx + b * (vq[2 * j] - vp[2 * j]);
    f[2 * j + 1] = s * dy + b * (vq[2 * j + 1] - vp[2 * j + 1]);
  }
}

void add(double* __restrict to, const double* __restrict f, int values) {
  for (int e = 0; e < values; ++e)
    to[e] += f[e];
}

void subtract(double* __restrict to, const double* __restrict f, int values) {
  for (int e = 0; e < values; ++e)
    to[e] -= f[e];
}

// The rows of `rows` that thread `t` of `threads` owns: [first, end).
std::pair<int, int> rows_of(int t, int threads, int rows) {
  return {int(long(rows) * t / threads), int(long(rows) * (t + 1) / threads)};
}

}  // namespace

std::optional<GridForces> GridForces::of(const std::vector<Spring>& springs, int rows, int cols) {
  if (rows < 1 || cols < 1) return std::nullopt;
  struct Found {
    SpringFamily family;
    Link link;
    long count = 0;
    std::vector<bool> seen;  // by first end
  };
  std::vector<Found> found;
  const long n = long(rows) * cols;
  for (const Spring& s : springs) {
    long p = std::min(s.p, s.q), q = std::max(s.p, s.q);  // so di > 0, or di = 0 and dj > 0
    if (p < 0 || q >= n) return std::nullopt;
    const int di = int(q / cols - p / cols), dj = int(q % cols - p % cols);
    // Links reach two rows at most: a thread recomputes that many rows of its neighbour's.
    if (di > 2 || std::abs(dj) > 2 || (di == 0 && dj == 0)) return std::nullopt;
    auto same = std::find_if(found.begin(), found.end(), [&](const Found& f) {
      return f.family == s.family && f.link.di == di && f.link.dj == dj;
    });
    if (same == found.end()) {
      found.push_back({s.family, {di, dj, s.k, s.b, s.rest_length}, 0, std::vector<bool>(n)});
      same = found.end() - 1;
    }
    const Link& link = same->link;
    if (link.k != s.k || link.b != s.b || link.rest_length != s.rest_length || same->seen[p])
      return std::nullopt;
    same->seen[p] = true;
    ++same->count;
  }
  std::vector<Link> links;
  for (const Found& f : found) {
    if (f.count != long(rows - f.link.di) * (cols - std::abs(f.link.dj))) return std::nullopt;
    links.push_back(f.link);
  }
  return GridForces(std::move(links), rows, cols);
}

GridForces::GridForces(std::vector<Link> links, int rows, int cols)
    : links_(std::move(links)), rows_(rows), cols_(cols) {
  for (const Link& link : links_)
    deepest_ = std::max(deepest_, link.di);
}

// Rows [first_row, end_row) of force, from every spring with an end on them. A spring with its
// first end above first_row is computed here too (at most deepest_ rows of them) rather than
// taken from the thread that owns that row: so each particle's sum runs over the rows above it
// in the same order whatever the split, with no waiting between threads.
void GridForces::compute_rows(int first_row, int end_row, const Vectors& r, const Vectors& v,
                              Vectors& force, const GridFinish& finish, double* buffer) {
  double* out = force.data();
  const long begin = 2L * first_row * cols_, end = 2L * end_row * cols_;
  std::fill(out + begin, out + end, 0.0);
  for (int row = std::max(0, first_row - deepest_); row < end_row; ++row) {
    for (const Link& link : links_) {
      const int q_row = row + link.di;
      const bool own_p = row >= first_row, own_q = q_row >= first_row && q_row < end_row;
      if (q_row >= rows_ || !(own_p || own_q)) continue;
      const int count = cols_ - std::abs(link.dj);
      const long first = long(row) * cols_ + std::max(0, -link.dj);
      const long offset = long(link.di) * cols_ + link.dj;
      link_row(link.k, link.b, link.rest_length, r.data(), v.data(), first, offset, count, buffer);
      if (own_p) add(out + 2 * first, buffer, 2 * count);
      if (own_q) subtract(out + 2 * (first + offset), buffer, 2 * count);
    }
    // No later row has a spring ending on this one: finish it while it is in the cache.
    if (row >= first_row) finish_row(row, r, v, force, finish);
  }
}

// Each thread writes only its own rows of force, the acceleration and the wind's memory.
void GridForces::finish_row(int row, const Vectors& r, const Vectors& v, Vectors& force,
                            const GridFinish& finish) {
  const int begin = row * cols_, end = begin + cols_;
  double* f = force.data();
  if (finish.gravity) {
    const double gx = finish.gravity->x(), gy = finish.gravity->y();
    const double* m = finish.mass->data();
    for (int i = begin; i < end; ++i) {
      f[2 * i] += m[i] * gx;  // (5.2)
      f[2 * i + 1] += m[i] * gy;
    }
  }
  if (finish.wind) {
    const bool same_time = finish.time == wind_time_;
    for (int i = begin; i < end; ++i) {
      if (!same_time || wind_position_.col(i) != r.col(i)) {
        wind_position_.col(i) = r.col(i);
        wind_velocity_.col(i) = finish.wind->velocity_at(finish.time, r.col(i));
      }
      force.col(i) += finish.wind->drag() * (wind_velocity_.col(i) - v.col(i));  // (5.3)
    }
  }
  if (!finish.inverse_mass) return;
  double* a = finish.acceleration->data();
  const double* inverse_mass = finish.inverse_mass->data();
  for (int i = begin; i < end; ++i) {
    a[2 * i] = f[2 * i] * inverse_mass[i];
    a[2 * i + 1] = f[2 * i + 1] * inverse_mass[i];
  }
  if (finish.pinned)
    for (int i = begin; i < end; ++i)
      if ((*finish.pinned)[i]) a[2 * i] = a[2 * i + 1] = 0.0;
}

void GridForces::compute(const Vectors& r, const Vectors& v, Vectors& force,
                         const GridFinish& finish) {
  const long n = long(rows_) * cols_;
  if (r.cols() != n || v.cols() != n)
    throw InvalidParameter(
        "positions and velocities",
        std::to_string(r.cols()) + " and " + std::to_string(v.cols()) + " particles",
        std::to_string(n) + " each, the grid's particles");
  force.resize(2, n);
  if (finish.inverse_mass) finish.acceleration->resize(2, n);
  const int threads = n >= parallel_particles ? std::min(thread_count(), rows_) : 1;
  // Sized here, before any thread starts: a thread that allocated would get its own malloc
  // arena, 64 MiB of address space that a memory limit (ulimit -v) would have to hold.
  buffers_.resize(std::size_t(threads) * 2 * cols_);
  if (finish.wind && (wind_position_.cols() != n || finish.wind != wind_field_)) {
    wind_field_ = finish.wind;
    wind_position_.resize(2, n);
    wind_velocity_.resize(2, n);
    wind_time_ = std::numeric_limits<double>::quiet_NaN();
  }
#ifdef _OPENMP
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const int t = omp_get_thread_num(), granted = omp_get_num_threads();
#else
  {
    const int t = 0, granted = 1;
#endif
    const auto [first_row, end_row] = rows_of(t, granted, rows_);
    compute_rows(first_row, end_row, r, v, force, finish,
                 buffers_.data() + std::size_t(t) * 2 * cols_);
  }
  if (finish.wind) wind_time_ = finish.time;
}

}  // namespace springlab
