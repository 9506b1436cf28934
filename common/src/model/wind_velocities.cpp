// WindField::velocities (wind.hpp): w(t, r) for a row of particles at a time, its sines four at
// a time. Apart from wind.cpp so that only this loop uses libmvec's sines: velocity() and
// compute() there keep std::sin's own results, and code that never calls velocities() never needs
// libmvec. Part of the task support library, which a submission links (a task 5 may call it: it
// is in the public header), compiled at -O3.
#include "springlab/wind.hpp"

#include "springlab/avx2.hpp"

#include <algorithm>
#include <cmath>

// glibc's libmvec holds vector versions of sin (2 lanes for SSE2, 4 for AVX2; at most 4 ulp from
// the exact value, where std::sin is within 1). Declaring them lets GCC vectorise the loop in
// WindField::velocities; libm links libmvec as needed. (Clang has no such attribute: there the
// loop calls std::sin one value at a time; so does GCC where the C library is not glibc's or has no
// libmvec for the processor: macOS, Windows, and glibc before 2.38 on arm64.)
#if defined(__GNUC__) && !defined(__clang__) && defined(__GLIBC__) && defined(__x86_64__)
extern "C" double sin(double) __attribute__((simd("notinbranch")));
#endif

namespace springlab {

// A file-local function, the member below its caller: under Clang a multiversioned function is
// not a symbol another file can call (issue 36).
namespace {

struct Gust {
  double amplitude, angular_frequency, phase;
};
struct Flow {
  double dx, dy, lag, speed, gustiness;
  Gust g0, g1, g2;
};

// The same sum as compute(), written over plain arrays so that the sines go four at a time. The
// sines run over fixed chunks of aligned storage, whole chunks always: every particle's sine then
// takes the vector path wherever its row starts in memory (a loop over `count` could be peeled to
// align its output, giving the first few particles the scalar sine, and so different bits
// depending on an address).
SPRINGLAB_AVX2_CLONES void flow_velocities(const Flow& f, double t, const double* __restrict r,
                                           int count, double* __restrict w) {
  // 16: small enough that a row's last chunk pays for few unused sines (a 100-column row for
  // 112, not 128), large enough that the loops below run in whole vectors with no scalar tail.
  constexpr int chunk = 16;
  alignas(64) double s[chunk], gust[chunk];
  const double dx = f.dx, dy = f.dy, lag = f.lag;
  const Gust g0 = f.g0, g1 = f.g1, g2 = f.g2;
  for (int first = 0; first < count; first += chunk) {
    const int n = std::min(chunk, count - first);
    const double* rc = r + 2 * first;
    for (int j = 0; j < n; ++j)
      s[j] = t - (rc[2 * j] * dx + rc[2 * j + 1] * dy) * lag;
    for (int j = n; j < chunk; ++j)
      s[j] = 0.0;
    for (int j = 0; j < chunk; ++j)
      gust[j] = g0.amplitude * std::sin(g0.angular_frequency * s[j] + g0.phase) +
                g1.amplitude * std::sin(g1.angular_frequency * s[j] + g1.phase) +
                g2.amplitude * std::sin(g2.angular_frequency * s[j] + g2.phase);
    double* wc = w + 2 * first;
    for (int j = 0; j < n; ++j) {
      const double speed = f.speed * (1.0 + f.gustiness * gust[j]);
      wc[2 * j] = speed * dx;
      wc[2 * j + 1] = speed * dy;
    }
  }
}

}  // namespace

void WindField::velocities(double t, const double* r, int count, double* w) const {
  const auto gust = [this](int i) {
    return Gust{gusts_[i].amplitude, gusts_[i].angular_frequency, gusts_[i].phase};
  };
  const double lag = speed_ > 0.0 ? 1.0 / speed_ : 0.0;
  const Flow flow{direction_.x(), direction_.y(), lag,     speed_,
                  gustiness_,     gust(0),        gust(1), gust(2)};
  flow_velocities(flow, t, r, count, w);
}

}  // namespace springlab
