#include "springlab/grid_forces.hpp"

#include "springlab/avx2.hpp"
#include "springlab/errors.hpp"
#include "springlab/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace springlab {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Spring j of one row of a link joins the particle p = first + j to q = p + offset; rp, rq, vp
// and vq point at the row's first p and q. Its two forces on p: the spring's s (r_q − r_p) with
// s = k (L − ℓ0) / L, (1.1), and the damper's b (v_q − v_p), (1.2); q receives the opposite
// (2.4). At zero length there is no direction to push along: like (1.1) in the solutions, no
// force; dividing by infinity instead of 0 gives that without a branch. Inlined into each
// kernel below, whose restrict pointers and plain arrays are what GCC needs to vectorise it.
struct LinkTerms {
  double spring_x, spring_y, damper_x, damper_y;
};
[[gnu::always_inline]] inline LinkTerms link_terms(double k, double b, double rest_length,
                                                   const double* rp, const double* rq,
                                                   const double* vp, const double* vq, int j) {
  const double dx = rq[2 * j] - rp[2 * j];
  const double dy = rq[2 * j + 1] - rp[2 * j + 1];
  const double length = std::sqrt(dx * dx + dy * dy);
  const double s = k * (length - rest_length) / (length > 0.0 ? length : infinity);
  return {s * dx, s * dy, b * (vq[2 * j] - vp[2 * j]), b * (vq[2 * j + 1] - vp[2 * j + 1])};
}

// The kernels: each a clone for AVX2 (four doubles a vector, chosen at load time on processors
// that have it, springlab/avx2.hpp) beside the baseline one; neither contracts to fused
// multiply-adds, so both give the same bits.

// Each spring's and damper's force together on the first ends of `count` springs, into f.
SPRINGLAB_AVX2_CLONES void link_row(double k, double b, double rest_length,
                                    const double* __restrict rp, const double* __restrict vp,
                                    long offset, int count, double* __restrict f) {
  for (int j = 0; j < count; ++j) {
    const LinkTerms t = link_terms(k, b, rest_length, rp, rp + 2 * offset, vp, vp + 2 * offset, j);
    f[2 * j] = t.spring_x + t.damper_x;
    f[2 * j + 1] = t.spring_y + t.damper_y;
  }
}

// The same added straight to p's sums and taken from q's, for links to another row (di > 0),
// whose two runs of sums never overlap: the same additions in the same order as link_row
// followed by add and subtract, without the round trip through a buffer.
SPRINGLAB_AVX2_CLONES void link_row_into(double k, double b, double rest_length,
                                         const double* __restrict rp, const double* __restrict vp,
                                         long offset, int count, double* __restrict p_sums,
                                         double* __restrict q_sums) {
  for (int j = 0; j < count; ++j) {
    const LinkTerms t = link_terms(k, b, rest_length, rp, rp + 2 * offset, vp, vp + 2 * offset, j);
    const double fx = t.spring_x + t.damper_x, fy = t.spring_y + t.damper_y;
    p_sums[2 * j] += fx;
    p_sums[2 * j + 1] += fy;
    q_sums[2 * j] -= fx;
    q_sums[2 * j + 1] -= fy;
  }
}

// The two apart: the springs' forces in f, the dampers' in d.
SPRINGLAB_AVX2_CLONES void link_row_apart(double k, double b, double rest_length,
                                          const double* __restrict rp, const double* __restrict vp,
                                          long offset, int count, double* __restrict f,
                                          double* __restrict d) {
  for (int j = 0; j < count; ++j) {
    const LinkTerms t = link_terms(k, b, rest_length, rp, rp + 2 * offset, vp, vp + 2 * offset, j);
    f[2 * j] = t.spring_x;
    f[2 * j + 1] = t.spring_y;
    d[2 * j] = t.damper_x;
    d[2 * j + 1] = t.damper_y;
  }
}

// The dampers alone, as in link_row_apart.
SPRINGLAB_AVX2_CLONES void damper_row(double b, const double* __restrict v, long first, long offset,
                                      int count, double* __restrict d) {
  const double* vp = v + 2 * first;
  const double* vq = vp + 2 * offset;
  for (int e = 0; e < 2 * count; ++e)
    d[e] = b * (vq[e] - vp[e]);
}

// The energies ½ k (L − ℓ0)² (whose negative gradient is (1.1)) of `count` springs of one row of a
// link, as link_row.
SPRINGLAB_AVX2_CLONES void link_energy_row(double k, double rest_length, const double* __restrict r,
                                           long first, long offset, int count,
                                           double* __restrict e) {
  const double* rp = r + 2 * first;
  const double* rq = rp + 2 * offset;
  for (int j = 0; j < count; ++j) {
    const double dx = rq[2 * j] - rp[2 * j];
    const double dy = rq[2 * j + 1] - rp[2 * j + 1];
    const double stretch = std::sqrt(dx * dx + dy * dy) - rest_length;
    e[j] = 0.5 * k * stretch * stretch;
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

// A row of a link within a row (di = 0, dj > 0) into the row's sums: particle c gets +f of the
// spring it starts (c < count), then −f of the one it ends (c ≥ dj). The same two additions in
// the same order as add followed by subtract, in one pass over the sums instead of two.
void scatter_within_row(const double* __restrict f, int count, int dj, int cols,
                        double* __restrict sums) {
  int c = 0;
  for (; c < std::min(dj, count); ++c) {
    sums[2 * c] += f[2 * c];
    sums[2 * c + 1] += f[2 * c + 1];
  }
  for (c = dj; c < count; ++c) {
    sums[2 * c] = (sums[2 * c] + f[2 * c]) - f[2 * (c - dj)];
    sums[2 * c + 1] = (sums[2 * c + 1] + f[2 * c + 1]) - f[2 * (c - dj) + 1];
  }
  for (c = std::max(dj, count); c < cols; ++c) {
    sums[2 * c] -= f[2 * (c - dj)];
    sums[2 * c + 1] -= f[2 * (c - dj) + 1];
  }
}

// The end of a row of sums F when every particle has one mass, in one pass: the remembered
// springs' sums first (F = S + F), then m g (5.2), then c (w − v) (5.3), then a = F · (1/m); F is
// then cleared for the ring's next row. The same operations in the same order as a pass for
// each, so the same bits, with the row read and written once.
struct RowEnd {
  const double* springs;  // S, or null when F holds them already
  double gravity_x, gravity_y;
  const double *wind, *velocity;  // w (null: no wind) and v of the row
  double drag, inverse_mass;
};
template <bool Springs, bool Gravity, bool Wind>
[[gnu::always_inline]] inline void end_row(const RowEnd& end, int width, double* __restrict f,
                                           double* __restrict a) {
  const double* __restrict s = end.springs;
  const double* __restrict w = end.wind;
  const double* __restrict v = end.velocity;
  for (int e = 0; e < width; e += 2) {  // x and y of one particle
    double x = f[e], y = f[e + 1];
    if constexpr (Springs) x = s[e] + x, y = s[e + 1] + y;
    if constexpr (Gravity) x += end.gravity_x, y += end.gravity_y;
    if constexpr (Wind) x += end.drag * (w[e] - v[e]), y += end.drag * (w[e + 1] - v[e + 1]);
    a[e] = x * end.inverse_mass;
    a[e + 1] = y * end.inverse_mass;
    f[e] = f[e + 1] = 0.0;
  }
}
SPRINGLAB_AVX2_CLONES void end_row(const RowEnd& end, bool gravity, int width, double* __restrict f,
                                   double* __restrict a) {
  switch (4 * (end.springs != nullptr) + 2 * gravity + (end.wind != nullptr)) {
    case 0:
      return end_row<false, false, false>(end, width, f, a);
    case 1:
      return end_row<false, false, true>(end, width, f, a);
    case 2:
      return end_row<false, true, false>(end, width, f, a);
    case 3:
      return end_row<false, true, true>(end, width, f, a);
    case 4:
      return end_row<true, false, false>(end, width, f, a);
    case 5:
      return end_row<true, false, true>(end, width, f, a);
    case 6:
      return end_row<true, true, false>(end, width, f, a);
    default:
      return end_row<true, true, true>(end, width, f, a);
  }
}

// f += c (w − v), (5.3), over `values` entries.
void add_drag(double c, const double* __restrict w, const double* __restrict v, int values,
              double* __restrict f) {
  for (int e = 0; e < values; ++e)
    f[e] += c * (w[e] - v[e]);
}

// Row `row` of a link: its `count` springs start at column p_col, particle `first`, and end
// `offset` particles further on.
struct RowOfLink {
  int count, p_col;
  long first, offset;
};
RowOfLink row_of(const GridForces::Link& link, int row, int cols) {
  const int p_col = std::max(0, -link.dj);
  return {cols - std::abs(link.dj), p_col, long(row) * cols + p_col,
          long(link.di) * cols + link.dj};
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

// Rows [first_row, end_row), from every spring with an end on them. A spring with its first end
// above first_row is computed here too (at most deepest_ rows of them) rather than taken from the
// thread that owns that row: so each particle's sum runs over the rows above it in the same order
// whatever the split, with no waiting between threads. The sums go to force, or, when only the
// acceleration is wanted, to `ring`: deepest_ + 1 rows that a row leaves once it is finished, so a
// large grid's forces never travel to memory and back. With remembered springs (pass_ apart or
// dampers_only), the springs' sums go to spring_sums_ and only the dampers' to force or the ring.
void GridForces::compute_rows(int first_row, int end_row, const Vectors& r, const Vectors& v,
                              Vectors& force, const GridFinish& finish, const Scratch& scratch) {
  const long width = 2L * cols_;
  const int slots = deepest_ + 1;
  const auto sums = [&](int row) {
    return scratch.ring ? scratch.ring + width * (row % slots) : force.data() + width * row;
  };
  if (scratch.ring)
    std::fill(scratch.ring, scratch.ring + width * slots, 0.0);
  else
    std::fill(force.data() + width * first_row, force.data() + width * end_row, 0.0);
  // Only the acceleration wanted but no ring: a small grid, its sums in force, finished in one
  // pass at the end (compute).
  const bool whole_finish = finish.inverse_mass && !scratch.ring;
  double* springs = spring_sums_.data();
  if (pass_ == Pass::apart) std::fill(springs + width * first_row, springs + width * end_row, 0.0);
  // Adds a row of first ends' forces to the rows this thread owns: +f on p, −f on q (2.4).
  const auto scatter = [&](const double* f, double* p, double* q, const Link& link, int count) {
    if (link.di == 0 && p) return scatter_within_row(f, count, link.dj, cols_, p);
    if (p) add(p, f, 2 * count);
    if (q) subtract(q, f, 2 * count);
  };
  for (int row = std::max(0, first_row - deepest_); row < end_row; ++row) {
    for (const Link& link : links_) {
      const int q_row = row + link.di;
      const bool own_p = row >= first_row, own_q = q_row >= first_row && q_row < end_row;
      if (q_row >= rows_ || !(own_p || own_q)) continue;
      const auto [count, p_col, first, offset] = row_of(link, row, cols_);
      const int q_col = p_col + link.dj;
      double* p_sums = own_p ? sums(row) + 2 * p_col : nullptr;
      double* q_sums = own_q ? sums(q_row) + 2 * q_col : nullptr;
      switch (pass_) {
        case Pass::together:
          if (link.di > 0 && p_sums && q_sums) {
            link_row_into(link.k, link.b, link.rest_length, r.data() + 2 * first,
                          v.data() + 2 * first, offset, count, p_sums, q_sums);
            break;
          }
          link_row(link.k, link.b, link.rest_length, r.data() + 2 * first, v.data() + 2 * first,
                   offset, count, scratch.springs);
          scatter(scratch.springs, p_sums, q_sums, link, count);
          break;
        case Pass::apart:
          link_row_apart(link.k, link.b, link.rest_length, r.data() + 2 * first,
                         v.data() + 2 * first, offset, count, scratch.springs, scratch.dampers);
          scatter(scratch.springs, own_p ? springs + 2 * first : nullptr,
                  own_q ? springs + 2 * (first + offset) : nullptr, link, count);
          scatter(scratch.dampers, p_sums, q_sums, link, count);
          break;
        case Pass::dampers_only:
          damper_row(link.b, v.data(), first, offset, count, scratch.dampers);
          scatter(scratch.dampers, p_sums, q_sums, link, count);
          break;
      }
    }
    // No later row has a spring ending on this one: finish it while it is in the cache.
    if (row >= first_row && !whole_finish)
      finish_rows(row, 1, r, v, sums(row),
                  pass_ == Pass::together ? nullptr : springs + width * row, finish,
                  scratch.springs);
  }
  if (whole_finish)
    finish_rows(first_row, end_row - first_row, r, v, sums(first_row),
                pass_ == Pass::together ? nullptr : springs + width * first_row, finish,
                scratch.springs);
}

// compute_rows for one thread over the whole grid with each spring's and damper's force added
// together into force: no rows of other threads, no ring, no passes apart. On a 10×10 fabric,
// about a microsecond an evaluation, that bookkeeping per link row measured 3 % of the time.
void GridForces::compute_whole(const Vectors& r, const Vectors& v, Vectors& force,
                               const GridFinish& finish, double* buffer) {
  const long width = 2L * cols_;
  double* sums = force.data();
  std::fill(sums, sums + width * rows_, 0.0);
  for (int row = 0; row < rows_; ++row) {
    for (const Link& link : links_) {
      if (row + link.di >= rows_) continue;
      const auto [count, p_col, first, offset] = row_of(link, row, cols_);
      const double *rp = r.data() + 2 * first, *vp = v.data() + 2 * first;
      if (link.di > 0) {
        link_row_into(link.k, link.b, link.rest_length, rp, vp, offset, count, sums + 2 * first,
                      sums + 2 * (first + offset));
      } else {
        link_row(link.k, link.b, link.rest_length, rp, vp, offset, count, buffer);
        scatter_within_row(buffer, count, link.dj, cols_, sums + 2 * first);
      }
    }
    if (!finish.inverse_mass)  // the forces wanted: each row finished while in the cache
      finish_rows(row, 1, r, v, sums + width * row, nullptr, finish, buffer);
  }
  if (finish.inverse_mass) finish_rows(0, rows_, r, v, sums, nullptr, finish, buffer);
}

// Rows [first_row, first_row + rows) at once: each thread writes only its own rows of the
// acceleration and the wind's memory. f: the rows' forces, x and y of each particle in turn;
// spring_sums: their remembered springs' sums to add first, or null. With finish.inverse_mass
// f is cleared (in the ring, for the row that takes its place). scratch: 2 doubles a particle,
// free.
void GridForces::finish_rows(int first_row, int rows, const Vectors& r, const Vectors& v,
                             double* __restrict f, const double* spring_sums,
                             const GridFinish& finish, double* __restrict scratch) {
  const long begin = long(first_row) * cols_;
  const int count = rows * cols_, width = 2 * count;  // particles, numbers
  const double* vr = v.data() + 2 * begin;
  const double* w = nullptr;                // the rows' wind velocities
  if (finish.wind && !remember_springs_) {  // new positions every call: w for these rows only
    finish.wind->velocities(finish.time, r.data() + 2 * begin, count, scratch);
    w = scratch;
  } else if (finish.wind) {
    const double* rr = r.data() + 2 * begin;
    double* remembered = wind_position_.data() + 2 * begin;
    double* remembered_w = wind_velocity_.data() + 2 * begin;
    if (finish.time != wind_time_ ||
        std::memcmp(remembered, rr, sizeof(double) * std::size_t(width)) != 0) {
      std::copy(rr, rr + width, remembered);
      finish.wind->velocities(finish.time, rr, count, remembered_w);
    }
    w = remembered_w;
  }
  double* __restrict a = finish.inverse_mass ? finish.acceleration->data() + 2 * begin : nullptr;
  const double m = finish.same_mass;
  if (a && m > 0.0) {
    const Vec2 g = finish.gravity ? Vec2(m * finish.gravity->x(), m * finish.gravity->y())  // (5.2)
                                  : Vec2::Zero();
    const RowEnd end{spring_sums, g.x(), g.y(), w, vr, finish.wind ? finish.wind->drag() : 0.0,
                     1.0 / m};
    end_row(end, finish.gravity != nullptr, width, f, a);
  } else {
    if (spring_sums)
      for (long e = 0; e < width; ++e)
        f[e] = spring_sums[e] + f[e];
    if (finish.gravity) {
      const double gx = finish.gravity->x(), gy = finish.gravity->y();
      const double* mass = m > 0.0 ? nullptr : finish.mass->data() + begin;
      for (int j = 0; j < count; ++j) {
        const double mj = m > 0.0 ? m : mass[j];
        f[2 * j] += mj * gx;  // (5.2)
        f[2 * j + 1] += mj * gy;
      }
    }
    if (w) add_drag(finish.wind->drag(), w, vr, width, f);
    if (!a) return;
    const double* inverse_mass = finish.inverse_mass->data() + begin;
    for (int j = 0; j < count; ++j) {
      a[2 * j] = f[2 * j] * inverse_mass[j];
      a[2 * j + 1] = f[2 * j + 1] * inverse_mass[j];
    }
    std::fill(f, f + width, 0.0);
  }
  if (finish.pinned) {
    const std::vector<int>& pins = *finish.pinned;
    for (auto pin = std::lower_bound(pins.begin(), pins.end(), begin);
         pin != pins.end() && *pin < begin + count; ++pin)
      a[2 * (*pin - begin)] = a[2 * (*pin - begin) + 1] = 0.0;
  }
}

void GridForces::compute(const Vectors& r, const Vectors& v, Vectors& force,
                         const GridFinish& finish) {
  const long n = long(rows_) * cols_;
  if (r.cols() != n || v.cols() != n)
    throw InvalidParameter(
        "positions and velocities",
        std::to_string(r.cols()) + " and " + std::to_string(v.cols()) + " particles",
        std::to_string(n) + " each, the grid's particles");
  if (finish.inverse_mass)
    finish.acceleration->resize(2, n);
  else
    force.resize(2, n);
  const int threads = n >= parallel_particles ? std::min(thread_count(), rows_) : 1;
  // Sized here, before any thread starts: a thread that allocated would get its own malloc
  // arena, 64 MiB of address space that a memory limit (ulimit -v) would have to hold.
  pass_ = Pass::together;
  if (remember_springs_) {
    const bool same = springs_position_.cols() == n &&
                      std::memcmp(springs_position_.data(), r.data(), sizeof(double) * 2 * n) == 0;
    if (!same) {
      springs_position_.resize(2, 0);  // no sums to reuse until this pass has made them
      spring_sums_.resize(2, n);
    }
    pass_ = same ? Pass::dampers_only : Pass::apart;
    ++damper_passes_;
  }
  if (pass_ != Pass::dampers_only) ++spring_passes_;
  // A small grid (one thread, forces within 40 kB) is finished in one pass at the end, its sums
  // in force: for 100 particles, calls and set-up per row would cost more than the pass.
  const bool whole_finish = finish.inverse_mass && n < parallel_particles;
  if (whole_finish) force.resize(2, n);
  const std::size_t row = 2 * std::size_t(cols_);
  const std::size_t ring =
      finish.inverse_mass && !whole_finish ? row * std::size_t(deepest_ + 1) : 0;
  // A thread's springs (one row, or the whole grid's wind when finished whole), dampers, ring.
  const std::size_t springs = whole_finish ? 2 * std::size_t(n) : row;
  const std::size_t each = springs + row + ring;
  buffers_.resize(std::size_t(threads) * each);
  if (finish.wind && remember_springs_ &&
      (wind_position_.cols() != n || finish.wind != wind_field_)) {
    wind_field_ = finish.wind;
    wind_position_.resize(2, n);
    wind_velocity_.resize(2, n);
    wind_time_ = std::numeric_limits<double>::quiet_NaN();
  }
  const auto rows_of_thread = [&](int t, int granted) {
    const auto [first_row, end_row] = rows_of(t, granted, rows_);
    double* mine = buffers_.data() + std::size_t(t) * each;
    compute_rows(first_row, end_row, r, v, force, finish,
                 {mine, mine + springs, ring > 0 ? mine + springs + row : nullptr});
  };
  // One thread: without OpenMP's runtime, so that a small grid's call costs as little as can be.
  if (threads == 1 && ring == 0 && pass_ == Pass::together) {
    compute_whole(r, v, force, finish, buffers_.data());
  } else if (threads == 1) {
    rows_of_thread(0, 1);
  } else {
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
    rows_of_thread(omp_get_thread_num(), omp_get_num_threads());
#else
    rows_of_thread(0, 1);  // unreachable: thread_count() is 1 without OpenMP
#endif
  }
  if (pass_ == Pass::apart) springs_position_ = r;  // the sums above are r's
  if (finish.wind) wind_time_ = finish.time;
}

void GridForces::add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                          Vectors& force) const {
  std::vector<double> w(2 * std::size_t(cols_));
  for (int row = 0; row < rows_; ++row) {
    const long begin = 2L * row * cols_;
    wind.velocities(t, r.data() + begin, cols_, w.data());
    add_drag(wind.drag(), w.data(), v.data() + begin, 2 * cols_, force.data() + begin);
  }
}

double GridForces::spring_energy(const Vectors& r) const {
  std::vector<double> energies(static_cast<std::size_t>(cols_));
  double total = 0.0;
  for (int row = 0; row < rows_; ++row)
    for (const Link& link : links_) {
      if (row + link.di >= rows_) continue;
      const int count = cols_ - std::abs(link.dj);
      link_energy_row(link.k, link.rest_length, r.data(), long(row) * cols_ + std::max(0, -link.dj),
                      long(link.di) * cols_ + link.dj, count, energies.data());
      total += Eigen::Map<const Eigen::VectorXd>(energies.data(), count).sum();
    }
  return total;
}

}  // namespace springlab
