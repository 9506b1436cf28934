// The model of the forces that ran, measured about rest (measured_model.hpp).
#include "diagnosis/measured_model.hpp"

#include "springlab/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace springlab::internal {

namespace {

// The mean rest length of the springs (m): the scale of a small displacement. 1 without springs.
double typical_length(const Scene& scene, const Vectors& rest) {
  double sum = 0.0;
  for (const Spring& s : scene.springs)
    sum += (rest.col(s.p) - rest.col(s.q)).norm();
  return scene.springs.empty() || !(sum > 0.0) ? 1.0 : sum / double(scene.springs.size());
}

double largest(const Eigen::MatrixXd& m) {
  return m.size() == 0 ? 0.0 : m.cwiseAbs().maxCoeff();
}

}  // namespace

std::optional<LinearModel> measured_model(const Scene& scene, const Implementation& impl,
                                          const Vectors& rest) {
  Scene quiet = scene;
  SceneParameters& p = quiet.parameters;
  p.gravity.enabled = false;
  p.wind.enabled = false;
  p.push_duration = 0.0;
  std::vector<int> free;  // coordinates 2i (x) and 2i + 1 (y) of the free particles
  for (int i = 0; i < quiet.particles.size(); ++i)
    if (!quiet.particles.pinned[std::size_t(i)]) free.insert(free.end(), {2 * i, 2 * i + 1});
  const auto n = Eigen::Index(free.size());
  // Small enough that the forces are linear to rounding, large enough that rounding (about 1e-16
  // of a force) stays far below the difference: 1e-6 of a spring's length, and of the speed that
  // covers it in one step.
  const double dr = 1e-6 * typical_length(quiet, rest), dv = dr / p.step;
  LinearModel model;
  model.stiffness = Eigen::MatrixXd::Zero(n, n);
  model.damping = Eigen::MatrixXd::Zero(n, n);
  model.mass.resize(n);
  try {
    Simulation sim(std::move(quiet), impl);
    const Vectors still = Vectors::Zero(2, rest.cols());
    for (Eigen::Index j = 0; j < n; ++j) {
      const int coordinate = free[std::size_t(j)];
      model.mass[j] = sim.particles().mass[coordinate / 2];
      const auto slope = [&](bool of_velocity, double delta) {
        Vectors r = rest, v = still;
        Vectors& moved = of_velocity ? v : r;
        moved(coordinate % 2, coordinate / 2) += delta;
        const Vectors up = sim.acceleration(r, v);
        moved(coordinate % 2, coordinate / 2) -= 2.0 * delta;
        const Vectors& down = sim.acceleration(r, v);
        return Vectors((up - down) / (2.0 * delta));
      };
      const Vectors by_r = slope(false, dr), by_v = slope(true, dv);
      for (Eigen::Index i = 0; i < n; ++i) {
        const int row = free[std::size_t(i)];
        const double m = sim.particles().mass[row / 2];
        model.stiffness(i, j) = -m * by_r(row % 2, row / 2);
        model.damping(i, j) = -m * by_v(row % 2, row / 2);
      }
    }
  } catch (...) {
    return std::nullopt;  // the code under test failed here: nothing measured
  }
  if (!model.stiffness.allFinite() || !model.damping.allFinite()) return std::nullopt;
  model.stiffness = 0.5 * (model.stiffness + model.stiffness.transpose()).eval();
  model.damping = 0.5 * (model.damping + model.damping.transpose()).eval();
  return model;
}

double model_gap(const LinearModel& measured, const LinearModel& expected) {
  const auto gap = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    if (a.rows() != b.rows() || a.cols() != b.cols())
      return std::numeric_limits<double>::infinity();
    const double scale = largest(b) > 0.0 ? largest(b) : 1.0;
    return largest(a - b) / scale;
  };
  return std::max(gap(measured.stiffness, expected.stiffness),
                  gap(measured.damping, expected.damping));
}

}  // namespace springlab::internal
