// Task 4: nine masses (a 3×3 grid) with structural and shear springs, stepped with Verlet.
// Handout: handout/task4_verlet.md. Your files: tasks/task4_verlet/. TODO tag: T4.
#pragma once

#include "springlab/task_api.hpp"
#include "springlab/todo.hpp"
#include "springlab/types.hpp"
#include "springlab/verlet_support.hpp"

SPRINGLAB_TASK_API_BEGIN

/// One Störmer–Verlet step of length h with a central-difference velocity for the dampers:
///   (4.1)  r_{n+1} = 2 r_n - r_{n-1} + h² a(r_n, v_n)
///   (4.2)  v_n     = (r_{n+1} - r_{n-1}) / (2h)
/// The dampers make a depend on v_n and (4.2) makes v_n depend on r_{n+1}, so solve the two
/// together: start from v_n = v (the velocity passed in), then repeat (4.1) and (4.2) until
/// velocity_settled(...) is true; after verlet_max_iterations throw StepFailed. Each repeat costs
/// one evaluation of `acceleration`; at the lab's values it settles in a few.
/// On the first step (history.has_previous is false) make the missing r_{-1} from a Taylor step
/// backwards in time, (4.3)  r_{-1} = r_0 - h v_0 + ½ h² a(r_0, v_0), so the start is second order.
/// Afterwards v holds the velocity at the new time from the second-order backward difference
///   (4.4)  v_{n+1} = (3 r_{n+1} - 4 r_n + r_{n-1}) / (2h),
/// and history.previous_position holds r_n for the next step.
/// Order 2, also with damping, because (4.2) is central; stable for h < 2/ω_max (equation (4.5))
/// whatever the damping, where ω_max is the scene's highest angular frequency, as long as the
/// repetition settles (h·c/2 below about 0.76, see verlet_max_iterations).
/// @param acceleration  the physical model, a = F/m per particle, m/s²
/// @param h             the step, s (the same for every step of one run)
/// @param r             positions r_n, m; replaced by r_{n+1}
/// @param v             velocities v_n, m/s; replaced by v_{n+1} from (4.4)
/// @param history       r_{n-1}, kept between steps; has_previous = false before the first step
void verlet_step(const AccelerationFunction& acceleration, double h, Vectors& r, Vectors& v,
                 VerletHistory& history);

SPRINGLAB_TASK_API_END
