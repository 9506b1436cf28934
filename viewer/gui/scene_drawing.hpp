// Draws a running scene with SFML: springs as lines coloured by strain, particles as dots (pinned
// ones as squares), and the forces on one particle as arrows. Positions go through the Camera.
#pragma once

#include "gui/camera.hpp"
#include "springlab/simulation.hpp"

#include <SFML/Graphics/Color.hpp>
#include <SFML/Graphics/RenderTarget.hpp>

#include <set>

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

/// The particles' radius on screen, pixels.
float particle_radius(const Camera& camera, double spacing);

void draw_scene(sf::RenderTarget& target, const Simulation& sim, const Camera& camera,
                const DrawOptions& options);

/// The force of each spring and damper on `particle` and their sum, as arrows; a spring of
/// structural strength stretched by a fifth of its rest length makes an arrow one spacing long.
void draw_force_arrows(sf::RenderTarget& target, const Simulation& sim, const Camera& camera,
                       int particle);

/// The particle drawn under `screen`, or -1.
int particle_at(const Simulation& sim, const Camera& camera, sf::Vector2f screen);

/// The sum of the spring and damper forces on `particle` (N), as the simulation's code computes
/// them; zero when that code is not written yet.
Vec2 spring_force_on(const Simulation& sim, int particle);

}  // namespace springlab::view
