#include "gui/scene_drawing.hpp"

#include "gui/pixel_canvas.hpp"

#include <SFML/Graphics/Vertex.hpp>
#include <SFML/Graphics/VertexArray.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numbers>
#include <vector>

namespace springlab::view {
namespace {

// Springs are thick lines drawn by OpenGL up to this many; beyond, hairlines drawn in memory.
constexpr std::size_t thick_spring_limit = 5000;
constexpr int square_dot_limit = 2000;  // particles beyond which dots are drawn as squares

sf::Color mix(sf::Color a, sf::Color b, double t) {
  const auto channel = [t](std::uint8_t x, std::uint8_t y) {
    return static_cast<std::uint8_t>(std::lround(double(x) + (double(y) - double(x)) * t));
  };
  return {channel(a.r, b.r), channel(a.g, b.g), channel(a.b, b.b), channel(a.a, b.a)};
}

sf::Color strain_colour(double strain, double scale) {
  const double t = std::clamp(strain / scale, -1.0, 1.0);
  return t >= 0 ? mix(colour::at_rest, colour::stretched, t)
                : mix(colour::at_rest, colour::compressed, -t);
}

double strain_of(const Spring& s, const Vectors& r) {
  return ((r.col(s.p) - r.col(s.q)).norm() - s.rest_length) / s.rest_length;
}

sf::Color faded(sf::Color c, bool ghost) {
  return ghost ? sf::Color(colour::ghost.r, colour::ghost.g, colour::ghost.b, 110) : c;
}

bool finite(sf::Vector2f p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// A segment `width` pixels wide as two triangles.
void add_segment(std::vector<sf::Vertex>& triangles, sf::Vector2f a, sf::Vector2f b, float width,
                 sf::Color c) {
  const sf::Vector2f d = b - a;
  const float length = std::hypot(d.x, d.y);
  if (!(length > 0.0f)) return;
  const sf::Vector2f n(-d.y / length * width / 2, d.x / length * width / 2);
  for (sf::Vector2f p : {a + n, a - n, b + n, b + n, a - n, b - n})
    triangles.push_back({p, c});
}

// A dot as an octagon (fan of triangles), or a pinned particle as a square (two triangles).
// Large grids draw every particle as a square: an octagon costs four times the vertices, which
// software OpenGL feels at 10,000 particles, and at a few pixels the two look alike.
void add_dot(std::vector<sf::Vertex>& triangles, sf::Vector2f centre, float radius, bool square,
             sf::Color c) {
  static const auto octagon = [] {
    std::array<sf::Vector2f, 9> corners;
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const double a = 2 * std::numbers::pi * double(k) / 8;
      corners[k] = {float(std::cos(a)), float(std::sin(a))};
    }
    return corners;
  }();
  if (square) {
    const sf::Vector2f a = centre + sf::Vector2f(-radius, -radius);
    const sf::Vector2f b = centre + sf::Vector2f(radius, -radius);
    const sf::Vector2f d = centre + sf::Vector2f(-radius, radius);
    const sf::Vector2f e = centre + sf::Vector2f(radius, radius);
    for (sf::Vector2f p : {a, b, d, d, b, e})
      triangles.push_back({p, c});
    return;
  }
  for (std::size_t k = 0; k < 8; ++k) {
    triangles.push_back({centre, c});
    triangles.push_back({centre + octagon[k] * radius, c});
    triangles.push_back({centre + octagon[k + 1] * radius, c});
  }
}

void add_arrow(std::vector<sf::Vertex>& triangles, sf::Vector2f from, sf::Vector2f to, float width,
               sf::Color c) {
  const sf::Vector2f d = to - from;
  const float length = std::hypot(d.x, d.y);
  if (!(length > 2.0f)) return;
  const sf::Vector2f u = d / length, n(-u.y, u.x);
  const float head = std::min(length / 2, 4.0f * width + 4.0f);
  const sf::Vector2f base = to - u * head;
  add_segment(triangles, from, base, width, c);
  for (sf::Vector2f p : {to, base + n * (head / 2), base - n * (head / 2)})
    triangles.push_back({p, c});
}

// The spring and damper force on particle `at` from spring s (N).
Vec2 force_of(const Implementation& impl, const Spring& s, const Vectors& r, const Vectors& v,
              int at) {
  const int other = s.p == at ? s.q : s.p;
  return impl.spring_force(r.col(at), r.col(other), s.k, s.rest_length) +
         impl.damper_force(v.col(at), v.col(other), s.b);
}

// The strain colours, from fully compressed (index 0) through at rest (strain_steps) to fully
// stretched (2 strain_steps): one look-up a spring instead of a blend of three channels.
constexpr int strain_steps = 255;
template <class Colour>
using StrainTable = std::array<Colour, 2 * strain_steps + 1>;
using StrainColours = StrainTable<std::uint32_t>;

// The table's colours as SFML's, for vertices (the surface).
const StrainTable<sf::Color>& strain_vertex_colours(bool ghost) {
  static const auto make = [](bool faint) {
    StrainTable<sf::Color> table;
    for (int k = -strain_steps; k <= strain_steps; ++k)
      table[std::size_t(k + strain_steps)] =
          faded(strain_colour(double(k) / strain_steps, 1.0), faint);
    return table;
  };
  static const StrainTable<sf::Color> solid = make(false), faint = make(true);
  return ghost ? faint : solid;
}

// The same colours packed for the canvas (the hairlines).
const StrainColours& strain_colours(bool ghost) {
  static const auto make = [](bool faint) {
    StrainColours table;
    const StrainTable<sf::Color>& colours = strain_vertex_colours(faint);
    for (std::size_t k = 0; k < table.size(); ++k)
      table[k] = PixelCanvas::packed(colours[k]);
    return table;
  };
  static const StrainColours solid = make(false), faint = make(true);
  return ghost ? faint : solid;
}

// A strain's index in the tables: clamped first, so the cast is safe; adding ±0.5 rounds without
// a call into libm. NaN is drawn as at rest.
std::size_t strain_index(double strain, double per_step) {
  const double k = std::isnan(strain)
                       ? 0.0
                       : std::clamp(strain * per_step, -double(strain_steps), double(strain_steps));
  return std::size_t(int(k + (k >= 0 ? 0.5 : -0.5)) + strain_steps);
}

// Large scenes: hairlines and square dots written into memory (pixel_canvas.hpp), each particle
// taken to the screen once rather than once for every spring it ends.
DrawCounts draw_in_memory(sf::RenderTarget& target, const RunState& run, const Camera& camera,
                          const DrawOptions& options) {
  static std::vector<sf::Vector2f> screen;  // reused from frame to frame
  static PixelCanvas canvas;
  const Simulation& sim = *run.sim;
  const Vectors& r = run.position;
  const int particles = int(r.cols());
  const float radius = particle_radius(camera, sim.parameters().spacing);
  const float reach = radius * 1.8f + 1.0f;  // the largest dot's half-width, and rounding
  screen.resize(std::size_t(particles));
  const Viewport& view = camera.viewport();
  sf::Vector2f low(view.left + view.width, view.top + view.height), high(view.left, view.top);
  for (int i = 0; i < particles; ++i) {
    const sf::Vector2f at = screen[std::size_t(i)] = camera.to_screen(r.col(i));
    if (!finite(at)) continue;
    low = {std::min(low.x, at.x - reach), std::min(low.y, at.y - reach)};
    high = {std::max(high.x, at.x + reach), std::max(high.y, at.y + reach)};
  }
  // Only what the scene covers of the viewport: springs join particles, so none reaches beyond.
  low = {std::max(low.x, view.left), std::max(low.y, view.top)};
  high = {std::min(high.x, view.left + view.width), std::min(high.y, view.top + view.height)};
  if (!(low.x < high.x && low.y < high.y)) return {};
  canvas.begin({low.x, low.y, high.x - low.x, high.y - low.y});
  DrawCounts counts;

  std::array<bool, std::size(spring_families)> hidden{};
  for (int family : options.hidden_families)
    if (family >= 0 && family < int(hidden.size())) hidden[std::size_t(family)] = true;
  const StrainColours& colours = strain_colours(options.ghost);
  const double per_step = strain_steps / options.strain_scale;
  for (const Spring& s : sim.scene().springs) {
    if (hidden[std::size_t(s.family)]) continue;
    const sf::Vector2f a = screen[std::size_t(s.p)], b = screen[std::size_t(s.q)];
    if (!finite(a) || !finite(b)) continue;
    canvas.line(a, b, colours[strain_index(strain_of(s, r), per_step)]);
    ++counts.springs;
  }
  const std::uint32_t particle = PixelCanvas::packed(faded(colour::particle, options.ghost));
  const std::uint32_t pinned = PixelCanvas::packed(faded(colour::pinned, options.ghost));
  const std::uint32_t highlight = PixelCanvas::packed(colour::highlight);
  for (int i = 0; i < particles; ++i) {
    const sf::Vector2f at = screen[std::size_t(i)];
    if (!finite(at)) continue;
    const bool is_pinned = run.pinned[std::size_t(i)];
    if (i == options.highlighted) canvas.square(at, radius * 1.8f, highlight);
    canvas.square(at, radius * (is_pinned ? 1.3f : 1.0f), is_pinned ? pinned : particle);
    ++counts.dots;
  }
  canvas.draw(target);
  return counts;
}

// Every stride-th index from 0, and the last: the grid lines the surface is drawn on.
void sampled(int count, int stride, std::vector<int>& at) {
  at.clear();
  for (int k = 0; k < count - 1; k += stride)
    at.push_back(k);
  at.push_back(count - 1);
}

// The strain at each drawn grid point: the mean strain of the drawn edges that meet there (two
// to four), each edge's rest length that of the structural springs it spans. An edge spanning
// several springs has their mean strain: the surface shows the strain averaged over what one of
// its cells covers, not one spring's of it.
void point_strains(const Vectors& r, int cols, double rest, const std::vector<int>& rows,
                   const std::vector<int>& columns, std::vector<float>& strain) {
  static std::vector<float> edges;  // how many edges meet at each point
  const std::size_t m = columns.size();
  strain.assign(rows.size() * m, 0.0f);
  edges.assign(rows.size() * m, 0.0f);
  const auto edge = [&](std::size_t a, std::size_t b, int i, int j, int springs) {
    const double length = double(springs) * rest;
    const float e = float(((r.col(j) - r.col(i)).norm() - length) / length);
    strain[a] += e;
    strain[b] += e;
    edges[a] += 1.0f;
    edges[b] += 1.0f;
  };
  for (std::size_t y = 0; y < rows.size(); ++y)
    for (std::size_t x = 0; x < m; ++x) {
      const int i = rows[y] * cols + columns[x];
      if (x + 1 < m)
        edge(y * m + x, y * m + x + 1, i, i + columns[x + 1] - columns[x],
             columns[x + 1] - columns[x]);
      if (y + 1 < rows.size())
        edge(y * m + x, (y + 1) * m + x, i, i + (rows[y + 1] - rows[y]) * cols,
             rows[y + 1] - rows[y]);
    }
  for (std::size_t k = 0; k < strain.size(); ++k)
    strain[k] /= edges[k];
}

// The cloth as two triangles a drawn cell, coloured by the strain at their corners: one triangle
// strip down the rows, its rows joined by two repeated vertices (degenerate triangles, which
// cover no pixel). A strip sends a vertex a point and row instead of six a cell: software
// OpenGL transforms, sets up and bins each one, so the cells are also never drawn smaller than
// surface_cell_pixels (surface_stride). Pinned particles and the highlighted one are then drawn
// as squares, which a person can still pick out.
DrawCounts draw_surface(sf::RenderTarget& target, const RunState& run, const Camera& camera,
                        const DrawOptions& options) {
  static sf::VertexArray strip(
      sf::PrimitiveType::TriangleStrip);  // resized in place: no allocation once grown
  static std::vector<sf::Vertex> marks;
  static std::vector<float> strain;
  static std::vector<int> rows, columns;
  const SceneParameters& p = run.sim->parameters();
  const Vectors& r = run.position;
  const int stride = surface_stride(p, camera);
  sampled(p.rows, stride, rows);
  sampled(p.cols, stride, columns);
  point_strains(r, p.cols, p.structural.rest_length, rows, columns, strain);
  const StrainTable<sf::Color>& colours = strain_vertex_colours(options.ghost);
  const double per_step = strain_steps / options.strain_scale;
  const std::size_t m = columns.size();
  // A particle off every scale (a diverging run) is drawn at the origin: its triangles then
  // collapse rather than streak across the window.
  const auto vertex = [&](std::size_t y, std::size_t x) {
    sf::Vector2f at = camera.to_screen(r.col(rows[y] * p.cols + columns[x]));
    if (!finite(at)) at = {0.0f, 0.0f};
    return sf::Vertex{at, colours[strain_index(double(strain[y * m + x]), per_step)]};
  };
  strip.resize(2 * m * (rows.size() - 1) + 2 * (rows.size() - 2));
  std::size_t v = 0;
  for (std::size_t y = 0; y + 1 < rows.size(); ++y) {
    if (y > 0) strip[v++] = vertex(y, 0);  // the join: this row's first vertex twice
    for (std::size_t x = 0; x < m; ++x) {
      strip[v++] = vertex(y, x);
      strip[v++] = vertex(y + 1, x);
    }
    if (y + 2 < rows.size()) {  // and the last row's last vertex twice
      const sf::Vertex last = strip[v - 1];
      strip[v++] = last;
    }
  }
  // Opaque unless a ghost: no blending spares software OpenGL reading every pixel it writes.
  target.draw(strip, options.ghost ? sf::RenderStates::Default : sf::RenderStates(sf::BlendNone));
  DrawCounts counts;
  counts.surface = true;
  counts.triangles = 2L * long(rows.size() - 1) * long(m - 1);
  marks.clear();
  const float radius = particle_radius(camera, p.spacing);
  for (int i = 0; i < int(r.cols()); ++i) {
    const bool pinned = run.pinned[std::size_t(i)];
    if (!pinned && i != options.highlighted) continue;
    const sf::Vector2f at = camera.to_screen(r.col(i));
    if (!finite(at)) continue;
    if (i == options.highlighted) add_dot(marks, at, radius * 1.8f, true, colour::highlight);
    add_dot(marks, at, radius * (pinned ? 1.3f : 1.0f), true,
            faded(pinned ? colour::pinned : colour::particle, options.ghost));
    ++counts.dots;
  }
  target.draw(marks.data(), marks.size(), sf::PrimitiveType::Triangles);
  return counts;
}

}  // namespace

float particle_radius(const Camera& camera, double spacing) {
  // A tenth of the spacing, but large enough to see unless the grid itself is that dense.
  const float apart = static_cast<float>(spacing * camera.pixels_per_metre());
  return std::clamp(0.1f * apart, std::min(2.5f, 0.2f * apart), 11.0f);
}

void RunState::capture(const Simulation& simulation, bool with_velocity) {
  sim = &simulation;
  const Particles& particles = simulation.particles();
  position = particles.position;  // Eigen keeps the storage when the size is the same
  if (with_velocity)
    velocity = particles.velocity;
  else
    velocity.resize(2, 0);
  pinned = particles.pinned;
}

DrawCounts& DrawCounts::operator+=(const DrawCounts& other) {
  surface = surface || other.surface;
  triangles += other.triangles;
  springs += other.springs;
  dots += other.dots;
  return *this;
}

bool draws_surface(const SceneParameters& p, const Camera& camera) {
  return p.rows >= 2 && p.cols >= 2 && p.spacing * camera.pixels_per_metre() < surface_below_pixels;
}

int surface_stride(const SceneParameters& p, const Camera& camera) {
  const double pixels = p.spacing * camera.pixels_per_metre();
  if (!(pixels > 0.0)) return std::max(p.rows, p.cols);  // a degenerate view: the corners only
  const double stride = std::ceil(surface_cell_pixels / pixels);
  return int(std::clamp(stride, 1.0, double(std::max({p.rows, p.cols, 1}))));
}

DrawCounts draw_scene(sf::RenderTarget& target, const RunState& run, const Camera& camera,
                      const DrawOptions& options) {
  const Simulation& sim = *run.sim;
  if (draws_surface(sim.parameters(), camera)) return draw_surface(target, run, camera, options);
  if (sim.scene().springs.size() > thick_spring_limit)
    return draw_in_memory(target, run, camera, options);
  const Vectors& r = run.position;
  static std::vector<sf::Vertex> lines, dots;  // reused from frame to frame
  lines.clear();
  dots.clear();
  DrawCounts counts;
  const float width = std::clamp(particle_radius(camera, sim.parameters().spacing) / 3, 1.0f, 3.0f);
  for (const Spring& s : sim.scene().springs) {
    if (options.hidden_families.count(int(s.family))) continue;
    const sf::Vector2f a = camera.to_screen(r.col(s.p)), b = camera.to_screen(r.col(s.q));
    if (!finite(a) || !finite(b)) continue;
    add_segment(lines, a, b, width,
                faded(strain_colour(strain_of(s, r), options.strain_scale), options.ghost));
    ++counts.springs;
  }
  target.draw(lines.data(), lines.size(), sf::PrimitiveType::Triangles);

  const float radius = particle_radius(camera, sim.parameters().spacing);
  const int particles = int(r.cols());
  const bool squares = particles > square_dot_limit;
  for (int i = 0; i < particles; ++i) {
    const sf::Vector2f at = camera.to_screen(r.col(i));
    if (!finite(at)) continue;
    const bool pinned = run.pinned[std::size_t(i)];
    const float size = i == options.highlighted ? 1.8f : pinned ? 1.3f : 1.0f;
    const sf::Color c = faded(pinned ? colour::pinned : colour::particle, options.ghost);
    if (i == options.highlighted) add_dot(dots, at, radius * size, squares, colour::highlight);
    add_dot(dots, at, radius * (pinned ? 1.3f : 1.0f), squares || pinned, c);
    ++counts.dots;
  }
  target.draw(dots.data(), dots.size(), sf::PrimitiveType::Triangles);
  return counts;
}

Vec2 spring_force_on(const Simulation& sim, int particle) {
  Vec2 total = Vec2::Zero();
  try {
    for (const Spring& s : sim.scene().springs)
      if (s.p == particle || s.q == particle)
        total += force_of(sim.implementation(), s, sim.particles().position,
                          sim.particles().velocity, particle);
  } catch (const std::exception&) {
    return Vec2::Zero();  // the student's force is not written yet: the banner says so
  }
  return total;
}

void draw_force_arrows(sf::RenderTarget& target, const RunState& run, const Camera& camera,
                       int particle) {
  const Simulation& sim = *run.sim;
  if (particle < 0 || particle >= run.position.cols() || run.velocity.cols() != run.position.cols())
    return;
  const SceneParameters& p = sim.parameters();
  const double newtons_per_spacing =
      std::max(0.2 * p.structural.k * p.structural.rest_length, 1e-9);
  const double metres_per_newton = p.spacing / newtons_per_spacing;
  const Vec2 at = run.position.col(particle);
  std::vector<sf::Vertex> arrows;
  Vec2 total = Vec2::Zero();
  try {
    for (const Spring& s : sim.scene().springs) {
      if (s.p != particle && s.q != particle) continue;
      const Vec2 f = force_of(sim.implementation(), s, run.position, run.velocity, particle);
      total += f;
      add_arrow(arrows, camera.to_screen(at), camera.to_screen(at + f * metres_per_newton), 2.0f,
                mix(colour::at_rest, sf::Color::White, 0.5));
    }
  } catch (const std::exception&) {
    return;
  }
  add_arrow(arrows, camera.to_screen(at), camera.to_screen(at + total * metres_per_newton), 3.5f,
            colour::net_force);
  target.draw(arrows.data(), arrows.size(), sf::PrimitiveType::Triangles);
}

int particle_at(const Simulation& sim, const Camera& camera, sf::Vector2f screen) {
  const Vectors& r = sim.particles().position;
  const float reach = std::max(particle_radius(camera, sim.parameters().spacing) * 1.5f, 6.0f);
  int best = -1;
  float best_distance = reach * reach;
  for (int i = 0; i < sim.particles().size(); ++i) {
    const sf::Vector2f d = camera.to_screen(r.col(i)) - screen;
    const float distance = d.x * d.x + d.y * d.y;
    if (distance <= best_distance) best_distance = distance, best = i;
  }
  return best;
}

}  // namespace springlab::view
