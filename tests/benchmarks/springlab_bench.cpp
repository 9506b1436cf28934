// springlab-bench: how fast the force code and each integrator run on the task 5 fabric, from
// 10×10 to 1000×1000 particles (README.md beside this file explains each row and lists figures).
//
//   force/limit/N          the limit kernel alone: what no force code can avoid (see LimitKernel)
//   force/springs/N        the reference accumulate_spring_forces (tasks 1–2): the readable code
//   force/fast/N           the kit's fast path (grid_forces.hpp), springs and dampers only
//   force/model/N          Simulation::acceleration without wind: springs, gravity, pins
//   force/model+wind/N     the same with the lab's gusty wind (the task 5 scene as shipped)
//   force/model+wind-repeat/N  the same at an unchanged t and r (Verlet's later iterations)
//                          Each force row: ns_per_spring, and over_limit, its time over the
//                          limit kernel's measured in alternation, in batches of evaluations
//                          (batch_size), least batch over least batch (over_limit_all: all
//                          over all). The model rows also run on two threads in alternation
//                          with one: speedup_2_threads, and speedup_2_threads_all.
//   step/METHOD/N          one step of each of the six integrators on the model without wind:
//                          steps_per_s, evaluations_per_step, and cost_in_evaluations, the step's
//                          time over the time of one force evaluation, measured in alternation
//   step/xpbd/N            one XPBD step (10 substeps of one iteration, the defaults): steps_per_s,
//                          ns_per_projection (a step's time over its constraint projections: one
//                          spring, one pass, the external forces' share included), over_limit (a
//                          step's time over as many limit-kernel calls as it makes passes over
//                          the springs), cost_in_evaluations as above
//   rk4-vs-odeint/N        the kit's rk4 and Boost.Odeint's runge_kutta4 stepping the same model
//                          in alternation: kit_over_odeint < 1 means the kit's step is faster
//
// Every row runs on one thread (set_thread_count(1)) except the second half of the
// speedup_2_threads alternation; times are the CPU time of this thread, or the wall clock in the
// model rows, where two threads take part. The counters are the figures: the Time column is that
// of one iteration, a batch of steps or evaluations and what it alternates with (the limit
// kernel, as many evaluations, or Odeint steps; one of each from 150×150 up). Every fabric starts
// as the lab's scene does, flat and at rest under its pinned top row, then falls for 0.3 s (30
// symplectic Euler steps) so that its springs are stretched and moving; each step benchmark goes
// back to that state every 1000 steps (explicit Euler, unstable at the lab's h on a fabric,
// every 100) so no run drifts into overflow.
#include "odeint_system.hpp"
#include "springlab/avx2.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/parallel.hpp"
#include "springlab/scene.hpp"
#include "springlab/simulation.hpp"
#include "springlab/this_implementation.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

using namespace springlab;

namespace {

// s of CPU time used by this thread.
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// s on the wall clock: for what runs on two threads.
double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The limit to measure the force code against: per spring only what no force code can avoid,
// the difference r_q − r_p, a square root for its length, one division, and the scatter of
// the result d/|d| to both ends, over the same grid links and rows as the fast path, vectorised
// by the same compiler with the same AVX2 clone. It reads no velocity and no parameter.
SPRINGLAB_AVX2_CLONES void limit_row(const double* __restrict r, long first, long offset, int count,
                                     double* __restrict f) {
  const double* rp = r + 2 * first;
  const double* rq = rp + 2 * offset;
  for (int j = 0; j < count; ++j) {
    const double dx = rq[2 * j] - rp[2 * j], dy = rq[2 * j + 1] - rp[2 * j + 1];
    const double inverse_length = 1.0 / std::sqrt(dx * dx + dy * dy);
    f[2 * j] = dx * inverse_length;
    f[2 * j + 1] = dy * inverse_length;
  }
}

// The same, added straight to both ends' sums: for links to another row (di > 0), whose two runs
// never overlap, no round trip through a buffer (as the fast path does there).
SPRINGLAB_AVX2_CLONES void limit_row_into(const double* __restrict r, long first, long offset,
                                          int count, double* __restrict p, double* __restrict q) {
  const double* rp = r + 2 * first;
  const double* rq = rp + 2 * offset;
  for (int j = 0; j < count; ++j) {
    const double dx = rq[2 * j] - rp[2 * j], dy = rq[2 * j + 1] - rp[2 * j + 1];
    const double inverse_length = 1.0 / std::sqrt(dx * dx + dy * dy);
    p[2 * j] += dx * inverse_length;
    p[2 * j + 1] += dy * inverse_length;
    q[2 * j] -= dx * inverse_length;
    q[2 * j + 1] -= dy * inverse_length;
  }
}

void scatter(double* __restrict to, const double* __restrict f, int values, double sign) {
  for (int e = 0; e < values; ++e)
    to[e] += sign * f[e];
}

class LimitKernel {
 public:
  explicit LimitKernel(const GridForces& grid)
      : grid_(grid), buffer_(2 * std::size_t(grid.cols())) {}
  void run(const Vectors& r, Vectors& out) {
    out.setZero(2, r.cols());
    const int rows = grid_.rows(), cols = grid_.cols();
    for (int row = 0; row < rows; ++row)
      for (const GridForces::Link& link : grid_.links()) {
        if (row + link.di >= rows) continue;
        const int count = cols - std::abs(link.dj);
        const long first = long(row) * cols + std::max(0, -link.dj);
        const long offset = long(link.di) * cols + link.dj;
        if (link.di > 0) {
          limit_row_into(r.data(), first, offset, count, out.data() + 2 * first,
                         out.data() + 2 * (first + offset));
          continue;
        }
        limit_row(r.data(), first, offset, count, buffer_.data());
        scatter(out.data() + 2 * first, buffer_.data(), 2 * count, 1.0);
        scatter(out.data() + 2 * (first + offset), buffer_.data(), 2 * count, -1.0);
      }
  }

 private:
  const GridForces& grid_;
  std::vector<double> buffer_;
};

// The task 5 fabric at n×n, with or without its wind, 0.3 s into its fall; its model set up
// for symplectic Euler, or for Verlet (whose iterations ask again at the same r: the fast path
// then remembers the springs and the wind). One at a time is kept (a 1000×1000 fabric holds 6
// million springs): benchmarks are registered grouped by fabric.
class Fabric {
 public:
  static Fabric& get(int n, bool wind, bool verlet = false) {
    static std::unique_ptr<Fabric> current;
    if (!current || current->n_ != n || current->wind_ != wind || current->verlet_ != verlet) {
      current.reset();
      current.reset(new Fabric(n, wind, verlet));
    }
    return *current;
  }

  Simulation& simulation() { return *simulation_; }
  const Scene& scene() const { return simulation_->scene(); }
  double springs() const { return double(scene().springs.size()); }
  GridForces& grid() { return *grid_; }
  LimitKernel& limit() { return *limit_; }

  // The model as an integrator sees it (Simulation::step passes the same).
  const AccelerationFunction& acceleration() const { return acceleration_; }
  Model model() const {
    return Model{acceleration_, scene().springs, scene().particles.mass, scene().particles.pinned,
                 &external_};
  }

 private:
  Fabric(int n, bool wind, bool verlet) : n_(n), wind_(wind), verlet_(verlet) {
    SceneParameters p = task_scene(5);
    p.rows = n;
    p.cols = n;
    p.wind.enabled = wind;
    p.integrator = "symplectic-euler";  // for the fall only: one evaluation a step
    simulation_ = std::make_unique<Simulation>(p, implementation());
    simulation_->advance(30);
    if (verlet) {
      Scene fallen = simulation_->scene();
      fallen.parameters.integrator = "verlet";
      simulation_ = std::make_unique<Simulation>(std::move(fallen), implementation());
    }
    grid_ = GridForces::of(scene().springs, n, n);
    limit_ = std::make_unique<LimitKernel>(*grid_);
    acceleration_ = [sim = simulation_.get()](const Vectors& r,
                                              const Vectors& v) -> const Vectors& {
      return sim->acceleration(r, v);
    };
    external_ = [sim = simulation_.get()](const Vectors& r, const Vectors& v) -> const Vectors& {
      return sim->external_acceleration(r, v);
    };
  }

  int n_;
  bool wind_, verlet_;
  std::unique_ptr<Simulation> simulation_;
  std::optional<GridForces> grid_;
  std::unique_ptr<LimitKernel> limit_;
  AccelerationFunction acceleration_, external_;
};

// Steps or evaluations per timed batch: about 20000 particles' worth, so that reading a clock
// costs nothing measurable even on the 10×10 fabric (the thread's CPU clock is a system call of
// about 0.6 µs here, a third of a 10×10 evaluation; the wall clock about 20 ns).
long batch_size(int n) {
  return std::max(1L, 20000L / (long(n) * n));
}

// The seconds that batches of one kind took: in all, and the least of them. The least is the
// figure to compare: other work on a shared machine only ever adds time to a batch (so timeit's
// advice), and a ratio of the least times compares the two codes each at its least disturbed.
struct Batches {
  double total = 0.0, least = std::numeric_limits<double>::infinity();
  void add(double seconds) {
    total += seconds;
    least = std::min(least, seconds);
  }
};

// Runs `kit` (a batch of force evaluations, as batch_size says, timing itself into `kit_batches`)
// and as many calls of the limit kernel in alternation, timed on `clock`.
struct Alternation {
  Batches limit;
  long evaluations = 0;  // of each
};
template <typename Kit>
Alternation alternate_with_limit(benchmark::State& state, Fabric& fabric, long batch, Kit kit,
                                 double (*clock)()) {
  const Particles& particles = fabric.scene().particles;
  Vectors limit_out;
  Alternation seconds;
  for (auto _ : state) {
    kit();
    const double t0 = clock();
    for (long i = 0; i < batch; ++i) {
      fabric.limit().run(particles.position, limit_out);
      benchmark::DoNotOptimize(limit_out.data());
    }
    seconds.limit.add(clock() - t0);
    seconds.evaluations += batch;
  }
  state.counters["batch_size"] = double(batch);
  return seconds;
}

// ns_per_spring of `evaluations` taking `kit` in all; over_limit, the least batch's time over the
// limit kernel's least, and over_limit_all, the ratio of all batches' times.
void report_against_limit(benchmark::State& state, const Fabric& fabric, long evaluations,
                          const Batches& kit, const Batches& limit) {
  state.counters["ns_per_spring"] = 1e9 * kit.total / double(evaluations) / fabric.springs();
  state.counters["over_limit"] = kit.least / limit.least;
  state.counters["over_limit_all"] = kit.total / limit.total;
}

void force_limit(benchmark::State& state, int n) {
  Fabric& fabric = Fabric::get(n, false);
  const Particles& particles = fabric.scene().particles;
  Vectors out;
  const double begin = thread_seconds();
  for (auto _ : state) {
    fabric.limit().run(particles.position, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ns_per_spring"] =
      1e9 * (thread_seconds() - begin) / double(state.iterations()) / fabric.springs();
}

void force_springs(benchmark::State& state, int n) {
  Fabric& fabric = Fabric::get(n, false);
  const Scene& scene = fabric.scene();
  const Implementation& impl = implementation();
  Vectors force = Vectors::Zero(2, scene.particles.size());
  // Not cleared between calls: this row is the spring code alone. The sums grow but stay finite
  // (|F| ~ 10 N, at most ~1e7 calls).
  const long batch = batch_size(n);
  Batches kit;
  const Alternation seconds = alternate_with_limit(
      state, fabric, batch,
      [&] {
        const double t0 = thread_seconds();
        for (long i = 0; i < batch; ++i) {
          impl.accumulate_spring_forces(scene.springs, scene.particles.position,
                                        scene.particles.velocity, force);
          benchmark::DoNotOptimize(force.data());
        }
        kit.add(thread_seconds() - t0);
      },
      thread_seconds);
  report_against_limit(state, fabric, seconds.evaluations, kit, seconds.limit);
  state.counters["springs"] = fabric.springs();
}

void force_fast(benchmark::State& state, int n) {
  Fabric& fabric = Fabric::get(n, false);
  const Particles& particles = fabric.scene().particles;
  Vectors force;
  const long batch = batch_size(n);
  Batches kit;
  const Alternation seconds = alternate_with_limit(
      state, fabric, batch,
      [&] {
        const double t0 = thread_seconds();
        for (long i = 0; i < batch; ++i) {
          fabric.grid().compute(particles.position, particles.velocity, force);
          benchmark::DoNotOptimize(force.data());
        }
        kit.add(thread_seconds() - t0);
      },
      thread_seconds);
  report_against_limit(state, fabric, seconds.evaluations, kit, seconds.limit);
}

// Evaluations alternate between the state and a copy moved 1 nm along x, so each pays for all of
// its work. `repeat` times Verlet's iterations after the first of a step instead: the fabric's
// model is set up for Verlet and asked again at the same t and r, so the fast path sums only the
// dampers again and reuses the springs' sums and the wind it remembers. Each iteration
// times a batch of evaluations on one thread, as many on two threads and as many calls of the
// limit kernel, all on the wall clock.
void force_model(benchmark::State& state, int n, bool wind, bool repeat = false) {
  Fabric& fabric = Fabric::get(n, wind, repeat);
  Simulation& simulation = fabric.simulation();
  const Particles& particles = fabric.scene().particles;
  Vectors moved = particles.position;
  moved.row(0).array() += 1e-9;
  const Vectors* positions[2] = {&particles.position, repeat ? &particles.position : &moved};
  int which = 0;
  Batches one_thread, two_threads;
  const long batch = batch_size(n);
  const auto evaluate = [&] {
    for (long i = 0; i < batch; ++i)
      benchmark::DoNotOptimize(
          simulation.acceleration(*positions[which ^= 1], particles.velocity).data());
  };
  const Alternation seconds = alternate_with_limit(
      state, fabric, batch,
      [&] {
        const double t0 = wall_seconds();
        evaluate();
        const double t1 = wall_seconds();
        set_thread_count(2);
        evaluate();
        const double t2 = wall_seconds();
        set_thread_count(1);
        one_thread.add(t1 - t0);
        two_threads.add(t2 - t1);
      },
      wall_seconds);
  report_against_limit(state, fabric, seconds.evaluations, one_thread, seconds.limit);
  state.counters["ns_per_particle"] =
      1e9 * one_thread.total / double(seconds.evaluations) / double(particles.size());
  state.counters["speedup_2_threads"] = one_thread.least / two_threads.least;
  state.counters["speedup_2_threads_all"] = one_thread.total / two_threads.total;
}

// Each iteration is a batch of steps, then as many force evaluations at the state reached, each
// batch timed: the cost in evaluations is a ratio of times measured side by side, which the
// other work of a shared machine disturbs far less than two separate benchmarks.
void step(benchmark::State& state, int n, const std::string& method) {
  Fabric& fabric = Fabric::get(n, false);
  Simulation& simulation = fabric.simulation();
  const Model model = fabric.model();
  const Particles& start = fabric.scene().particles;
  const double h = fabric.scene().parameters.step;
  const std::unique_ptr<Integrator> integrator = make_integrator(method, implementation());
  Vectors r = start.position, v = start.velocity;
  integrator->step(model, h, r, v);  // builds what the method keeps (patterns, matrices)
  simulation.acceleration(r, v);
  const long restart_every = method == "explicit-euler" ? 100 : 1000;
  const long batch = batch_size(n);
  long steps = 0, step_evaluations = 0;
  double step_seconds = 0.0, evaluation_seconds = 0.0;
  for (auto _ : state) {
    const long before = simulation.force_evaluations();
    const double t0 = thread_seconds();
    for (long i = 0; i < batch; ++i)
      integrator->step(model, h, r, v);
    const double t1 = thread_seconds();
    step_evaluations += simulation.force_evaluations() - before;
    for (long i = 0; i < batch; ++i)
      benchmark::DoNotOptimize(simulation.acceleration(r, v).data());
    const double t2 = thread_seconds();
    step_seconds += t1 - t0;
    evaluation_seconds += t2 - t1;
    steps += batch;
    if (steps % restart_every < batch) {  // back to the start state now and then
      r = start.position;
      v = start.velocity;
      integrator->restart();
    }
  }
  state.counters["steps_per_s"] = double(steps) / step_seconds;
  state.counters["evaluations_per_step"] = double(step_evaluations) / double(steps);
  state.counters["cost_in_evaluations"] = step_seconds / evaluation_seconds;
  state.counters["evaluation_us"] = 1e6 * evaluation_seconds / double(steps);
}

// XPBD (xpbd.cpp) works in passes over the springs, not force evaluations: each iteration is a
// batch of steps, then as many limit-kernel calls as those steps made passes (substeps ×
// iterations each), then as many force evaluations as steps, each batch timed.
void xpbd_step(benchmark::State& state, int n) {
  Fabric& fabric = Fabric::get(n, false);
  Simulation& simulation = fabric.simulation();
  const Model model = fabric.model();
  const Particles& start = fabric.scene().particles;
  const SceneParameters& p = fabric.scene().parameters;
  const std::unique_ptr<Integrator> integrator = make_integrator("xpbd", implementation(), p.xpbd);
  const long passes = long(p.xpbd.substeps) * p.xpbd.iterations;
  Vectors r = start.position, v = start.velocity, limit_out;
  integrator->step(model, p.step, r, v);  // its storage, once
  const long batch = batch_size(n);
  long steps = 0;
  const long projections_before = integrator->solver_work().projections;
  Batches step_batches, limit_batches;
  double evaluation_seconds = 0.0;
  for (auto _ : state) {
    const double t0 = thread_seconds();
    for (long i = 0; i < batch; ++i)
      integrator->step(model, p.step, r, v);
    const double t1 = thread_seconds();
    for (long i = 0; i < batch * passes; ++i) {
      fabric.limit().run(r, limit_out);
      benchmark::DoNotOptimize(limit_out.data());
    }
    const double t2 = thread_seconds();
    for (long i = 0; i < batch; ++i)
      benchmark::DoNotOptimize(simulation.acceleration(r, v).data());
    const double t3 = thread_seconds();
    step_batches.add(t1 - t0);
    limit_batches.add(t2 - t1);
    evaluation_seconds += t3 - t2;
    steps += batch;
    if (steps % 1000 < batch) {  // back to the start state now and then
      r = start.position;
      v = start.velocity;
      integrator->restart();
    }
  }
  const double projections =
      double(integrator->solver_work().projections - projections_before);  // timed steps only
  state.counters["steps_per_s"] = double(steps) / step_batches.total;
  state.counters["ns_per_projection"] = 1e9 * step_batches.total / projections;
  state.counters["over_limit"] = step_batches.least / limit_batches.least;
  state.counters["over_limit_all"] = step_batches.total / limit_batches.total;
  state.counters["cost_in_evaluations"] = step_batches.total / evaluation_seconds;
  state.counters["passes_per_step"] = double(passes);
  state.counters["batch_size"] = double(batch);
}

// Each iteration is a batch of kit steps, then as many Odeint steps, each batch timed.
void rk4_vs_odeint(benchmark::State& state, int n) {
  Fabric& fabric = Fabric::get(n, false);
  const Model model = fabric.model();
  const Particles& start = fabric.scene().particles;
  const double h = fabric.scene().parameters.step;
  const std::unique_ptr<Integrator> kit = make_integrator("rk4", implementation());
  Vectors r = start.position, v = start.velocity;
  OdeintSystem system(fabric.simulation());
  OdeintRk4 odeint;
  const OdeintState y0 = odeint_state(start);
  OdeintState y = y0;
  kit->step(model, h, r, v);  // both allocate their stage storage once
  odeint.do_step(std::ref(system), y, 0.0, h);
  const long batch = batch_size(n);
  double kit_seconds = 0.0, odeint_seconds = 0.0;
  long steps = 0;
  for (auto _ : state) {
    const double t0 = thread_seconds();
    for (long i = 0; i < batch; ++i)
      kit->step(model, h, r, v);
    const double t1 = thread_seconds();
    for (long i = 0; i < batch; ++i)
      odeint.do_step(std::ref(system), y, 0.0, h);
    const double t2 = thread_seconds();
    kit_seconds += t1 - t0;
    odeint_seconds += t2 - t1;
    steps += batch;
    if (steps % 1000 < batch) {  // back to the start about every 1000 steps
      r = start.position;
      v = start.velocity;
      y = y0;
    }
  }
  state.counters["kit_over_odeint"] = kit_seconds / odeint_seconds;
  state.counters["kit_steps_per_s"] = double(steps) / kit_seconds;
  state.counters["odeint_steps_per_s"] = double(steps) / odeint_seconds;
}

// The processor's name as the system gives it: absolute times do not travel between machines.
std::string processor_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.starts_with("model name"))
      if (const auto colon = line.find(':'); colon != std::string::npos)
        return line.substr(colon + 2);
  return "unknown";
}

void register_all() {
  const std::vector<std::string> methods = integrator_names();
  for (const int n : {10, 30, 100, 300, 1000}) {
    const auto add = [n](const std::string& name, auto function) {
      return benchmark::RegisterBenchmark((name + "/" + std::to_string(n)).c_str(), function, n)
          ->Unit(benchmark::kMicrosecond);
    };
    // A 1000×1000 model row's iteration takes about 45 ms: at 0.2 s only three pairs of batches
    // would decide speedup_2_threads, and this machine's vCPUs slow one now and then for tens of
    // ms. At least 2 s (about fifty pairs) whatever --benchmark_min_time says.
    const auto add_model = [&](const std::string& name, auto function) {
      benchmark::internal::Benchmark* row = add(name, function);
      if (n >= 1000) row->MinTime(2.0);
    };
    add("force/limit", force_limit);
    add("force/springs", force_springs);
    add("force/fast", force_fast);
    add_model("force/model", [](benchmark::State& s, int m) { force_model(s, m, false); });
    for (const std::string& method : methods) {
      // The implicit step's matrix at 1000×1000 (2 million unknowns, ~100 million entries and
      // their slots) would take several GB: measured up to 300×300.
      if (method == "implicit-euler" && n > 300) continue;
      if (method == "xpbd") {
        add("step/xpbd", xpbd_step);
        continue;
      }
      add("step/" + method, [method](benchmark::State& s, int m) { step(s, m, method); });
    }
    add("rk4-vs-odeint", rk4_vs_odeint);
    add_model("force/model+wind", [](benchmark::State& s, int m) { force_model(s, m, true); });
    add_model("force/model+wind-repeat",
              [](benchmark::State& s, int m) { force_model(s, m, true, true); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  // 0.2 s a benchmark unless --benchmark_min_time says otherwise (later flags win): the whole
  // default run then takes about a minute.
  std::vector<char*> args{argv[0], const_cast<char*>("--benchmark_min_time=0.2")};
  args.insert(args.end(), argv + 1, argv + argc);
  int count = int(args.size());
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
  benchmark::AddCustomContext("processor", processor_name());
  benchmark::AddCustomContext(
      "threads", parallel_built() ? "1, and 2 where a row says so" : "1 (built without OpenMP)");
  set_thread_count(1);
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
