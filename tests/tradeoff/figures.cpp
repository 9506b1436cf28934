// The figures, drawn by gnuplot from data files and scripts written here (kept in the output
// directory, so a figure can be redrawn or restyled without rerunning the study). SVG: small,
// sharp at any size, and readable in a diff.
#include "measure.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace springlab::tradeoff {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> all_methods(const StudyOptions& options) {
  std::vector<std::string> methods = study_methods(options);
  methods.push_back(odeint_rk4);
  methods.push_back(odeint_dopri5);
  return methods;
}

std::string header(const std::string& svg, const std::string& title, const std::string& key) {
  return "set terminal svg size 760,560 dynamic font 'DejaVu Sans,12'\nset output '" + svg +
         "'\nset title '" + title + "'\nset key " + key + " font ',10'\nset grid\n";
}

// Error against wall time, one curve per method: the lower left is cheap and accurate.
std::string work_precision(const Results& r, const Scenario& s, const fs::path& data,
                           const std::string& svg) {
  std::ofstream out(data);
  out.precision(8);
  std::string plot = "plot";
  int index = 0;
  for (const std::string& method : all_methods(r.options)) {
    out << "# " << method << "\n";
    bool any = false;
    for (const Run& run : r.runs)
      if (run.scene == s.name && run.method == method && run.stable)
        out << run.wall << ' ' << run.max_error << '\n', any = true;
    out << "\n\n";
    if (any)  // a method with no stable run (the student's, not written yet) has no curve
      plot += std::string(plot == "plot" ? "" : ",") + " '" + data.string() + "' index " +
              std::to_string(index) + " with linespoints title '" + shown(method) + "'";
    ++index;
  }
  return header(svg, s.title + ": work against precision", "inside left bottom") +
         "set logscale xy\nset format xy '10^{%L}'\nset xlabel 'wall time of the run (s, "
         "minimum of the repeats)'\nset ylabel 'largest position error (m)'\n" +
         plot + "\n";
}

// Error against step with each fitted slope in the legend and the fitted line drawn over the
// range it was fitted on.
std::string error_vs_step(const Results& r, const Scenario& s, const fs::path& data,
                          const std::string& svg) {
  std::ofstream out(data);
  out.precision(8);
  std::string plot = "plot";
  int index = 0, colour = 1;
  for (const Order& o : r.orders) {
    if (o.scene != s.name) continue;
    out << "# " << o.method << "\n";
    double sx = 0, sy = 0;
    int n = 0;
    bool any = false;
    for (const Run& run : r.runs) {
      if (run.scene != s.name || run.method != o.method || !run.stable) continue;
      out << run.h << ' ' << run.max_error << '\n';
      any = true;
      if (run.h >= o.h_from && run.h <= o.h_to)
        sx += std::log(run.h), sy += std::log(run.max_error), ++n;
    }
    out << "\n\n# fit\n";
    if (n > 0 && !std::isnan(o.measured)) {
      const double a = (sy - o.measured * sx) / n;
      for (const double h : {o.h_from, o.h_to})
        out << h << ' ' << std::exp(a + o.measured * std::log(h)) << '\n';
    }
    out << "\n\n";
    const std::string c = " lc " + std::to_string(colour++);
    if (!any) {  // nothing stable to draw
      index += 2;
      continue;
    }
    plot += std::string(plot == "plot" ? "" : ",") + " '" + data.string() + "' index " +
            std::to_string(index) + " with linespoints" + c + " title '" + shown(o.method) +
            " (slope " + number(o.measured, 3) + ", theory " + std::to_string(o.theory) + ")'";
    if (n > 0 && !std::isnan(o.measured))  // the fitted line, where there is one
      plot += ", '" + data.string() + "' index " + std::to_string(index + 1) +
              " with lines dt 2 lw 3" + c + " notitle";
    index += 2;
  }
  return header(svg, s.title + ": error against step", "inside right bottom") +
         "set logscale xy\nset format xy '10^{%L}'\nset xlabel 'step h (s)'\nset ylabel "
         "'largest position error (m)'\n" +
         plot + "\n";
}

// Theory's and the measured critical step side by side, per method.
std::string critical(const Results& r, const Scenario& s, const fs::path& data,
                     const std::string& svg) {
  std::ofstream out(data);
  out.precision(8);
  out << "method theory measured\n";
  for (const StepLimit& c : r.critical)
    if (c.scene == s.name && !std::isinf(c.theory))
      out << '"' << shown(c.method) << "\" " << (c.theory > 0 ? number(c.theory, 8) : "NaN") << ' '
          << (c.measured > 0 ? number(c.measured, 8) : "NaN") << '\n';
  const std::string measured = "measured (linear motion about the equilibrium)";
  const std::string theory = "theory (stability.hpp, at the equilibrium)";
  return header(svg, s.title + ": critical steps", "inside left top") +
         "set style data histogram\nset style histogram clustered gap 1\nset style fill solid "
         "0.8 border -1\nset logscale y\nset ylabel 'critical step h_c (s)'\nset xtics "
         "rotate by -20\nplot '" +
         data.string() + "' using 2:xtic(1) title '" + theory + "', '' using 3 title '" + measured +
         "'\n";
}

// Total energy over time at the lab step, the reference drawn thick.
std::string energy(const Results& r, const Scenario& s, const fs::path& data,
                   const std::string& svg) {
  std::ofstream out(data);
  out.precision(8);
  std::vector<const Run*> lab;
  out << "t reference";
  for (const Run& run : r.runs)
    if (run.scene == s.name && run.method != odeint_dopri5 && run.method != odeint_rk4 &&
        !run.energy.empty())
      lab.push_back(&run), out << " \"" << shown(run.method) << '"';
  out << '\n';
  for (std::size_t j = 0; j < s.reference.time.size(); ++j) {
    out << s.reference.time[j] << ' ' << s.reference.energy[j];
    for (const Run* run : lab)
      out << ' ' << (j < run->energy.size() ? number(run->energy[j], 8) : "NaN");
    out << '\n';
  }
  // The reference's range and some room: an unstable method leaves the picture upwards.
  double lo = 0.0, hi = 0.0;
  for (const double e : s.reference.energy)
    lo = std::min(lo, e), hi = std::max(hi, e);
  std::string plot = "plot '" + data.string() +
                     "' using 1:2 with lines lw 6 lc 'gray70' title "
                     "'reference'";
  for (std::size_t i = 0; i < lab.size(); ++i)
    plot += ", '' using 1:" + std::to_string(i + 3) + " with lines lw 1.5 title '" +
            shown(lab[i]->method) + "'";
  return header(svg, s.title + ": total energy at h = " + number(s.params.step) + " s",
                "inside right top") +
         "set xlabel 't (s)'\nset ylabel 'kinetic + spring + gravity energy (J)'\n" +
         "set yrange [" + number(lo - 0.25 * s.energy_scale) + ":" +
         number(hi + 0.5 * s.energy_scale) + "]\n" + plot + "\n";
}

}  // namespace

bool write_figures(const Results& r, const std::string& dir, const std::string& figures) {
  fs::create_directories(dir);
  fs::create_directories(figures);
  const fs::path script = fs::path(dir) / "figures.gp";
  {
    std::ofstream out(script);
    for (const Scenario& s : r.scenarios) {
      const auto svg = [&](const std::string& what) {
        return (fs::path(figures) / (s.name + "-" + what + ".svg")).string();
      };
      const auto data = [&](const std::string& what) {
        return fs::path(dir) / (s.name + "-" + what + ".dat");
      };
      out << work_precision(r, s, data("work-precision"), svg("work-precision")) << "reset\n";
      out << error_vs_step(r, s, data("error-vs-step"), svg("error-vs-step")) << "reset\n";
      out << critical(r, s, data("critical-steps"), svg("critical-steps")) << "reset\n";
      out << energy(r, s, data("energy"), svg("energy")) << "reset\n";
    }
    out << write_damped_figure(r.damped, dir, figures);
    if (r.xpbd) out << write_xpbd_figures(*r.xpbd, dir, figures);
  }
  const std::string command = "gnuplot '" + script.string() + "'";
  return std::system(command.c_str()) == 0;
}

}  // namespace springlab::tradeoff
