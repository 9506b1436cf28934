// Draws a running scene with SFML: springs as lines coloured by strain, particles as dots (pinned
// ones as squares), and the forces on one particle as arrows. Positions go through the Camera.
// When the grid's spacing on screen is a few pixels, springs would only paint over each other:
// the cloth is then drawn as a surface of triangles coloured by the strain of its cells.
#pragma once

#include "gui/camera.hpp"
#include "springlab/simulation.hpp"

#include <SFML/Graphics/Color.hpp>
#include <SFML/Graphics/RenderTarget.hpp>

#include <set>
#include <vector>

namespace springlab::view {

/// Every colour the scene is drawn with, in one place (the tests look for them in screenshots).
namespace colour {
inline const sf::Color background{24, 26, 33};
inline const sf::Color particle{255, 196, 0};
inline const sf::Color pinned{235, 235, 245};
inline const sf::Color ghost{90, 200, 255, 150};  // the reference under the student's run
inline const sf::Color compressed{60, 120, 255};
inline const sf::Color at_rest{150, 150, 160};
inline const sf::Color stretched{255, 70, 50};
inline const sf::Color net_force{120, 255, 120};
inline const sf::Color highlight{255, 60, 200};  // the particle under the mouse, or that diverged
}  // namespace colour

struct DrawOptions {
  std::set<int> hidden_families;  ///< SpringFamily values (as int) not drawn
  double strain_scale = 0.05;     ///< |strain| drawn fully red or blue
  bool ghost = false;             ///< draw translucent, as the reference in overlay mode
  int highlighted = -1;           ///< a particle ringed in the highlight colour
};

/// A run as it is drawn: what stepping changes, copied when the frame is planned (the stepping
/// thread goes on meanwhile), and the simulation for what stepping leaves alone (its springs,
/// parameters and code), which only the window changes, with the stepping thread idle.
struct RunState {
  const Simulation* sim = nullptr;
  Vectors position, velocity;  // velocity only when force arrows are drawn, otherwise empty
  std::vector<bool> pinned;
  /// Copies sim's state into the storage of the last copy (no allocation once it has grown).
  void capture(const Simulation& simulation, bool with_velocity);
};

/// What the last draw_scene drew, counted: tests check the level of detail by these, not by time.
struct DrawCounts {
  bool surface = false;  ///< the cloth as a surface rather than as springs
  long triangles = 0;    ///< the surface's triangles
  long springs = 0;      ///< springs drawn as lines
  long dots = 0;         ///< particles drawn as dots or squares
  DrawCounts& operator+=(const DrawCounts& other);
};

/// Spacing on screen (pixels) below which a grid is drawn as a surface rather than as springs.
inline constexpr double surface_below_pixels = 4.0;
/// The smallest cell the surface is drawn with, pixels: finer cells are merged (surface_stride).
inline constexpr double surface_cell_pixels = 8.0;

/// The particles' radius on screen, pixels.
float particle_radius(const Camera& camera, double spacing);

/// Whether a scene of parameters p is drawn as a surface through this camera: a grid of at least
/// 2x2 whose spacing on screen is below surface_below_pixels.
bool draws_surface(const SceneParameters& p, const Camera& camera);

/// Every how many grid lines the surface is drawn (1: every one): the fewest that makes its
/// cells at least surface_cell_pixels wide at rest. Each drawn cell has the mean strain of the
/// springs it spans; the grid's last row and column are always drawn, so the outline is whole.
int surface_stride(const SceneParameters& p, const Camera& camera);

DrawCounts draw_scene(sf::RenderTarget& target, const RunState& run, const Camera& camera,
                      const DrawOptions& options);

/// The force of each spring and damper on `particle` and their sum, as arrows; a spring of
/// structural strength stretched by a fifth of its rest length makes an arrow one spacing long.
/// Needs the run's velocities.
void draw_force_arrows(sf::RenderTarget& target, const RunState& run, const Camera& camera,
                       int particle);

/// The particle drawn under `screen`, or -1.
int particle_at(const Simulation& sim, const Camera& camera, sf::Vector2f screen);

/// The sum of the spring and damper forces on `particle` (N), as the simulation's code computes
/// them; zero when that code is not written yet.
Vec2 spring_force_on(const Simulation& sim, int particle);

}  // namespace springlab::view
