#include "integrators/spring_matrices.hpp"

#include "springlab/integrator.hpp"

#include <algorithm>

namespace springlab::detail {

FreeParticles::FreeParticles(const std::vector<bool>& pinned) : index(pinned.size(), -1) {
  for (std::size_t i = 0; i < pinned.size(); ++i)
    if (!pinned[i]) {
      index[i] = size();
      particle.push_back(int(i));
    }
}

Eigen::SparseMatrix<double> scalar_damping(const std::vector<Spring>& springs,
                                           const FreeParticles& free) {
  std::vector<Eigen::Triplet<double>> entries;
  for (const Spring& s : springs) {
    const int p = free.index[std::size_t(s.p)], q = free.index[std::size_t(s.q)];
    if (p >= 0) entries.emplace_back(p, p, s.b);
    if (q >= 0) entries.emplace_back(q, q, s.b);
    if (p >= 0 && q >= 0) entries.emplace_back(p, q, -s.b), entries.emplace_back(q, p, -s.b);
  }
  Eigen::SparseMatrix<double> damping(free.size(), free.size());
  damping.setFromTriplets(entries.begin(), entries.end());  // sums the duplicates
  return damping;
}

}  // namespace springlab::detail

namespace springlab::detail {

bool ModelFingerprint::changed(const Model& model) {
  const auto same_damper = [](const Spring& a, const Spring& b) {
    return a.p == b.p && a.q == b.q && a.b == b.b;
  };
  if (known_ && pinned_ == model.pinned && mass_.size() == model.mass.size() &&
      mass_ == model.mass &&
      std::equal(springs_.begin(), springs_.end(), model.springs.begin(), model.springs.end(),
                 same_damper))
    return false;
  known_ = true;
  springs_ = model.springs;
  mass_ = model.mass;
  pinned_ = model.pinned;
  return true;
}

}  // namespace springlab::detail
