// The reference model's fast path: the spring and damper forces (1.1), (1.2) of a scene whose
// springs are whole regular families on its rows × cols grid, as every lab scene's are. Each
// family is a "link": every spring joins the particle at [row, col] to the one at
// [row + di, col + dj], all with one k, b and ℓ0. A row of a link is then two contiguous runs of
// particles, so the compiler vectorises it, with no index per spring to read.
//
// Only the kit's own model uses it (Simulation, with the reference implementation): students'
// functions and the reference task functions they compare with stay as they are. The result
// equals accumulate_spring_forces up to rounding (the sums are taken in another order; the
// tests compare the two on every scene). Large grids are split over thread_count() threads
// (parallel.hpp) by rows; every particle's sum is taken in the same order whatever the split,
// so the result is the same to the bit for any number of threads.
#pragma once

#include "springlab/parallel.hpp"
#include "springlab/types.hpp"
#include "springlab/wind.hpp"

#include <limits>
#include <optional>
#include <vector>

namespace springlab {

/// What the fast path does after the springs, each thread on its own rows (the model of
/// Simulation::acceleration when no push acts).
struct GridFinish {
  const Vec2* gravity = nullptr;                  ///< g, m/s²: adds m_i g (5.2) when set
  const Eigen::VectorXd* mass = nullptr;          ///< m_i, kg (needed with gravity)
  const WindField* wind = nullptr;                ///< adds c (w(t, r_i) − v_i) (5.3) when set
  double time = 0.0;                              ///< t, s: the wind's time
  const Eigen::VectorXd* inverse_mass = nullptr;  ///< 1/m_i: then acceleration = F_i / m_i
  /// m, kg, when every particle's mass is m (> 0): then the two arrays above are not read (the
  /// same bits, m and 1/m being the arrays' every entry), a large grid's 16 bytes a particle less.
  double same_mass = 0.0;
  const std::vector<int>* pinned = nullptr;  ///< pinned particles, ascending: zero acceleration
  Vectors* acceleration = nullptr;           ///< m/s², resized (with inverse_mass)
};

class GridForces {
 public:
  /// The fast path for `springs` on a rows × cols grid (particle [row, col] has the index
  /// row·cols + col, equation (2.1)), or nothing when the springs are not whole regular
  /// families: a spring missing, doubled or with its own k, b or ℓ0.
  static std::optional<GridForces> of(const std::vector<Spring>& springs, int rows, int cols);

  /// force = every spring's and damper's force on each particle, N (resized to 2 × rows·cols);
  /// then `finish`. With finish.inverse_mass, only the acceleration is meant: force is then
  /// scratch (untouched, or zeros below `parallel_particles` particles). Uses
  /// thread_count() threads from `parallel_particles` particles up. Throws InvalidParameter when r
  /// or v do not hold rows·cols particles.
  void compute(const Vectors& r, const Vectors& v, Vectors& force, const GridFinish& finish = {});

  /// force += c (w(t, r_i) − v_i), (5.3), with the wind the fast path's finish computes: the same
  /// bits (WindField::velocities, row by row), for a replay that watches a fast-path run.
  void add_wind(const WindField& wind, double t, const Vectors& r, const Vectors& v,
                Vectors& force) const;

  /// For an integrator that asks again at the same positions (Verlet's velocity iterations): the
  /// springs' forces, which depend on r alone, are then summed apart from the dampers' and
  /// remembered, and a call at the same r (to the bit) sums only the dampers; so is the wind w
  /// at the same t and r. The result is the
  /// same to the bit whether the springs were remembered or not; it differs from the default
  /// (each spring's and damper's force added together) by rounding.
  void remember_springs(bool on) {
    remember_springs_ = on;
    springs_position_.resize(2, 0);
    wind_time_ = std::numeric_limits<double>::quiet_NaN();
  }

  /// Work done so far: passes over the springs' forces (with or without the dampers'), and
  /// passes over the dampers' alone or apart from the springs'.
  long spring_passes() const { return spring_passes_; }
  long damper_passes() const { return damper_passes_; }

  /// Σ ½ k (L − ℓ0)² over every spring, J: spring_energy (diagnostics.hpp) up to rounding, summed
  /// link row by link row, vectorised, in one thread (the viewer's plots ask for it every frame).
  double spring_energy(const Vectors& r) const;

  /// Below this many particles one thread is faster than two (parallel.hpp).
  static constexpr int parallel_particles = parallel_force_particles;

  /// One family: every spring joins [row, col] to [row + di, col + dj] (di ≥ 0).
  struct Link {
    int di = 0, dj = 0;
    double k = 0.0;            ///< N/m
    double b = 0.0;            ///< N·s/m
    double rest_length = 0.0;  ///< ℓ0, m
  };
  /// In the order the springs list first names them.
  const std::vector<Link>& links() const { return links_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }

 private:
  GridForces(std::vector<Link> links, int rows, int cols);
  struct Scratch {  // a thread's: one row of a link's spring and damper forces, the ring
    double *springs, *dampers, *ring;
  };
  enum class Pass { together, apart, dampers_only };
  void compute_rows(int first_row, int end_row, const Vectors& r, const Vectors& v, Vectors& force,
                    const GridFinish& finish, const Scratch& scratch);
  void compute_whole(const Vectors& r, const Vectors& v, Vectors& force, const GridFinish& finish,
                     double* buffer);
  // scratch: 2 free doubles a particle (the thread's spring buffer, done with for these rows).
  void finish_rows(int first_row, int rows, const Vectors& r, const Vectors& v, double* f,
                   const double* spring_sums, const GridFinish& finish, double* scratch);

  std::vector<Link> links_;
  int rows_ = 0, cols_ = 0, deepest_ = 0;  // deepest_: the largest di
  // Per thread: a row of a link's spring forces and one of its damper forces (2·cols each), then,
  // when only the acceleration is wanted, the deepest_ + 1 rows of sums still open.
  std::vector<double> buffers_;
  // remember_springs: the springs' sums and the positions they were computed at.
  bool remember_springs_ = false;
  Pass pass_ = Pass::together;
  Vectors springs_position_, spring_sums_;
  long spring_passes_ = 0, damper_passes_ = 0;
  // With remember_springs, the wind at each particle for wind_time_ and the position it was
  // computed at: Verlet's iterations ask again at the same t and r, and get it without the three
  // sines. Other integrators ask at new positions every time and keep no such memory.
  Vectors wind_position_, wind_velocity_;
  double wind_time_ = std::numeric_limits<double>::quiet_NaN();
  const WindField* wind_field_ = nullptr;  // the field wind_velocity_ came from
};

}  // namespace springlab
