#include "springlab/diagnostics.hpp"

#include "springlab/parallel.hpp"

#include <sstream>

namespace springlab {

// Both sums run over fixed blocks (parallel.hpp): on two threads for large scenes, with the
// same result for any thread count, and exactly the plain sum below sum_block items.
double kinetic_energy(const Eigen::VectorXd& mass, const Vectors& v) {
  return sum_blocks(long(v.cols()), [&](long begin, long end) {
    return 0.5 * mass.segment(begin, end - begin)
                     .dot(v.middleCols(begin, end - begin).colwise().squaredNorm().transpose());
  });
}

double spring_energy(const std::vector<Spring>& springs, const Vectors& r) {
  return sum_blocks(long(springs.size()), [&](long begin, long end) {
    double energy = 0.0;
    for (long i = begin; i < end; ++i) {
      const Spring& s = springs[std::size_t(i)];
      const double stretch = (r.col(s.p) - r.col(s.q)).norm() - s.rest_length;
      energy += 0.5 * s.k * stretch * stretch;
    }
    return energy;
  });
}

Vec2 linear_momentum(const Eigen::VectorXd& mass, const Vectors& v) {
  return v * mass;
}

double angular_momentum(const Eigen::VectorXd& mass, const Vectors& r, const Vectors& v,
                        const Vec2& about) {
  double total = 0.0;
  for (Eigen::Index i = 0; i < r.cols(); ++i) {
    const Vec2 arm = r.col(i) - about;
    total += mass[i] * (arm.x() * v(1, i) - arm.y() * v(0, i));
  }
  return total;
}

Vec2 centre_of_mass(const Eigen::VectorXd& mass, const Vectors& r) {
  return r * mass / mass.sum();
}

double gravitational_energy(const Eigen::VectorXd& mass, const Vectors& r, const Vectors& start,
                            const Vec2& g) {
  return -((g.transpose() * (r - start)) * mass).value();
}

Diagnostics diagnose(const Particles& particles, const std::vector<Spring>& springs, const Vec2& g,
                     const Vectors& start) {
  return diagnose(particles, spring_energy(springs, particles.position), g, start);
}

Diagnostics diagnose(const Particles& particles, double spring_energy, const Vec2& g,
                     const Vectors& start) {
  Diagnostics d = diagnose(particles, spring_energy);
  d.gravitational = gravitational_energy(particles.mass, particles.position, start, g);
  return d;
}

Diagnostics diagnose(const Particles& particles, const std::vector<Spring>& springs) {
  return diagnose(particles, spring_energy(springs, particles.position));
}

Diagnostics diagnose(const Particles& particles, double spring_energy) {
  Diagnostics d;
  d.kinetic = kinetic_energy(particles.mass, particles.velocity);
  d.potential = spring_energy;
  d.momentum = linear_momentum(particles.mass, particles.velocity);
  d.angular_momentum = angular_momentum(particles.mass, particles.position, particles.velocity);
  return d;
}

std::string energy_parts(const Diagnostics& d, bool gravity) {
  std::ostringstream out;
  out << "kinetic " << d.kinetic << ", potential " << d.all_potential();
  if (gravity) out << " (springs " << d.potential << ", gravity " << d.gravitational << ")";
  return out.str();
}

}  // namespace springlab
