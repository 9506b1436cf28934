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

#include "springlab/errors.hpp"
#include "springlab/scene_text.hpp"

#include <cerrno>
#include <cstring>
#include <iostream>
#include <sstream>

namespace springlab {

CsvOutput::CsvOutput(const std::string& path)
    : stream_(path == "-" ? &std::cout : &file_),
      shown_(path == "-" ? "standard output" : quoted_for_terminal(path)) {
  if (path == "-") return;
  errno = 0;
  file_.open(path);
  if (!file_)
    throw InvalidParameter("--csv", shown_,
                           std::string("a file that can be written") +
                               (errno ? std::string(" (") + std::strerror(errno) + ")" : ""));
}

bool CsvOutput::to_stdout() const {
  return stream_ == &std::cout;
}

void CsvOutput::start(const Simulation& simulation) {
  errno = 0;
  write_csv_header(*stream_, simulation.particles().size());
  check(simulation);  // before row() clears errno: the header may be what failed
  row(simulation);
}

void CsvOutput::row(const Simulation& simulation) {
  errno = 0;
  write_csv_row(*stream_, simulation);
  ++rows_;
  check(simulation);
}

void CsvOutput::finish(const Simulation& simulation) {
  errno = 0;
  stream_->flush();
  if (file_.is_open()) file_.close();
  check(simulation);
}

void CsvOutput::check(const Simulation& simulation) {
  // The stream fails when its buffer is written out, some rows after the one that filled it.
  if (!file_.fail() && (!to_stdout() || std::cout.good())) return;
  std::ostringstream message;
  message << "the CSV could not be written to " << shown_;
  if (errno) message << " (" << std::strerror(errno) << ")";
  message << ": it failed after " << rows_ << (rows_ == 1 ? " row" : " rows")
          << ", and the run stopped at t = " << simulation.time() << " s";
  throw WriteFailed(message.str());
}

}  // namespace springlab
