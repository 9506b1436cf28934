#include "probes.hpp"
#include "exception_names.hpp"
#include "least_squares.hpp"

#include "springlab/parameters.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>

namespace springlab::testing {
namespace {

// "likely mistake: A; B", or "" when nothing was found.
std::string likely_mistake(const std::vector<std::string>& said) {
  if (said.empty()) return "";
  std::string text = "likely mistake: ";
  for (std::size_t i = 0; i < said.size(); ++i)
    text += (i == 0 ? "" : "; ") + said[i];
  return text;
}

// What was measured when no concrete mistake reproduces it, or "": facts only, no cause, on a
// line of its own kind, "measured: " (issue 38: a fit is evidence, not a cause).
std::string measured(const std::vector<std::string>& said) {
  if (said.empty()) return "";
  std::string text = "measured: ";
  for (std::size_t i = 0; i < said.size(); ++i)
    text += (i == 0 ? "" : "; ") + said[i];
  return text;
}

constexpr double close = 1e-7;  // relative agreement that counts as exact after a fit

// A fitted coefficient that can name a mistake: a small whole number or half of one (0, ±1/2,
// ±1, ±3/2, ±2, ...), to the fit's rounding. Any other value (0.9524, 1.003, 3e-8) is a
// measurement: it says how far the code is off, not which formula it uses.
bool simple(double c) {
  return std::abs(c) <= 4.0 && std::abs(2.0 * c - std::round(2.0 * c)) <= close * (1 + std::abs(c));
}

std::string number(double x) {
  if (std::abs(x - std::round(x)) < 1e-9) return std::to_string(long(std::round(x)));
  std::ostringstream out;
  out << std::setprecision(4) << x;
  return out.str();
}

bool near(double a, double b, double scale = 1.0) {
  return std::abs(a - b) <= close * (std::abs(a) + std::abs(b) + scale);
}

Vec2 unit(double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  return {std::cos(a), std::sin(a)};
}

// A sum of terms c · L^i · l0^j, as a formula: "L^2 - l0^2", "2 L - l0", "L^2 - l0 L".
struct Term {
  double coefficient;
  int power_l, power_rest;
};

std::string formula(std::vector<Term> terms) {
  std::sort(terms.begin(), terms.end(),
            [](const Term& a, const Term& b) { return a.power_l > b.power_l; });
  std::string text;
  for (const Term& t : terms) {
    if (std::abs(t.coefficient) < 1e-9) continue;
    const double magnitude = std::abs(t.coefficient);
    std::string factors;
    const auto power = [](const char* name, int p) -> std::string {
      if (p == 0) return "";
      if (p == 1) return name;
      if (p == -1) return std::string("/") + name;
      return std::string(name) + "^" + std::to_string(p);
    };
    const std::string l = power("L", t.power_l), r = power("l0", t.power_rest);
    for (const std::string& f : {l, r})
      if (!f.empty()) factors += (factors.empty() || f[0] == '/' ? "" : " ") + f;
    std::string term = std::abs(magnitude - 1.0) < 1e-9 && !factors.empty() && factors[0] != '/'
                           ? factors
                           : number(magnitude) + (factors.empty() ? "" : " " + factors);
    if (!factors.empty() && factors[0] == '/') term = number(magnitude) + factors;
    if (text.empty())
      text = (t.coefficient < 0 ? "-" : "") + term;
    else
      text += (t.coefficient < 0 ? " - " : " + ") + term;
  }
  return text.empty() ? "0" : text;
}

// A linear combination as a formula: {{1, "r0"}, {1, "h v0"}, {-0.5, "h^2 a"}} reads
// "r0 + h v0 - 0.5 h^2 a"; zero terms are left out.
std::string combination(const std::vector<std::pair<double, std::string>>& terms) {
  std::string text;
  for (const auto& [c, name] : terms) {
    if (std::abs(c) < 1e-9) continue;
    const std::string magnitude =
        std::abs(std::abs(c) - 1.0) < 1e-9 ? "" : number(std::abs(c)) + " ";
    if (text.empty())
      text = (c < 0 ? "-" : "") + magnitude + name;
    else
      text += (c < 0 ? " - " : " + ") + magnitude + name;
  }
  return text.empty() ? "0" : text;
}

// The power m of x in a coefficient c(x) = κ x^m, from c at x and at 2x; nothing when c is not
// such a power of x.
std::optional<int> power_of(double at_x, double at_2x) {
  if (std::abs(at_x) < 1e-12 && std::abs(at_2x) < 1e-12) return 0;
  if (std::abs(at_x) < 1e-12 || at_x * at_2x <= 0.0) return std::nullopt;
  const double m = std::log2(at_2x / at_x);
  const double whole = std::round(m);
  if (std::abs(m - whole) > 1e-6) return std::nullopt;
  return int(whole);
}

// The powers of L a law of the spring's length may hold.
constexpr int length_powers[] = {3, 2, 1, 0, -1};
constexpr int length_terms = 5;
using Law = Eigen::Matrix<double, length_terms, 1>;

// Fits y(L) = c3 L³ + c2 L² + c1 L + c0 + c_1 / L exactly on the lengths given; nothing when no
// such law fits.
std::optional<Law> law_in_length(const std::vector<double>& lengths,
                                 const std::vector<double>& values) {
  Eigen::MatrixXd a(long(lengths.size()), length_terms);
  Eigen::VectorXd y(long(lengths.size()));
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    for (int j = 0; j < length_terms; ++j)
      a(long(i), j) = std::pow(lengths[i], length_powers[j]);
    y[long(i)] = values[i];
    if (!std::isfinite(values[i])) return std::nullopt;
  }
  Law c = least_squares(a, y);
  if ((a * c - y).norm() > 1e-7 * (1.0 + y.norm())) return std::nullopt;
  for (int i = 0; i < length_terms; ++i)
    if (std::abs(c[i]) < 1e-9 * (1.0 + y.norm())) c[i] = 0.0;
  return c;
}

// Concrete wrong versions of (1.1), each evaluated on every probe before it is named.
struct SpringMistake {
  std::string words;
  std::function<Vec2(const Vec2& d, double k, double rest)> force;  // d = r_p - r_q
};

const std::vector<SpringMistake>& spring_mistakes() {
  using V = const Vec2&;
  static const std::vector<SpringMistake> all = {
      {"the spring force (1.1) has the opposite sign",
       [](V d, double k, double l0) { return Vec2(k * (d.norm() - l0) * d / d.norm()); }},
      {"the force uses the length |r_p - r_q| where (1.1) has the stretch |r_p - r_q| - l0",
       [](V d, double k, double) { return Vec2(-k * d); }},
      {"the direction r_p - r_q is not divided by its length |r_p - r_q| (1.1 needs a unit "
       "vector)",
       [](V d, double k, double l0) { return Vec2(-k * (d.norm() - l0) * d); }},
      {"the force is divided by the rest length l0: (1.1) is k (L - l0), not k (L - l0) / l0",
       [](V d, double k, double l0) { return Vec2(-k * (d.norm() - l0) / l0 * d / d.norm()); }},
      {"the force is multiplied by the rest length l0: (1.1) is k (L - l0)",
       [](V d, double k, double l0) { return Vec2(-k * (d.norm() - l0) * l0 * d / d.norm()); }},
      {"the stretch is taken in absolute value, k |L - l0|: stretched springs are right, but a "
       "compressed one (L < l0) pulls where (1.1) pushes; keep the sign of L - l0",
       [](V d, double k, double l0) { return Vec2(-k * std::abs(d.norm() - l0) * d / d.norm()); }},
      {"the length is measured after the direction was normalised, so L is always 1: the force "
       "is k (1 - l0) whatever the length; take |r_p - r_q| before normalising",
       [](V d, double k, double l0) { return Vec2(-k * (1.0 - l0) * d / d.norm()); }},
      {"the length is |r_p - r_q|^2 (squaredNorm) where (1.1) has |r_p - r_q| (norm)",
       [](V d, double k, double l0) {
         return Vec2(-k * (d.squaredNorm() - l0) * d / d.squaredNorm());
       }},
      {"the length is measured from the x components only, |x_p - x_q|, where (1.1) has the "
       "whole length |r_p - r_q| (norm()): a spring that is not horizontal gets the wrong force",
       [](V d, double k, double l0) {
         const double length = std::abs(d.x());
         return Vec2(-k * (length - l0) * d / length);
       }},
      {"the length is measured from the y components only, |y_p - y_q|, where (1.1) has the "
       "whole length |r_p - r_q| (norm()): a spring that is not vertical gets the wrong force",
       [](V d, double k, double l0) {
         const double length = std::abs(d.y());
         return Vec2(-k * (length - l0) * d / length);
       }},
      {"the length |r_p - r_q| is rounded to a float (about 7 digits): keep it a double",
       [](V d, double k, double l0) {
         const double length = double(float(d.norm()));
         return Vec2(-k * (length - l0) * d / length);
       }},
      {"the spring force (1.1) is twice as large as it should be",
       [](V d, double k, double l0) { return Vec2(-2 * k * (d.norm() - l0) * d / d.norm()); }},
      {"the spring force (1.1) is half as large as it should be",
       [](V d, double k, double l0) { return Vec2(-0.5 * k * (d.norm() - l0) * d / d.norm()); }},
      {"the spring force (1.1) is zero on every spring tried, stretched or compressed",
       [](V, double, double) { return Vec2(Vec2::Zero()); }},
  };
  return all;
}

// The first concrete mistake that gives f's force, to rounding, on every spring tried: lengths
// stretched and compressed, several rest lengths, stiffnesses and directions; "" when none does.
std::string spring_mistake_everywhere(const SpringForce& f) {
  const Vec2 r_q(0.4, -0.7);
  std::vector<std::pair<Vec2, std::pair<double, double>>> probes;  // d, (k, l0)
  for (const double degrees : {0.0, 37.0, 200.0, -135.0})
    for (const double rest : {1.0, std::numbers::sqrt2, 0.5, 2.0})
      for (const double ratio : {0.3, 0.6, 1.3, 2.5})
        for (const double k : {20.0, 7.5})
          probes.push_back({ratio * rest * unit(degrees), {k, rest}});
  std::vector<Vec2> got;
  for (const auto& [d, values] : probes)
    got.push_back(f(r_q + d, r_q, values.first, values.second));
  for (const SpringMistake& m : spring_mistakes()) {
    bool everywhere = true;
    for (std::size_t i = 0; i < probes.size() && everywhere; ++i) {
      const auto& [d, values] = probes[i];
      const Vec2 wrong = m.force(d, values.first, values.second);
      everywhere =
          got[i].allFinite() && (got[i] - wrong).norm() <= 1e-12 * values.first * (1.0 + d.norm());
    }
    if (everywhere) return "likely mistake: " + m.words;
  }
  return "";
}

// What f gives along the spring against (1.1) on a compressed and a stretched spring, in numbers.
std::string along_examples(const std::function<double(double k, double l0, double L)>& along) {
  std::ostringstream out;
  out << "along the spring, towards q, the force is";
  bool first = true;
  for (const auto& [l0, length] : {std::pair{1.0, 0.6}, std::pair{1.0, 1.3}, std::pair{2.0, 2.6}}) {
    out << (first ? " " : ", ") << std::setprecision(10) << along(20.0, l0, length)
        << " N at L = " << length << " m, l0 = " << l0 << " m";
    first = false;
  }
  out << " (k = 20 N/m), where (1.1), k (L - l0), gives " << 20.0 * (0.6 - 1.0) << ", "
      << 20.0 * (1.3 - 1.0) << " and " << 20.0 * (2.6 - 2.0) << " N";
  return out.str();
}

std::string spring_force_findings(const SpringForce& f) {
  const double k = 20.0, rest = 1.0;
  const Vec2 r_q(0.4, -0.7);
  // Across the spring: the force must lie along r_q - r_p.
  double worst_across = 0.0, worst_size = 0.0, angle = 0.0;
  bool finite = true;
  for (const double degrees : {0.0, 37.0, 90.0, 200.0, -135.0})
    for (const double ratio : {0.6, 1.3, 2.5}) {
      const Vec2 towards_q = -unit(degrees);
      const Vec2 r_p = r_q - ratio * rest * towards_q;
      const Vec2 got = f(r_p, r_q, k, rest);
      if (!got.allFinite()) finite = false;
      const double across = got.x() * towards_q.y() - got.y() * towards_q.x();
      if (std::abs(across) > worst_across) {
        worst_across = std::abs(across);
        worst_size = got.norm();
        angle = std::atan2(across, got.dot(towards_q)) * 180.0 / std::numbers::pi;
      }
    }
  if (!finite)
    return "likely mistake: the force is not a finite number for some springs of length between "
           "0.6 and 2.5 l0: a division by zero or a square root of a negative number?";
  // Across by more than rounding: a force of 1e17 N (a length near 0 divided by) has rounding
  // of its own far above 1e-9 k, and is along the spring all the same.
  if (worst_across > 1e-9 * k && worst_across > 1e-9 * worst_size) {
    std::ostringstream out;
    out << "likely mistake: the force is not along the spring: it makes an angle of up to "
        << number(std::abs(angle)) << " degrees with r_q - r_p on the springs tried, and (1.1) "
        << "is along r_p - r_q (look at which components, and which ends, the direction uses)";
    return out.str();
  }
  if (const std::string named = spring_mistake_everywhere(f); !named.empty()) return named;
  // Along the spring, towards q: (1.1) gives k (L - l0). As a law in L, l0 and k.
  const auto along = [&](double stiffness, double rest_length, double length) {
    const Vec2 towards_q = -unit(37.0);
    return f(r_q - length * towards_q, r_q, stiffness, rest_length).dot(towards_q);
  };
  const std::vector<double> ratios = {0.3, 0.6, 0.9, 1.4, 2.0, 3.1, 4.2};
  const auto fit = [&](double stiffness, double rest_length, double per) {
    std::vector<double> lengths, values;
    for (const double r : ratios) {
      lengths.push_back(r * rest_length);
      values.push_back(along(stiffness, rest_length, r * rest_length) / per);
    }
    return law_in_length(lengths, values);
  };
  // How it grows with k: in proportion (as (1.1)), not at all, or otherwise.
  const double at_k = along(k, rest, 1.7 * rest), at_2k = along(2 * k, rest, 1.7 * rest);
  const bool proportional = near(at_2k, 2 * at_k), constant_in_k = near(at_2k, at_k);
  const double per = proportional ? k : 1.0;  // the law is said per k when it is k times one
  const auto at_1 = fit(k, 1.0, per), at_2 = fit(k, 2.0, per);
  if (!at_1 || !at_2)
    return "likely mistake: " + along_examples(along) +
           "; no law a L^3 + b L^2 + c L + d + e/L fits it on the lengths tried";
  // Each coefficient as κ l0^m, from l0 = 1 and l0 = 2.
  std::vector<Term> terms;
  bool exact = true;
  for (int i = 0; i < length_terms; ++i) {
    const auto m = power_of((*at_1)[i], (*at_2)[i]);
    if (!m) return "likely mistake: " + along_examples(along);
    exact = exact && simple((*at_1)[i]);
    terms.push_back({(*at_1)[i], length_powers[i], *m});
  }
  const std::string law = formula(terms);
  if (law == "L - l0" && proportional) return "";
  // A law with coefficients such as 3e-8 or 0.95 is a measurement, not a formula someone wrote.
  if (!exact) return "likely mistake: " + along_examples(along);
  std::ostringstream out;
  out << "likely mistake: along the spring, towards q, the force is ";
  if (proportional)
    out << "k (" << law << ")";
  else if (constant_in_k)
    out << law << ", the same for every k (k is not in it)";
  else
    out << law << " at k = " << number(k) << " N/m, and it grows with k otherwise than in "
        << "proportion";
  out << " on every length L tried (0.3 to 3.1 l0, l0 = 1 m and 2 m), where (1.1) has k (L - l0)";
  if (proportional && law == "-L + l0") out << ": the spring force (1.1) has the opposite sign";
  if (proportional && law == "L")
    out << ": it uses the length L where (1.1) has the stretch L - l0";
  if (proportional && law == "L^2 - L l0")
    out << ": the direction r_p - r_q is not divided by its length";
  if (proportional && law == "L/l0 - 1") out << ": the force is divided by the rest length";
  return out.str();
}

std::string vec2_text(const Vec2& x) {
  return "(" + number(x.x()) + ", " + number(x.y()) + ")";
}

std::string damper_force_findings(const DamperForce& f) {
  // The map v_p, v_q -> F, column by column, at b and at 2b.
  const auto map = [&](double b) {
    Eigen::Matrix<double, 2, 4> m;
    const Vec2 zero = Vec2::Zero();
    m.col(0) = f(Vec2::UnitX(), zero, b) - f(zero, zero, b);
    m.col(1) = f(Vec2::UnitY(), zero, b) - f(zero, zero, b);
    m.col(2) = f(zero, Vec2::UnitX(), b) - f(zero, zero, b);
    m.col(3) = f(zero, Vec2::UnitY(), b) - f(zero, zero, b);
    return m;
  };
  const double b = 0.3;
  const Eigen::Matrix<double, 2, 4> m = map(b), m2 = map(2 * b);
  if (!m.allFinite()) return "likely mistake: the damper force is not a finite number";
  const Vec2 offset = f(Vec2::Zero(), Vec2::Zero(), b);
  // Linear in the velocities? Random velocities against the map.
  std::mt19937 engine(5);
  std::uniform_real_distribution<double> any(-2.0, 2.0);
  for (int trial = 0; trial < 10; ++trial) {
    const Vec2 v_p(any(engine), any(engine)), v_q(any(engine), any(engine));
    Eigen::Vector4d v;
    v << v_p, v_q;
    const Vec2 got = f(v_p, v_q, b), linear = offset + m * v;
    if ((got - linear).norm() > 1e-9 * (1.0 + got.norm())) {
      // Not linear: twice the velocities give other than twice the force, or the parts' forces
      // do not add up (an abs() of a component doubles exactly). Which one, as measured.
      const bool scales = (f(2 * v_p, 2 * v_q, b) - 2 * got).norm() <= 1e-9 * (1 + got.norm());
      const bool even = (f(-v_p, -v_q, b) - got).norm() <= 1e-9 * (1 + got.norm());
      return std::string("measured: the damper force is not linear in the velocities: ") +
             (scales ? "twice the velocities give twice the force, but at v_p = " + vec2_text(v_p) +
                           ", v_q = " + vec2_text(v_q) + " it is " + vec2_text(got) +
                           " N where the forces of their components, added, give " +
                           vec2_text(linear) + " N" +
                           (even ? ", and -v_p, -v_q give the same force as v_p, v_q: the sign "
                                   "of the velocities is lost"
                                 : std::string())
                     : "twice v_p - v_q gives other than twice the force") +
             "; (1.2), -b (v_p - v_q), is linear";
    }
  }
  std::ostringstream out;
  if (offset.norm() > 1e-12)
    out << "likely mistake: with both velocities zero the damper force is (" << number(offset.x())
        << ", " << number(offset.y()) << ") N, not zero";
  // Each block a multiple of I, at b and at 2b: κ b (it grows with b), κ (it does not), or
  // neither (a measurement, said as one). Each velocity's coefficient on its own: -b v_p - v_q
  // (brackets left out) has one of each.
  struct Coefficient {
    double kappa;
    int b_power;  // 1: κ b, 0: κ, -1: neither (κ is then the value at b)
  };
  const auto coefficient = [&](int column) -> std::optional<Coefficient> {
    const auto scalar = [column](const Eigen::Matrix<double, 2, 4>& at) -> std::optional<double> {
      const Eigen::Matrix2d block = at.middleCols<2>(column);
      const double c = block(0, 0);
      if (std::abs(block(1, 1) - c) > 1e-9 || std::abs(block(0, 1)) > 1e-9 ||
          std::abs(block(1, 0)) > 1e-9)
        return std::nullopt;
      return c;
    };
    const auto at_b = scalar(m), at_2b = scalar(m2);
    if (!at_b || !at_2b) return std::nullopt;
    if (std::abs(*at_2b - 2 * *at_b) <= 1e-9 * (1 + std::abs(*at_b)))
      return Coefficient{*at_b / b, 1};
    if (std::abs(*at_2b - *at_b) <= 1e-9 * (1 + std::abs(*at_b))) return Coefficient{*at_b, 0};
    return Coefficient{*at_b, -1};
  };
  const auto on_p = coefficient(0), on_q = coefficient(2);
  if (!on_p || !on_q) {
    if (!out.str().empty()) return out.str();
    return "likely mistake: the damper force mixes or leaves out components: for v_p = (1, 0) it "
           "is (" +
           number(m(0, 0)) + ", " + number(m(1, 0)) + ") N and for v_p = (0, 1) it is (" +
           number(m(0, 1)) + ", " + number(m(1, 1)) + ") N, where (1.2) gives (-b, 0) and (0, -b)";
  }
  const auto is = [](const Coefficient& c, double kappa, int power) {
    return c.b_power == power && std::abs(c.kappa - kappa) < 1e-9;
  };
  if (is(*on_p, -1, 1) && is(*on_q, 1, 1) && out.str().empty()) return "";
  if (on_p->b_power < 0 || on_q->b_power < 0) {
    // Neither κ b nor κ: what was measured, at two values of b, and no more.
    const auto at = [&](const Eigen::Matrix<double, 2, 4>& measured_map, double b_here) {
      std::ostringstream law;
      law << number(measured_map(0, 0)) << " v_p + " << number(measured_map(0, 2))
          << " v_q at b = " << number(b_here);
      return law.str();
    };
    if (!out.str().empty()) out << "; ";
    out << "measured: the damper force is " << at(m, b) << " N·s/m and " << at(m2, 2 * b)
        << " N·s/m, where (1.2) gives -b v_p + b v_q: look at how b enters damper_force";
    return out.str();
  }
  const auto term = [](const Coefficient& c, const char* v) {
    std::string text =
        std::abs(std::abs(c.kappa) - 1.0) < 1e-9 ? "" : number(std::abs(c.kappa)) + " ";
    text += c.b_power == 1 ? "b " : "";
    return (c.kappa < 0 ? "- " : "+ ") + text + v;
  };
  if (!out.str().empty()) out << "; ";
  std::string law;
  if (std::abs(on_p->kappa) > 1e-12) law += term(*on_p, "v_p");
  if (std::abs(on_q->kappa) > 1e-12) law += (law.empty() ? "" : " ") + term(*on_q, "v_q");
  if (law.empty()) law = "0";
  if (law.rfind("+ ", 0) == 0) law.erase(0, 2);
  if (law.rfind("- ", 0) == 0) law = "-" + law.substr(2);
  out << (out.str().empty() ? "likely mistake: " : "") << "the damper force is " << law;
  if (on_p->b_power == 0 && on_q->b_power == 0) out << " (it does not change with b)";
  out << " for every velocity tried, where (1.2) has -b (v_p - v_q)";
  if (std::abs(on_p->kappa) < 1e-12 && std::abs(on_q->kappa) < 1e-12)
    out << ": the damper force (1.2) is zero";
  else if (is(*on_p, 1, 1) && is(*on_q, -1, 1))
    out << ": the damper force (1.2) has the opposite sign";
  else if (is(*on_p, -1, 1) && (is(*on_q, 1, 0) || is(*on_q, -1, 0)))
    out << ": this is -b * v_p " << (on_q->kappa > 0 ? "+" : "-")
        << " v_q, where b multiplies v_p only; (1.2) needs brackets, -b * (v_p - v_q)";
  else if (std::abs(on_q->kappa) < 1e-12)
    out << ": it ignores v_q";
  else if (std::abs(on_p->kappa) < 1e-12)
    out << ": it ignores v_p";
  return out.str();
}

// Concrete wrong versions of (2.3)-(2.4), each run on every probe before it is named. `spring`
// and `damper` are task 1's functions, so that a mistake of task 1 does not show here.
struct SumMistake {
  std::string words;
  ForceSum sum;
};

std::vector<SumMistake> sum_mistakes(const SpringForce& spring, const DamperForce& damper) {
  using Springs = const std::vector<Spring>&;
  using In = const Vectors&;
  // Each spring's forces on p and q, as a mistake computes them, added (or set) per spring.
  using Pair = std::pair<Vec2, Vec2>;
  using PerSpring = std::function<Pair(const Spring&, In r, In v)>;
  const auto right = [=](const Spring& s, In r, In v) {
    return Vec2(spring(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                damper(v.col(s.p), v.col(s.q), s.b));
  };
  const auto each = [](PerSpring per, std::size_t skip_first, std::size_t skip_last, bool clear,
                       bool assign) {
    return [=](Springs springs, In r, In v, Vectors& force) {
      if (clear) force.setZero();
      for (std::size_t i = skip_first; i + skip_last < springs.size(); ++i) {
        const auto [to_p, to_q] = per(springs[i], r, v);
        const Spring& s = springs[i];
        if (assign) {
          force.col(s.p) = to_p;
          force.col(s.q) = to_q;
        } else {
          force.col(s.p) += to_p;
          force.col(s.q) += to_q;
        }
      }
    };
  };
  const auto ends = [](std::function<Vec2(const Spring&, In, In)> f_pq, double p, double q) {
    return [=](const Spring& s, In r, In v) { return Pair(p * f_pq(s, r, v), q * f_pq(s, r, v)); };
  };
  const auto with = [=](std::function<Vec2(const Spring&, In, In)> f_pq) {
    return ends(f_pq, 1.0, -1.0);
  };
  const PerSpring newton = with(right);
  const SceneParameters lab;  // the lab's values, which a spring of the probes never has
  return {
      {"the forces passed in are lost: `force` was cleared (set to zero) first, where (2.4) adds "
       "to what is already there",
       each(newton, 0, 0, true, false)},
      {"the forces passed in are lost: each end's force is set (=) to its spring's, where (2.4) "
       "adds (+=) to what is already there",
       each(newton, 0, 0, false, true)},
      {"only one end of each spring gets its force: (2.4) adds F_pq to p and -F_pq to q",
       each(ends(right, 1.0, 0.0), 0, 0, false, false)},
      {"only one end of each spring gets its force: (2.4) adds F_pq to p and -F_pq to q",
       each(ends(right, 0.0, -1.0), 0, 0, false, false)},
      {"F_pq is added to both ends with the same sign: (2.4) gives q the opposite force, "
       "F_qp = -F_pq",
       each(ends(right, 1.0, 1.0), 0, 0, false, false)},
      {"the forces have the opposite sign: p gets -F_pq and q gets F_pq, where (2.4) adds F_pq "
       "to p",
       each(ends(right, -1.0, 1.0), 0, 0, false, false)},
      {"the damper's force (1.2) is left out: (2.3) adds it to the spring's",
       each(with([=](const Spring& s, In r, In) {
              return spring(r.col(s.p), r.col(s.q), s.k, s.rest_length);
            }),
            0, 0, false, false)},
      {"the damper's force (1.2) has the opposite sign (its velocities swapped?): (2.3) adds "
       "damper_force(v_p, v_q, b)",
       each(with([=](const Spring& s, In r, In v) {
              return Vec2(spring(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                          damper(v.col(s.q), v.col(s.p), s.b));
            }),
            0, 0, false, false)},
      {"the damper is given the positions r_p, r_q where (2.3) gives it the velocities v_p, v_q",
       each(with([=](const Spring& s, In r, In) {
              return Vec2(spring(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                          damper(r.col(s.p), r.col(s.q), s.b));
            }),
            0, 0, false, false)},
      {"the damper gets the spring's k where (2.3) has b",
       each(with([=](const Spring& s, In r, In v) {
              return Vec2(spring(r.col(s.p), r.col(s.q), s.k, s.rest_length) +
                          damper(v.col(s.p), v.col(s.q), s.k));
            }),
            0, 0, false, false)},
      {"the spring's force (1.1) is left out: (2.3) adds the spring's and the damper's",
       each(with([=](const Spring& s, In, In v) { return damper(v.col(s.p), v.col(s.q), s.b); }), 0,
            0, false, false)},
      {"every spring has the rest length 1 m: use each spring's own rest length (2.3)",
       each(with([=](const Spring& s, In r, In v) {
              return Vec2(spring(r.col(s.p), r.col(s.q), s.k, 1.0) +
                          damper(v.col(s.p), v.col(s.q), s.b));
            }),
            0, 0, false, false)},
      {"every spring gets the lab scene's structural values, k = " + number(lab.structural.k) +
           " N/m, b = " + number(lab.structural.b) +
           " N*s/m and l0 = " + number(lab.structural.rest_length) +
           " m, whatever its own: (2.3) takes each spring's own s.k, s.b and s.rest_length",
       each(with([=](const Spring& s, In r, In v) {
              return Vec2(
                  spring(r.col(s.p), r.col(s.q), lab.structural.k, lab.structural.rest_length) +
                  damper(v.col(s.p), v.col(s.q), lab.structural.b));
            }),
            0, 0, false, false)},
      {"the first spring of the list (springs[0]) gives no force, the others theirs: the loop "
       "starts at 1, where (2.3) sums over every spring",
       each(newton, 1, 0, false, false)},
      {"the last spring of the list gives no force, the others theirs: the loop stops one spring "
       "short",
       each(newton, 0, 1, false, false)},
  };
}

// The first concrete mistake that gives f's forces, to rounding, on every probe: single springs
// with their own k, b and l0 and forces already there, and a list of four springs that share
// particles; "" when none does.
std::string sum_mistake_everywhere(const ForceSum& f, const SpringForce& spring,
                                   const DamperForce& damper) {
  struct Probe {
    std::vector<Spring> springs;
    Vectors r, v, force;
  };
  std::vector<Probe> probes;
  std::mt19937 engine(13);
  std::uniform_real_distribution<double> any(-1.5, 1.5), positive(0.5, 2.0);
  const auto random = [&](int cols) {
    Vectors m(2, cols);
    for (int j = 0; j < cols; ++j)
      m.col(j) = Vec2(any(engine), any(engine));
    return m;
  };
  const auto random_spring = [&](int p, int q) {
    return Spring{p,
                  q,
                  SpringFamily::structural,
                  5.0 + 20.0 * positive(engine),
                  0.05 * positive(engine),
                  positive(engine)};
  };
  for (int trial = 0; trial < 4; ++trial)
    probes.push_back({{random_spring(trial % 2, 1 - trial % 2)}, random(2), random(2), random(2)});
  std::vector<Spring> list;
  for (const auto& [p, q] : {std::pair{0, 1}, std::pair{1, 3}, std::pair{0, 2}, std::pair{2, 3}})
    list.push_back(random_spring(p, q));
  probes.push_back({list, random(4), random(4), Vectors::Zero(2, 4)});
  probes.push_back({list, random(4), random(4), random(4)});
  std::vector<Vectors> got;
  for (const Probe& probe : probes) {
    Vectors force = probe.force;
    f(probe.springs, probe.r, probe.v, force);
    got.push_back(force);
  }
  for (const SumMistake& m : sum_mistakes(spring, damper)) {
    bool everywhere = true;
    for (std::size_t i = 0; i < probes.size() && everywhere; ++i) {
      Vectors force = probes[i].force;
      m.sum(probes[i].springs, probes[i].r, probes[i].v, force);
      everywhere = got[i].allFinite() && (got[i] - force).norm() <= 1e-9 * (1.0 + force.norm());
    }
    if (everywhere) return "likely mistake: " + m.words;
  }
  return "";
}

std::string force_sum_findings(const ForceSum& f, const SpringForce& spring,
                               const DamperForce& damper) {
  if (const std::string named = sum_mistake_everywhere(f, spring, damper); !named.empty())
    return named;
  std::mt19937 engine(9);
  std::uniform_real_distribution<double> any(-1.5, 1.5), positive(0.5, 2.0);
  // One spring between two particles: what each end gets, as α S + β D with S and D the spring's
  // and the damper's forces on p; per trial, for springs whose k, b and l0 differ.
  struct Fitted {
    double alpha, beta;
    bool fits;
  };
  const auto fit = [](const Vec2& got, const Vec2& s, const Vec2& d) {
    Eigen::Matrix2d basis;
    basis << s, d;
    const Eigen::Vector2d c = least_squares(basis, got);
    return Fitted{c[0], c[1], (basis * c - got).norm() <= 1e-9 * (1.0 + got.norm())};
  };
  std::vector<Fitted> on_p, on_q;
  std::vector<Spring> tried;
  Vec2 first_spring = Vec2::Zero(), first_damper = Vec2::Zero();
  Vec2 first_gained_p = Vec2::Zero(), first_gained_q = Vec2::Zero();
  bool cleared = true, added = true;
  for (int trial = 0; trial < 6; ++trial) {
    Spring s{0,
             1,
             SpringFamily::structural,
             5.0 + 20.0 * positive(engine),
             0.05 * positive(engine),
             positive(engine)};
    Vectors r(2, 2), v(2, 2), force(2, 2);
    r << any(engine), any(engine), any(engine), any(engine);
    v << any(engine), any(engine), any(engine), any(engine);
    force << any(engine), any(engine), any(engine), any(engine);
    const Vectors before = force;
    f({s}, r, v, force);
    const Vec2 fs = spring(r.col(0), r.col(1), s.k, s.rest_length);
    const Vec2 fd = damper(v.col(0), v.col(1), s.b);
    const Vec2 gained_p = force.col(0) - before.col(0), gained_q = force.col(1) - before.col(1);
    cleared = cleared && (force.col(0) - fs - fd).norm() <= 1e-9 * (1 + fs.norm() + fd.norm()) &&
              (force.col(1) + fs + fd).norm() <= 1e-9 * (1 + fs.norm() + fd.norm());
    added = added && (gained_p - fs - fd).norm() <= 1e-9 * (1 + fs.norm() + fd.norm()) &&
            (gained_q + fs + fd).norm() <= 1e-9 * (1 + fs.norm() + fd.norm());
    if (trial == 0) {
      first_spring = fs;
      first_damper = fd;
      first_gained_p = gained_p;
      first_gained_q = gained_q;
    }
    on_p.push_back(fit(gained_p, fs, fd));
    on_q.push_back(fit(gained_q, fs, fd));
    tried.push_back(s);
  }
  if (cleared && !added)
    return "likely mistake: the forces passed in are lost: each end's force is set to the "
           "spring's and the damper's, where (2.4) adds to what is already there (the force was "
           "cleared (set to zero) first, or overwritten)";
  if (!added) {
    // The same multiple in every trial, or a multiple that follows the spring's own values.
    using Coefficient = double Fitted::*;
    const auto constant = [](const std::vector<Fitted>& fits, Coefficient c) {
      for (const Fitted& x : fits)
        if (!x.fits || std::abs(x.*c - fits.front().*c) > 1e-7 * (1 + std::abs(x.*c))) return false;
      return true;
    };
    std::vector<std::string> said;
    const auto end_words = [&](const std::vector<Fitted>& fits, const char* end, double sign) {
      if (!fits.front().fits) return;
      if (constant(fits, &Fitted::alpha) && constant(fits, &Fitted::beta)) {
        const double a = fits.front().alpha * sign, b = fits.front().beta * sign;
        if (std::abs(a - 1) < 1e-7 && std::abs(b - 1) < 1e-7) return;
        // Multiples such as 1.003 are measurements, not a formula's: left to the numbers below.
        if (!simple(a) || !simple(b)) return;
        std::ostringstream out;
        out << end << " gets "
            << combination({{fits.front().alpha, "F_spring"}, {fits.front().beta, "F_damper"}})
            << " (with F_spring, F_damper the forces on p "
            << "of (1.1), (1.2)), where (2.3)-(2.4) give " << (sign > 0 ? "" : "-")
            << "(F_spring + F_damper)";
        said.push_back(out.str());
        return;
      }
      // A damper multiple that is one of the spring's own values over b: a value in b's place.
      bool k_for_b = true, unit_rest = true;
      for (std::size_t i = 0; i < fits.size(); ++i) {
        k_for_b = k_for_b && std::abs(fits[i].beta * sign - tried[i].k / tried[i].b) <
                                 1e-6 * tried[i].k / tried[i].b;
        unit_rest = unit_rest && !fits[i].fits;
      }
      if (k_for_b)
        said.push_back(std::string(end) +
                       "'s damper force is k/b times (1.2) for every spring "
                       "tried: the damper gets the spring's k where (2.3) has b");
    };
    end_words(on_p, "p", 1.0);
    end_words(on_q, "q", -1.0);
    if (said.empty()) {
      // The spring's force with another rest length? Springs with l0 other than 1 told apart.
      bool unit_rest = true;
      std::mt19937 again(9);
      for (int trial = 0; trial < 3; ++trial) {
        Spring s{0, 1, SpringFamily::structural, 20.0, 0.0, 1.7};
        Vectors r(2, 2), v = Vectors::Zero(2, 2), force = Vectors::Zero(2, 2);
        r << 0.0, 2.3 + trial, 0.1, -0.4;
        f({s}, r, v, force);
        unit_rest =
            unit_rest && (force.col(0) - spring(r.col(0), r.col(1), s.k, 1.0)).norm() < 1e-9 * 20;
      }
      if (unit_rest)
        said.push_back(
            "on springs of k = 20 N/m without dampers (the ones tried), the forces are those "
            "of rest length 1 m, whatever the spring's own rest length; look at the rest "
            "length (2.3) gives spring_force");
    }
    if (said.empty()) {
      // Nothing exact: the numbers of one spring, in the student's terms.
      const Spring& s = tried.front();
      const Vec2 fs = first_spring, fd = first_damper, want = fs + fd;
      std::ostringstream out;
      out << "likely mistake: one spring alone (k = " << number(s.k) << " N/m, b = " << number(s.b)
          << " N*s/m, l0 = " << number(s.rest_length) << " m) changes p's force by ("
          << number(first_gained_p.x()) << ", " << number(first_gained_p.y()) << ") N and q's by ("
          << number(first_gained_q.x()) << ", " << number(first_gained_q.y())
          << ") N, where (2.3)-(2.4) give p F_spring + F_damper = (" << number(want.x()) << ", "
          << number(want.y()) << ") N and q the opposite (F_spring = (" << number(fs.x()) << ", "
          << number(fs.y()) << "), F_damper = (" << number(fd.x()) << ", " << number(fd.y())
          << ")); look at what each term of (2.3) is given";
      return out.str();
    }
    std::string text = "likely mistake: ";
    for (std::size_t i = 0; i < said.size(); ++i)
      text += (i == 0 ? "" : "; ") + said[i];
    return text;
  }
  // Each spring right alone: is every spring of a list counted?
  std::vector<Spring> springs;
  Vectors r(2, 4), v(2, 4);
  r << 0.0, 1.1, 0.1, 1.3, 0.0, 0.2, 1.0, 0.9;
  v << 0.3, -0.2, 0.1, 0.0, -0.4, 0.5, 0.2, -0.1;
  for (const auto& [p, q] : {std::pair{0, 1}, std::pair{1, 3}, std::pair{0, 2}, std::pair{2, 3}})
    springs.push_back({p, q, SpringFamily::structural, 20.0, 0.1, 1.0});
  Vectors got = Vectors::Zero(2, 4);
  f(springs, r, v, got);
  const auto contribution = [&](const Spring& s) {
    Vectors c = Vectors::Zero(2, 4);
    const Vec2 pq =
        spring(r.col(s.p), r.col(s.q), s.k, s.rest_length) + damper(v.col(s.p), v.col(s.q), s.b);
    c.col(s.p) += pq;
    c.col(s.q) -= pq;
    return c;
  };
  Vectors all = Vectors::Zero(2, 4);
  for (const Spring& s : springs)
    all += contribution(s);
  if ((got - all).norm() <= 1e-9 * (1 + all.norm())) return "";
  for (std::size_t i = 0; i < springs.size(); ++i)
    if ((got - all + contribution(springs[i])).norm() <= 1e-9 * (1 + all.norm()))
      return "likely mistake: spring " + std::to_string(i) + " of the " +
             std::to_string(springs.size()) + " in the list gives no force, the others theirs" +
             (i + 1 == springs.size() ? ": the loop misses the last spring" : "");
  return "likely mistake: every spring alone gives its ends the right forces, but a list of "
         "several sums to something else: what one spring adds must stay when the next is added";
}

// Three copies of one particle stepped together with one constant acceleration must move alike:
// "" when they do, else which of them the step left where they were. Run before the probes below,
// whose one particle would hide a loop that misses some particles (or, looping over the rows,
// reach past the last column).
std::string particles_alike(const EulerStep& step, double h, const Vec2& A) {
  const Vectors r0 = Vec2(1.0, 2.0).replicate(1, 3), v0 = Vec2(0.5, 0.25).replicate(1, 3);
  Vectors r = r0, v = v0;
  const auto constant = [&](const Vectors& at, const Vectors&) -> const Vectors& {
    static Vectors a;
    a = A.replicate(1, at.cols());
    return a;
  };
  step(constant, h, r, v);
  std::vector<std::string> still, moved;
  for (int i = 0; i < 3; ++i)
    (r.col(i) == r0.col(i) && v.col(i) == v0.col(i) ? still : moved).push_back(std::to_string(i));
  const auto listed = [](const std::vector<std::string>& items) {
    std::string text;
    for (std::size_t i = 0; i < items.size(); ++i)
      text += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
    return text;
  };
  if (!still.empty() && !moved.empty())
    return "likely mistake: three particles with the same r0, v0 and a: the step moved particle" +
           std::string(moved.size() == 1 ? " " : "s ") + listed(moved) + " and left particle" +
           (still.size() == 1 ? " " : "s ") + listed(still) +
           (still.size() == 1 ? " where it was" : " where they were") +
           " (r1 = r0, v1 = v0): every particle takes the step, all r.cols() of them";
  for (int i = 1; i < 3; ++i)
    if ((r.col(i) - r.col(0)).norm() > 1e-12 || (v.col(i) - v.col(0)).norm() > 1e-12)
      return "likely mistake: three particles with the same r0, v0 and a moved differently "
             "(particle " +
             std::to_string(i) + " unlike particle 0): every particle takes the same step";
  return "";
}

std::string euler_step_findings(const EulerStep& step) {
  const double h = 0.1;
  if (std::string alike = particles_alike(step, h, Vec2(0.3, -0.8)); !alike.empty()) return alike;
  int calls = 0;
  Vectors evaluated_r, evaluated_v;
  // a = A, constant: r1 = ρ r0 + α h v0 + β h² A, v1 = v0 + γ h A + δ v0.
  const Vec2 A(0.3, -0.8);
  const auto constant = [&](const Vectors& r, const Vectors& v) -> const Vectors& {
    ++calls;
    evaluated_r = r;
    evaluated_v = v;
    static Vectors a;
    a = A.replicate(1, r.cols());
    return a;
  };
  Vectors r(2, 1), v(2, 1);
  r << 1.0, 2.0;
  v << 0.5, 0.25;
  const Vectors r0 = r, v0 = v;
  step(constant, h, r, v);
  const int calls_a = calls;
  // With A = 0 the motion alone: α, δ.
  Vectors r_still = r0, v_still = v0;
  const auto none = [&](const Vectors& rr, const Vectors&) -> const Vectors& {
    static Vectors a;
    a = Vectors::Zero(2, rr.cols());
    return a;
  };
  step(none, h, r_still, v_still);
  // At rest, with A = 0: what is left of r0 (ρ, 1 in (1.4)).
  Vectors r_rest = r0, v_rest = Vectors::Zero(2, 1);
  step(none, h, r_rest, v_rest);
  const double rho = r_rest.col(0).dot(r0.col(0)) / r0.col(0).squaredNorm();
  const double alpha = (r_still - rho * r0).col(0).dot(v0.col(0)) / (h * v0.col(0).squaredNorm());
  const double delta = (v_still - v0).col(0).dot(v0.col(0)) / v0.col(0).squaredNorm();
  const double beta = (r - r_still).col(0).dot(A) / (h * h * A.squaredNorm());
  const double gamma = (v - v_still).col(0).dot(A) / (h * A.squaredNorm());
  // The law r1 = ρ r0 + α h v0 + β h² a, v1 = (1 + δ) v0 + γ h a must give every output, each
  // component: a step that moves x alone, say, fits no such law, and its numbers are said as
  // they are.
  const auto off = [](const Vectors& got, const Vec2& law) { return (got.col(0) - law).norm(); };
  const double misfit = std::max(
      {off(r_rest, rho * r0.col(0)), off(r_still, rho * r0.col(0) + alpha * h * v0.col(0)),
       off(r, rho * r0.col(0) + alpha * h * v0.col(0) + beta * h * h * A),
       off(v_still, (1 + delta) * v0.col(0)), off(v, (1 + delta) * v0.col(0) + gamma * h * A)});
  if (misfit > 1e-12 * (1.0 + r0.norm() + v0.norm())) {
    const auto vec = [](const Vectors& x) { return vec2_text(x.col(0)); };
    return "measured: with r0 = " + vec(r0) + " m, v0 = " + vec(v0) + " m/s, h = " + number(h) +
           " s and a constant a = " + vec2_text(A) + " m/s^2 the step gives r1 = " + vec(r) +
           " and v1 = " + vec(v) + ", where (1.4)-(1.5) give r1 = " + vec(r0 + h * v0) +
           " and v1 = " + vec2_text(v0.col(0) + h * A) +
           "; no law r1 = r0 + α h v0 + β h^2 a fits it in both "
           "x and y: look at each component of (1.4) and (1.5)";
  }
  std::vector<std::string> said;
  if (calls_a != 1)
    said.push_back("the step evaluated the acceleration " + std::to_string(calls_a) +
                   " times, where (1.4)-(1.5) need it once, at the start of the step");
  if (!near(rho, 1.0) || !near(alpha, 1.0) || !near(beta, 0.0) || !near(gamma, 1.0) ||
      !near(delta, 0.0)) {
    std::ostringstream out;
    out << "with a constant acceleration a the step gives r1 = "
        << combination({{rho, "r0"}, {alpha, "h v0"}, {beta, "h^2 a"}})
        << " and v1 = " << combination({{1.0 + delta, "v0"}, {gamma, "h a"}})
        << ", where (1.4)-(1.5) give r1 = r0 + h v0 and v1 = v0 + h a";
    if (std::abs(rho) < 1e-12 && near(alpha, 1.0) && near(beta, 0.0))
      out << ": r0 is lost, the position is set to h v0 (r = h v where (1.4) has r += h v)";
    else if (near(rho, 1.0) && near(alpha, 1.0) && near(beta, 1.0) && near(gamma, 1.0))
      out << ": the position moved with the new velocity v1 (the state updated in the wrong "
             "order)";
    else if (near(alpha, 1.0) && near(beta, 0.5) && near(gamma, 1.0))
      out << ": the position has an extra h^2 a / 2";
    else if (near(alpha, 1.0) && near(beta, 0.0) && near(gamma, 1.0) && near(delta, -1.0))
      out << ": v0 is lost, the velocity is set to h a (v = h a where (1.5) has v += h a)";
    said.push_back(out.str());
  }
  // Where a was evaluated: the constant model saw the r and v it was called with, so this is
  // read, not inferred from v1 (which another mistake may have changed).
  if (calls_a == 1 && evaluated_r.cols() == 1 &&
      ((evaluated_r - r0).norm() > 1e-12 || (evaluated_v - v0).norm() > 1e-12)) {
    const Vec2 moved = (evaluated_r - r0).col(0), sped = (evaluated_v - v0).col(0);
    const double at = moved.dot(v0.col(0)) / (h * v0.col(0).squaredNorm());
    std::ostringstream out;
    out << "the acceleration was evaluated at r = (" << number(evaluated_r(0, 0)) << ", "
        << number(evaluated_r(1, 0)) << "), v = (" << number(evaluated_v(0, 0)) << ", "
        << number(evaluated_v(1, 0)) << "), where (1.5) takes it at the start of the step, r0 = ("
        << number(r0(0, 0)) << ", " << number(r0(1, 0)) << "), v0 = (" << number(v0(0, 0)) << ", "
        << number(v0(1, 0)) << ")";
    // Named only when the step is otherwise right: a(r0 + h v0, v0) after r += h v0.
    const bool after_move = sped.norm() <= 1e-12 && (moved - h * v0.col(0)).norm() <= 1e-12 &&
                            near(alpha, 1.0) && near(beta, 0.0) && near(gamma, 1.0) &&
                            near(delta, 0.0);
    if (after_move)
      out << ": r0 + h v0, the new position (your step evaluated the acceleration after moving "
             "the positions)";
    else if (moved.norm() > 1e-12 && (moved - at * h * v0.col(0)).norm() <= 1e-12)
      out << ": r0 + " << number(at) << " h v0";
    said.push_back(out.str());
  }
  const bool exact = simple(rho) && simple(alpha) && simple(beta) && simple(gamma) && simple(delta);
  if (said.empty()) return "";
  return exact || calls_a != 1 ? likely_mistake(said) : measured(said);
}

std::string verlet_step_findings(const VerletStep& step) {
  const double h = 0.05;
  const Vec2 A(0.4, -1.2);
  Vectors acceleration_storage;
  const auto constant = [&](const Vec2& a) {
    return [&, a](const Vectors& r, const Vectors&) -> const Vectors& {
      acceleration_storage = a.replicate(1, r.cols());
      return acceleration_storage;
    };
  };
  // A step from history (r_{n-1}, r_n) with velocity guess v: returns r_{n+1}, the velocity back
  // and what history keeps.
  struct After {
    Vec2 r, v, kept;
    bool has_previous;
  };
  const auto from = [&](const Vec2& r_previous, const Vec2& r_now, const Vec2& v_now,
                        const AccelerationFunction& a) {
    Vectors r(2, 1), v(2, 1);
    r.col(0) = r_now;
    v.col(0) = v_now;
    VerletHistory history{true, r_previous.replicate(1, 1)};
    step(a, h, r, v, history);
    return After{r.col(0), v.col(0),
                 history.previous_position.cols() == 1 ? Vec2(history.previous_position.col(0))
                                                       : Vec2::Constant(std::nan("")),
                 history.has_previous};
  };
  const Vec2 e(1.0, 0.0), zero = Vec2::Zero();
  const After p1 = from(zero, e, zero, constant(zero));  // r_{n+1} = α e
  const After p2 = from(e, zero, zero, constant(zero));  // r_{n+1} = β e
  const After p3 = from(zero, zero, zero, constant(A));  // r_{n+1} = γ h² A
  const double alpha = p1.r.x(), beta = p2.r.x(), gamma = p3.r.dot(A) / (h * h * A.squaredNorm());
  std::vector<std::string> said;
  bool exact = true;  // every coefficient said is a simple value (h a for h^2 a counts)
  if (!near(alpha, 2.0) || !near(beta, -1.0) || !near(gamma, 1.0)) {
    std::ostringstream out;
    out << "without dampers, from r_{n-1} and r_n, the step gives r_{n+1} = "
        << combination({{alpha, "r_n"}, {beta, "r_{n-1}"}, {gamma, "h^2 a"}})
        << ", where (4.1) has 2 r_n - r_{n-1} + h^2 a";
    if (near(alpha, -1.0) && near(beta, 2.0)) out << ": r_n and r_{n-1} are swapped";
    if (near(gamma, 1.0 / h)) out << ": r_{n+1} has h a where (4.1) has h^2 a";
    exact = simple(alpha) && simple(beta) && (simple(gamma) || near(gamma, 1.0 / h));
    said.push_back(out.str());
  }
  // The velocity handed back, (4.4): (λ1 r_{n+1} + λ2 r_n + λ3 r_{n-1}) / (2h).
  if (said.empty()) {
    // p3: r_{n+1} = h² A, r_n = r_{n-1} = 0: v = λ1 h² A / (2h) -> λ1.
    const double l1 = p3.v.dot(A) * 2 * h / (h * h * A.squaredNorm());
    // p1: r_{n+1} = 2 e, r_n = e: v = (2 λ1 + λ2) e / (2h); p2: r_{n+1} = -e, r_{n-1} = e.
    const double l2b = p1.v.x() * 2 * h - 2 * l1;
    const double l3 = p2.v.x() * 2 * h + l1;
    if (!near(l1, 3.0) || !near(l2b, -4.0) || !near(l3, 1.0)) {
      std::ostringstream out;
      out << "the velocity handed back is ("
          << combination({{l1, "r_{n+1}"}, {l2b, "r_n"}, {l3, "r_{n-1}"}})
          << ") / (2h), where (4.4) has (3 r_{n+1} - 4 r_n + r_{n-1}) / (2h)";
      exact = exact && simple(l1) && simple(l2b) && simple(l3);
      said.push_back(out.str());
    }
    if ((p1.kept - e).norm() > 1e-12)
      said.push_back("after the step the history holds (" + number(p1.kept.x()) + ", " +
                     number(p1.kept.y()) +
                     ") where it must hold r_n, the r_{n-1} of the next step");
    if (!p1.has_previous)
      said.push_back(
          "after a step the history's has_previous is false, so every step starts "
          "again from (4.3) instead of using r_{n-1}");
  }
  // The first step: r_1 = r_0 + μ h v_0 + ν h² a, where (4.3) gives μ = 1, ν = 1/2.
  if (said.empty()) {
    Vectors r(2, 1), v(2, 1);
    r.col(0) = zero;
    v.col(0) = Vec2(0.0, 1.0);
    VerletHistory history;
    step(constant(A), h, r, v, history);
    const Vec2 moved = r.col(0);
    // Split the move along v_0 = (0, 1) and along A: two unknowns, two components.
    Eigen::Matrix2d basis;
    basis << Vec2(0.0, h), Vec2(h * h * A);
    const Eigen::Vector2d c = least_squares(basis, moved);
    if (!near(c[0], 1.0) || !near(c[1], 0.5)) {
      std::ostringstream out;
      out << "the first step (no history) moves r_0 by "
          << combination({{c[0], "h v_0"}, {c[1], "h^2 a"}})
          << ", where (4.3) with (4.1) gives h v_0 + h^2 a / 2";
      if (near(c[0], 0.0) && near(c[1], 1.0))
        out << ": r_{-1} = r_0, as if at rest";
      else if (near(c[0], -1.0))
        out << ": (4.3) steps forwards in time";
      else if (near(c[0], 1.0) && near(c[1], 1.0))
        out << ": the h^2/2 a(r_0, v_0) term of (4.3) is missing";
      exact = exact && simple(c[0]) && simple(c[1]);
      said.push_back(out.str());
    }
  }
  // With dampers only, a = -c v: solved with v_n = (r_{n+1} - r_{n-1}) / (κ h), κ = 2 in (4.2).
  if (said.empty()) {
    double c = 2.0;
    int evaluations = 0;
    const AccelerationFunction damped = [&](const Vectors& r, const Vectors& v) -> const Vectors& {
      ++evaluations;
      acceleration_storage = -c * v + 0.0 * r;
      return acceleration_storage;
    };
    // The velocity the dampers saw, (λ r_{n+1} + ν r_n + μ r_{n-1}) / (2h), from (4.1) with a =
    // -c v: the step is r_{n+1} = α r_n + β r_{n-1}, so one c gives two equations (the r_n and
    // r_{n-1} parts): λ α + ν = 2 (2 - α) / (h c) and λ β + μ = 2 (-1 - β) / (h c). Two values
    // of c give λ, ν and μ, and a third equation that checks them.
    const Vec2 r_now(0.1, 0.0), guess(5.0, 0.0);
    struct Step {
      double alpha, beta, on_now, on_previous;  // the step, and the right-hand sides above
    };
    int evaluations_first = 0;
    double first_r = 0.0;
    const auto step_at = [&](double damping) {
      c = damping;
      const After d0 = from(Vec2::Zero(), r_now, guess, damped);
      if (evaluations_first == 0) evaluations_first = evaluations, first_r = d0.r.x();
      const After d1 = from(Vec2(0.03, 0.0), r_now, guess, damped);
      const double on_r = d0.r.x() / r_now.x(), on_prev = (d1.r.x() - d0.r.x()) / 0.03;
      return Step{on_r, on_prev, 2.0 * (2.0 - on_r) / (h * damping),
                  2.0 * (-1.0 - on_prev) / (h * damping)};
    };
    const Step one = step_at(2.0), two = step_at(5.0);
    c = 2.0;
    const double lambda = (one.on_now - two.on_now) / (one.alpha - two.alpha);
    const double nu = one.on_now - lambda * one.alpha;
    const double mu = one.on_previous - lambda * one.beta;
    const bool consistent =
        std::abs(two.on_previous - lambda * two.beta - mu) <= 1e-6 * (1 + std::abs(mu));
    const double one_evaluation = 2 * r_now.x() - h * h * 2.0 * guess.x();
    if (std::abs(first_r - one_evaluation) <= 1e-12 && evaluations_first == 1)
      said.push_back(
          "with dampers the step evaluated a once, with the velocity passed in: the "
          "iteration of section 4 is missing or stops too early");
    else if (!consistent) {
      // No one combination: a fit at one damping would print a law the code does not follow.
      said.push_back(
          "with dampers, the velocity the dampers saw is no single (λ r_{n+1} + ν r_n + μ "
          "r_{n-1}) / (2h) at two dampings (c = 2 and 5 1/s), as it would be once (4.1)-(4.2) "
          "have settled");
      exact = false;
    } else if (!near(lambda, 1.0) || !near(mu, -1.0) || std::abs(nu) > 1e-9) {
      std::ostringstream out;
      out << "with dampers, (4.1) holds with a velocity ("
          << combination({{lambda, "r_{n+1}"}, {nu, "r_n"}, {mu, "r_{n-1}"}})
          << ") / (2h) in the damper force, where (4.2) has (r_{n+1} - r_{n-1}) / (2h)";
      if (near(lambda, 1.0) && near(nu, -1.0) && std::abs(mu) <= 1e-9)
        out << ": r_n is used where (4.2) has r_{n-1}";
      exact = exact && simple(lambda) && simple(mu) && (std::abs(nu) <= 1e-9 || simple(nu));
      said.push_back(out.str());
    }
  }
  return exact ? likely_mistake(said) : measured(said);
}

std::string gravity_findings(const GravitySum& f) {
  Eigen::VectorXd mass(4);
  mass << 0.2, 0.5, 1.0, 2.0;
  const Vec2 g(0.3, -9.81);
  Vectors before(2, 4);
  before << 0.5, -1.0, 2.0, 0.0, 1.5, 0.25, -0.5, 3.0;
  Vectors force = before;
  f(mass, g, force);
  if (!force.allFinite()) return "likely mistake: the forces are not finite after add_gravity";
  std::vector<double> multiple(4);
  bool along_g = true, lost = true;
  for (int i = 0; i < 4; ++i) {
    const Vec2 added = force.col(i) - before.col(i);
    const double c = added.dot(g) / (mass[i] * g.squaredNorm());
    along_g = along_g && (added - c * mass[i] * g).norm() <= 1e-9 * (1 + added.norm());
    multiple[std::size_t(i)] = c;
    lost = lost && (force.col(i) - mass[i] * g).norm() <= 1e-9 * (1 + mass[i] * g.norm());
  }
  if (lost)
    return "likely mistake: each force is set to m_i g: the forces already there are lost; "
           "gravity is added to the force, equation (5.2): F_i += m_i g";
  if (!along_g)
    return "likely mistake: what add_gravity adds is not along g for every particle: gravity "
           "points along g, m_i g (5.2)";
  bool without_mass = true, same = true;
  for (int i = 0; i < 4; ++i) {
    without_mass = without_mass && near(multiple[std::size_t(i)] * mass[i], 1.0);
    same = same && near(multiple[std::size_t(i)], multiple[0]);
  }
  if (same && near(multiple[0], 1.0)) return "";
  if (without_mass)
    return "likely mistake: each particle gets g, not m_i g, on particles of 0.2 to 2 kg: "
           "gravity is m·g per particle, equation (5.2): the mass m_i is missing";
  if (same)
    return "likely mistake: each particle gets " + number(multiple[0]) +
           " m_i g, on particles of 0.2 to 2 kg, where (5.2) adds m_i g" +
           (near(multiple[0], -1.0)  ? std::string(": gravity points along g, not against it")
            : near(multiple[0], 2.0) ? std::string(": gravity is added twice")
                                     : std::string());
  std::string text = "likely mistake: the multiples of m_i g added differ between particles:";
  for (int i = 0; i < 4; ++i)
    text += " " + number(multiple[std::size_t(i)]);
  return text + " (m = 0.2, 0.5, 1, 2 kg), where (5.2) adds m_i g to each";
}

std::string wind_findings(const WindSum& f) {
  WindParameters parameters;
  parameters.enabled = true;
  parameters.direction = Vec2(1.0, 0.4);
  parameters.drag = 0.37;  // not the lab's 0.1, so that a value of its own shows
  const WindField wind(parameters);
  const double c = wind.drag();
  // What add_wind adds to one particle at r, moving with v, at time t.
  const auto added = [&](const Vec2& r, const Vec2& v, double t) {
    Vectors rr(2, 1), vv(2, 1), force = Vectors::Zero(2, 1);
    rr.col(0) = r;
    vv.col(0) = v;
    f(wind, t, rr, vv, force);
    return Vec2(force.col(0));
  };
  const Vec2 r(1.5, -0.7);
  const double t = 2.7;
  const Vec2 w = wind.velocity(t, r);
  const Vec2 at_rest = added(r, Vec2::Zero(), t);
  if (!at_rest.allFinite()) return "likely mistake: the wind's force is not a finite number";
  // Its change with the velocity: per component, and whether twice the velocity gives twice.
  const Vec2 dx = added(r, Vec2::UnitX(), t) - at_rest, dy = added(r, Vec2::UnitY(), t) - at_rest;
  const Vec2 dx2 = added(r, 2.0 * Vec2::UnitX(), t) - at_rest;
  std::vector<std::string> said;
  const bool linear = (dx2 - 2.0 * dx).norm() <= 1e-9 * (1.0 + dx.norm());
  if (!linear) {
    said.push_back(
        "what it adds does not change in proportion to the velocity (v = 1 and 2 m/s "
        "along x change it by " +
        number(-dx.x()) + " and " + number(-dx2.x()) +
        " N), where (5.3), c (w - v_i), is linear in v_i");
  } else {
    const bool isotropic =
        std::abs(dx.y()) < 1e-12 && std::abs(dy.x()) < 1e-12 && std::abs(dx.x() - dy.y()) < 1e-12;
    if (!isotropic) {
      said.push_back("a velocity along x changes it by (" + number(dx.x()) + ", " + number(dx.y()) +
                     ") N per m/s and one along y by (" + number(dy.x()) + ", " + number(dy.y()) +
                     "), where (5.3) gives (-c, 0) and (0, -c), c = " + number(c) +
                     (std::abs(dy.y()) < 1e-12 ? ": it is blind to the vertical velocity" : ""));
    } else if (!near(-dx.x(), c)) {
      said.push_back("its coefficient of the velocity is " + number(-dx.x()) +
                     " N*s/m where the wind's own drag is c = " + number(c) +
                     " (the wind's drag is this wind's own c = wind.drag())");
    }
  }
  // The part that does not depend on v: c w(t, r_i), at the particle's own place and time.
  if (said.empty() && (at_rest - c * w).norm() > 1e-9 * (1.0 + c * w.norm())) {
    const Vec2 elsewhere = added(r + Vec2(3.0, 1.0), Vec2::Zero(), t);
    const Vec2 later = added(r, Vec2::Zero(), t + 1.3);
    std::string what = "with the particle at rest it adds (" + number(at_rest.x()) + ", " +
                       number(at_rest.y()) + ") N where (5.3) adds c w(t, r_i) = (" +
                       number(c * w.x()) + ", " + number(c * w.y()) + ")";
    if ((elsewhere - at_rest).norm() < 1e-12 && (later - at_rest).norm() < 1e-12)
      what +=
          ": the same at every place and time (the wind blows at each particle's own place "
          "and time, equation (5.4))";
    else if ((at_rest + c * w).norm() < 1e-9 * (1 + c * w.norm()))
      what += ": the drag pulls a particle towards the wind's velocity, the wrong way";
    said.push_back(what);
  }
  return likely_mistake(said);
}

std::string pins_findings(const PinHold& f) {
  const std::vector<bool> pinned = {true, false, false, true, true, false, true};
  Vectors a(2, 7);
  a << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, -1.0, -2.0, -3.0, -4.0, -5.0, -6.0, -7.0;
  const Vectors before = a;
  f(pinned, a);
  std::vector<int> kept_pinned, zeroed_free, one_component;
  for (int i = 0; i < 7; ++i) {
    const bool zero = a.col(i).isZero(0.0), same = a.col(i) == before.col(i);
    if (pinned[std::size_t(i)] && !zero)
      (a(0, i) == 0.0 || a(1, i) == 0.0 ? one_component : kept_pinned).push_back(i);
    if (!pinned[std::size_t(i)] && !same) zeroed_free.push_back(i);
  }
  if (kept_pinned.empty() && zeroed_free.empty() && one_component.empty()) return "";
  const auto list = [](const std::vector<int>& items) {
    std::string text;
    for (const int i : items)
      text += (text.empty() ? "" : ", ") + std::to_string(i);
    return text;
  };
  std::vector<std::string> said;
  if (!kept_pinned.empty())
    said.push_back("pinned particles " + list(kept_pinned) + " keep their acceleration");
  if (!one_component.empty())
    said.push_back("pinned particles " + list(one_component) + " have one component set to 0 only");
  if (!zeroed_free.empty())
    said.push_back("free particles " + list(zeroed_free) + " are changed too");
  std::string text = "likely mistake: with particles 0, 3, 4 and 6 of 7 pinned, ";
  for (std::size_t i = 0; i < said.size(); ++i)
    text += (i == 0 ? "" : "; ") + said[i];
  return text + ", where (5.5) sets a_i = 0 for a pinned particle and leaves the others";
}

// A probe calls the student's function on inputs of its own: whatever it throws there is a fact
// measured, never an exception that would change the test's verdict.
std::string guarded(const std::string& function, const std::function<std::string()>& probe) {
  try {
    return probe();
  } catch (...) {
    return "likely mistake: while probing it on inputs of the kit's own, your " + function +
           " threw " + current_exception_text();
  }
}

}  // namespace

std::string probe_spring_force(const SpringForce& f) {
  return guarded("spring_force", [&] { return spring_force_findings(f); });
}

std::string probe_damper_force(const DamperForce& f) {
  return guarded("damper_force", [&] { return damper_force_findings(f); });
}

std::string probe_force_sum(const ForceSum& f, const SpringForce& spring,
                            const DamperForce& damper) {
  return guarded("accumulate_spring_forces", [&] { return force_sum_findings(f, spring, damper); });
}

std::string probe_euler_step(const EulerStep& step) {
  return guarded("explicit_euler_step", [&] { return euler_step_findings(step); });
}

std::string probe_verlet_step(const VerletStep& step) {
  return guarded("verlet_step", [&] { return verlet_step_findings(step); });
}

std::string probe_gravity(const GravitySum& f) {
  return guarded("add_gravity", [&] { return gravity_findings(f); });
}

std::string probe_wind(const WindSum& f) {
  return guarded("add_wind", [&] { return wind_findings(f); });
}

std::string probe_pins(const PinHold& f) {
  return guarded("hold_pinned", [&] { return pins_findings(f); });
}

}  // namespace springlab::testing
