#include "runner/csv.hpp"

#include <charconv>

namespace springlab {
namespace {

void put(std::ostream& out, double x) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, x).ptr;
  out << ',' << std::string_view(text, std::size_t(end - text));
}

}  // namespace

void write_csv_header(std::ostream& out, int particles) {
  out << 't';
  for (int i = 0; i < particles; ++i)
    out << ",x" << i << ",y" << i << ",vx" << i << ",vy" << i;
  out << ",kinetic,potential,px,py\n";
}

void write_csv_row(std::ostream& out, const Simulation& simulation) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, simulation.time()).ptr;
  out << std::string_view(text, std::size_t(end - text));
  const Particles& particles = simulation.particles();
  for (int i = 0; i < particles.size(); ++i) {
    put(out, particles.position(0, i));
    put(out, particles.position(1, i));
    put(out, particles.velocity(0, i));
    put(out, particles.velocity(1, i));
  }
  const Diagnostics d = simulation.diagnostics();
  put(out, d.kinetic);
  put(out, d.all_potential());  // springs and gravity, as the summary and the viewer say
  put(out, d.momentum.x());
  put(out, d.momentum.y());
  out << '\n';
}

}  // namespace springlab
