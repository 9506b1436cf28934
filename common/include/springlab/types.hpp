// The data every part of springlab shares: particles, springs and the physical model as the
// integrators see it. SI units throughout; positions live in a 2D world with y pointing up.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <string_view>
#include <vector>

namespace springlab {

/// A 2D vector: a position (m), a velocity (m/s), an acceleration (m/s²) or a force (N).
using Vec2 = Eigen::Vector2d;

/// One 2D vector per particle: column i belongs to particle i (row 0 is x, row 1 is y).
using Vectors = Eigen::Matrix2Xd;

/// The particles of a scene: column i of each matrix, entry i of mass and pinned, is particle i.
struct Particles {
  Vectors position;          ///< r_i, m
  Vectors velocity;          ///< v_i, m/s
  Eigen::VectorXd mass;      ///< m_i, kg (always > 0)
  std::vector<bool> pinned;  ///< a pinned particle never moves: its acceleration is held at zero

  int size() const { return static_cast<int>(position.cols()); }
};

/// The kinds of spring in a grid (handout sections 2, 3 and 5). Each family has its own k, b and
/// ℓ0.
enum class SpringFamily { structural, shear, bend };

/// Every family, in the order above: for loops over families (toggles, counts, colours).
inline constexpr SpringFamily spring_families[] = {SpringFamily::structural, SpringFamily::shear,
                                                   SpringFamily::bend};

std::string_view to_string(SpringFamily family);

/// A spring with its damper between particles p and q (indices into Particles).
struct Spring {
  int p = 0;                                       ///< index of one end
  int q = 0;                                       ///< index of the other end
  SpringFamily family = SpringFamily::structural;  ///< which family it belongs to
  double k = 0.0;                                  ///< stiffness, N/m
  double b = 0.0;                                  ///< damping coefficient, N·s/m
  double rest_length = 0.0;                        ///< ℓ0, m
};

/// The physical model as an integrator sees it (lecture: model → acceleration → numerical method):
/// a = acceleration(r, v), one column per particle, in m/s². The returned matrix is storage owned
/// by the model and stays valid until the next call: copy it if you need it longer.
using AccelerationFunction = std::function<const Vectors&(const Vectors& r, const Vectors& v)>;

/// What the Verlet method (task 4) remembers between steps.
struct VerletHistory {
  bool has_previous = false;  ///< false until the first step has made r_{n-1}
  Vectors previous_position;  ///< r_{n-1}, m
};

}  // namespace springlab
