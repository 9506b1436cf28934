// The kit's own integrators (integrator.hpp lists them all with order, cost and step limit),
// made by name in integrator.cpp. Private to the core's libraries
// (springlab_scenes and springlab_core, common/CMakeLists.txt).
#pragma once

#include "springlab/integrator.hpp"

#include <memory>

namespace springlab::detail {

std::unique_ptr<Integrator> make_symplectic_euler();
std::unique_ptr<Integrator> make_velocity_verlet();
std::unique_ptr<Integrator> make_rk4();
std::unique_ptr<Integrator> make_implicit_euler();
std::unique_ptr<Integrator> make_xpbd(const XpbdParameters& parameters);

}  // namespace springlab::detail
