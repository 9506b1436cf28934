// The study's numbers as CSV (one file per table), the source of the figures and the page.
#include "measure.hpp"

#include <filesystem>
#include <fstream>

namespace springlab::tradeoff {

namespace {

std::ofstream open(const std::string& dir, const std::string& name) {
  std::filesystem::create_directories(dir);
  std::ofstream out(std::filesystem::path(dir) / name);
  out.precision(10);
  return out;
}

}  // namespace

void write_csv(const Results& r, const std::string& dir) {
  std::ofstream runs = open(dir, "runs.csv");
  runs << "scene,method,h,tolerance,stable,max_error,end_error,energy_error,evaluations,steps,"
          "evaluations_per_step,wall_s,unstable_why\n";
  for (const Run& run : r.runs) {
    const double per_step = run.steps > 0 ? double(run.evaluations) / double(run.steps) : 0.0;
    runs << run.scene << ',' << run.method << ',' << run.h << ',' << run.tolerance << ','
         << (run.stable ? 1 : 0) << ',' << run.max_error << ',' << run.end_error << ','
         << run.energy_error << ',' << run.evaluations << ',' << run.steps << ',' << per_step << ','
         << run.wall << ",\"" << run.unstable_why << "\"\n";
  }
  std::ofstream orders = open(dir, "orders.csv");
  orders << "scene,method,theory,measured,h_from,h_to,points\n";
  for (const Order& o : r.orders)
    orders << o.scene << ',' << o.method << ',' << o.theory << ',' << o.measured << ',' << o.h_from
           << ',' << o.h_to << ',' << o.points << '\n';
  std::ofstream critical = open(dir, "critical.csv");
  critical << "scene,method,theory_s,theory_source,measured_s,measured_half_width_s,how,about\n";
  for (const StepLimit& c : r.critical)
    critical << c.scene << ',' << c.method << ',' << c.theory << ",\"" << c.source << "\","
             << c.measured << ',' << c.half_width << ",\"" << c.how << "\",\"" << c.about << "\"\n";
  std::ofstream reference = open(dir, "reference.csv");
  reference << "scene,reference_error_m,energy_scale_J,evaluation_s,note\n";
  for (std::size_t i = 0; i < r.scenarios.size(); ++i) {
    const Scenario& s = r.scenarios[i];
    reference << s.name << ',' << s.reference_error << ',' << s.energy_scale << ','
              << r.evaluation_seconds[i] << ",\"" << s.reference_note << "\"\n";
  }
}

}  // namespace springlab::tradeoff
