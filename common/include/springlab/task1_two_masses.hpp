// Task 1: two masses joined by a spring and a damper, stepped with explicit Euler.
// Handout: handout/task1_two_masses.md. Your files: tasks/task1_two_masses/. TODO tag: T1.
#pragma once

#include "springlab/task_api.hpp"
#include "springlab/todo.hpp"
#include "springlab/types.hpp"

SPRINGLAB_TASK_API_BEGIN

/// Hooke's law, equation (1.1): the force on particle p from a spring between p and q,
///   F_pq = -k (|r_p - r_q| - ℓ0) (r_p - r_q) / |r_p - r_q|.
/// It pulls p towards q when the spring is stretched and pushes it away when compressed; the force
/// on q is -F_pq. When r_p = r_q the direction is undefined and the force is zero.
/// @param r_p  position of p, m        @param r_q          position of q, m
/// @param k    stiffness, N/m           @param rest_length  ℓ0, m
/// @return     the force on p, N
Vec2 spring_force(const Vec2& r_p, const Vec2& r_q, double k, double rest_length);

/// The damper, equation (1.2): the force on particle p from a damper between p and q,
///   F_pq = -b (v_p - v_q).
/// It opposes the relative velocity, so it only ever removes energy; the force on q is -F_pq.
/// @param v_p  velocity of p, m/s       @param v_q  velocity of q, m/s
/// @param b    damping coefficient, N·s/m
/// @return     the force on p, N
Vec2 damper_force(const Vec2& v_p, const Vec2& v_q, double b);

/// One explicit (forward) Euler step of length h, equations (1.4) and (1.5):
///   r_{n+1} = r_n + h v_n,   v_{n+1} = v_n + h a_n,   a_n = acceleration(r_n, v_n).
/// Both updates use the values at the start of the step. Order 1; for one damped spring it is
/// stable only for h < 2ζ/ω = b/k (equation (1.6)), which the lab's h = 0.01 s exceeds.
/// @param acceleration  the physical model, a = F/m per particle (equation (1.3)), m/s²
/// @param h             the step, s
/// @param r             positions r_n, m; replaced by r_{n+1}
/// @param v             velocities v_n, m/s; replaced by v_{n+1}
void explicit_euler_step(const AccelerationFunction& acceleration, double h, Vectors& r,
                         Vectors& v);

SPRINGLAB_TASK_API_END
