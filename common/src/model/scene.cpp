#include "springlab/scene.hpp"

#include "springlab/builtin_scenes.hpp"
#include "springlab/errors.hpp"
#include "springlab/scene_file.hpp"
#include "springlab/selection.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace springlab {

Vec2 grid_position(int row, int col, double spacing) {
  return Vec2(col * spacing, -row * spacing);
}

namespace {

std::string text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// Springs can come from student code: refuse any that would index outside the particles or
// make no physical sense, so a mistake shows as a message instead of memory corruption.
void check_springs(const std::vector<Spring>& springs, int particles, const std::string& source) {
  for (std::size_t i = 0; i < springs.size(); ++i) {
    const Spring& s = springs[i];
    const std::string field = source + ", spring " + std::to_string(i);
    if (!(s.p >= 0 && s.p < particles && s.q >= 0 && s.q < particles) || s.p == s.q)
      throw InvalidParameter(
          field, "from " + std::to_string(s.p) + " to " + std::to_string(s.q),
          "both ends must be different particles from 0 to " + std::to_string(particles - 1));
    if (!(std::isfinite(s.k) && s.k >= 0 && std::isfinite(s.b) && s.b >= 0))
      throw InvalidParameter(field, "k = " + text(s.k) + ", b = " + text(s.b),
                             "k >= 0 and b >= 0, both finite");
    if (!(std::isfinite(s.rest_length) && s.rest_length > 0))
      throw InvalidParameter(field + " rest length", text(s.rest_length), "a finite length > 0 m");
  }
}

}  // namespace

Scene build_scene(const SceneParameters& p, const Implementation& impl) {
  validate(p);
  Scene scene;
  scene.parameters = p;
  const int n = p.rows * p.cols;
  Particles& particles = scene.particles;
  particles.position.resize(2, n);
  for (int row = 0; row < p.rows; ++row)
    for (int col = 0; col < p.cols; ++col)
      particles.position.col(row * p.cols + col) = grid_position(row, col, p.spacing);
  for (int i : select_particles("displaced", p.displaced, p.rows, p.cols))
    particles.position.col(i) += p.displacement;
  particles.velocity = Vectors::Zero(2, n);
  particles.mass = Eigen::VectorXd::Constant(n, p.mass);
  particles.pinned.assign(n, false);
  for (int i : select_particles("pinned", p.pinned, p.rows, p.cols))
    particles.pinned[i] = true;

  if (p.structural.enabled) {
    scene.springs = impl.structural_springs(p.rows, p.cols, p.structural);
    check_springs(scene.springs, n, "structural_springs (task 2)");
  }
  if (p.shear.enabled) {
    const auto shear = impl.shear_springs(p.rows, p.cols, p.shear);
    check_springs(shear, n, "shear_springs (task 3)");
    scene.springs.insert(scene.springs.end(), shear.begin(), shear.end());
  }
  if (p.bend.enabled) {
    const auto bend = impl.bend_springs(p.rows, p.cols, p.bend);
    check_springs(bend, n, "bend_springs (task 5)");
    scene.springs.insert(scene.springs.end(), bend.begin(), bend.end());
  }
  return scene;
}

std::pair<int, std::string> first_non_finite(const Particles& particles) {
  const char* axis[] = {"x", "y"};
  for (int i = 0; i < particles.size(); ++i)
    for (int d = 0; d < 2; ++d) {
      if (!std::isfinite(particles.position(d, i))) return {i, std::string("position.") + axis[d]};
      if (!std::isfinite(particles.velocity(d, i))) return {i, std::string("velocity.") + axis[d]};
    }
  return {-1, ""};
}

void validate(const Scene& scene) {
  validate_built(scene.parameters);
  const Particles& particles = scene.particles;
  const int n = particles.size();
  if (particles.velocity.cols() != n || particles.mass.size() != n ||
      int(particles.pinned.size()) != n)
    throw InvalidParameter("particles", std::to_string(n) + " positions",
                           "as many velocities, masses and pinned flags as positions");
  if (const auto [i, quantity] = first_non_finite(particles); i >= 0)
    throw InvalidParameter(quantity + " of particle " + std::to_string(i),
                           text(quantity[0] == 'p' ? particles.position(quantity.back() - 'x', i)
                                                   : particles.velocity(quantity.back() - 'x', i)),
                           "a finite number");
  for (int i = 0; i < n; ++i)
    if (!(std::isfinite(particles.mass[i]) && particles.mass[i] > 0))
      throw InvalidParameter("mass of particle " + std::to_string(i), text(particles.mass[i]),
                             "a finite mass > 0 kg");
  check_springs(scene.springs, n, "springs");
}

SceneParameters task_scene(int task) {
  return load_scene("task" + std::to_string(task));
}

std::vector<std::string> task_scene_names() {
  std::vector<std::string> names;
  for (const BuiltinScene& scene : builtin_scenes())
    names.emplace_back(scene.name);
  return names;
}

SceneParameters load_scene(const std::string& name_or_path) {
  for (const BuiltinScene& scene : builtin_scenes())
    if (name_or_path == scene.name) return parse_scene(scene.text, std::string(scene.path));
  if (name_or_path.rfind("task", 0) == 0 && name_or_path.find('.') == std::string::npos)
    throw InvalidParameter("scene", "\"" + name_or_path + "\"",
                           "task1 ... task5, task4-damped or the path of a readable scene file");
  return load_scene_file(name_or_path);
}

}  // namespace springlab
