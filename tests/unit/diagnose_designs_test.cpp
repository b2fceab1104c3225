// The honest hidden-effect harness (issue 16): effects are generated from
// physical shapes that are NOT candidate columns of the diagnosis — a pitch
// error with its second harmonic, a drift that is not an exponential, a
// coupling about an off-centre point, a scale or squareness whose zero is
// the measurement's own datum, a backlash that grows along the travel — on
// a virtual machine whose laser campaign has its noise on; each measurement
// carries an unknown datum offset per set. The designs are the real ones: a
// regular volumetric grid (serpentine, walked both ways; dx dy dz), one
// plate (dx dy), points along a toolpath at one Z (dx dy dz), ballbar
// circles in XY, XZ and YZ both ways (dn only) and the four body diagonals
// (displacement along the line). The gain is scored on a fresh,
// independent measurement of the same truth machine (new noise, new datum)
// against an oracle that knows the hidden deviation exactly.
//
// A case counts as identifiable when the design can tell the hidden shape
// from the rest of the catalogue (identifiable(), by the design's geometry)
// and the oracle gains at least 5 % on the fresh measurement — for a drift
// on the one-pass grid by its course within the levels
// (course_unresolved()), for an off-centre coupling beyond its linear parts
// of kinds the design cannot name (identifiable_parts_unresolved()).
// Outcome classes per case: `right` (kind, axis, direction and sign of the
// hidden effect named; parts of the same shape allowed, see consistent()),
// `ambiguous` (the truth reported only among alternatives; an off-centre
// coupling whose product part the design does not resolve counts as named
// right by an unambiguous linear part with that part's sign, scored(); a
// drift whose alternatives are all forms of the same drift counts as named
// right, same_drift_form()), `wrong` (a name that is not the truth nor part
// of its shape), `none` (nothing named).
// The measured rates are printed as a table (docs/diagnosis.md), with the
// identifiable cases' rate by the oracle's gain (POWER: how the rate falls
// near the practical floor), and the assertions hold the rates reached now,
// so that a regression fails.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include "abbe/diagnose/design_ambiguity.hpp"
#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/io/approach_directions.hpp"
#include "abbe/io/ballbar.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/io/units.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/truth_generator.hpp"
#include "abbe/sim/validation_measurement.hpp"
#include "diagnose_vm_test.hpp"

namespace abbe::diagnose {
namespace {

// µm per measured component; ABBE_DESIGNS_NOISE: another noise (the hidden
// effects keep their 3–20 × the noise), for a sweep at a noise the engine
// was not tuned on (the truth machine's own table error stays as it is).
// A positive length or noise from the environment, or `fallback` when unset
// (a sweep on a design the engine was not tuned on); junk is an error.
double env_positive(const char* name, double fallback, const char* what) {
  const char* s = std::getenv(name);
  if (!s) return fallback;
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || *end != '\0' || !(v > 0.0))
    throw std::invalid_argument(fmt::format("{}={}: want {} > 0", name, s, what));
  return v;
}

double noise_level() {
  static const double noise = env_positive("ABBE_DESIGNS_NOISE", 0.5, "a noise in µm");
  return noise;
}

// The virtual machine with its laser campaign's noise ON (the model does not
// match the truth exactly: that mismatch is part of every data set), waves
// shorter than two table intervals removed (else every data set holds the
// generator's 10 mm screw cycle, itself a hidden effect): the generator's
// "mazak" machine (seed 7), or another truth machine for a sweep by
// ABBE_DESIGNS_VM_SEED, ABBE_DESIGNS_VM_PROFILE (mazak, generic) and
// ABBE_DESIGNS_VM_CHAIN (e.g. "w b X Y Z t").
const testing::VirtualMachine& default_vm() {
  static const testing::VirtualMachine vm = [] {
    const char* seed = std::getenv("ABBE_DESIGNS_VM_SEED");
    const char* profile = std::getenv("ABBE_DESIGNS_VM_PROFILE");
    const char* chain = std::getenv("ABBE_DESIGNS_VM_CHAIN");
    return testing::build_virtual_machine(true, "abbe_designs_vm",
                                          sim::GeneratorOptions{}.noise_scale,
                                          seed ? std::strtoull(seed, nullptr, 10) : 7,
                                          profile ? profile : "mazak", chain ? chain : "");
  }();
  return vm;
}

// A machine the engine was not tuned on: the generator's generic profile
// (seed 11) with the chain `w b X Y Z t` (every axis on the tool side, as on
// a gantry). There an arm offset (the model's angular tables times an arm)
// fitted the model's own table error in place of scales and drifts
// (docs/diagnosis.md, "On machines it was not tuned on").
const testing::VirtualMachine& gantry_vm() {
  static const testing::VirtualMachine vm = testing::build_virtual_machine(
      true, "abbe_designs_gantry", sim::GeneratorOptions{}.noise_scale, 11, "generic",
      "w b X Y Z t");
  return vm;
}

// Another machine the engine was not tuned on (generic profile, seed 5,
// the chain of the tuned machine: an X' column).
const testing::VirtualMachine& generic5_vm() {
  static const testing::VirtualMachine vm = testing::build_virtual_machine(
      true, "abbe_designs_generic5", sim::GeneratorOptions{}.noise_scale, 5, "generic",
      "w X' b Y Z t");
  return vm;
}

// The machine the sweeps measure on (OnMachine switches it for one test).
const testing::VirtualMachine* current_vm = nullptr;
std::string current_vm_label;  // printed with the design's name
const testing::VirtualMachine& noisy_vm() { return current_vm ? *current_vm : default_vm(); }
struct OnMachine {
  OnMachine(const testing::VirtualMachine& vm, std::string label) {
    current_vm = &vm;
    current_vm_label = std::move(label);
  }
  ~OnMachine() {
    current_vm = nullptr;
    current_vm_label.clear();
  }
  OnMachine(const OnMachine&) = delete;
  OnMachine& operator=(const OnMachine&) = delete;
};

// ---------------------------------------------------------------- designs
enum class Design {
  grid,
  plane,
  toolpath,
  ballbar,
  diagonals,
  axis_lines,
  grid_one_pass,
  ballbar_xy,
  grid_irregular,
  diagonals_runs
};
// The body diagonals, measured once there and back or in five runs.
bool along_diagonals(Design d) { return d == Design::diagonals || d == Design::diagonals_runs; }
const char* design_name(Design d) {
  static const char* const names[] = {
      "grid 12x8x5, serpentine both ways (dx dy dz)",
      "one plate at one Z (dx dy)",
      "toolpath at one Z (dx dy dz)",
      "ballbar XY/XZ/YZ both ways (dn)",
      "four body diagonals (along the line)",
      "laser lines along X, Y, Z, 5 runs both ways (along the line)",
      "grid 9x7x3, serpentine one pass (dx dy dz)",
      "ballbar XY only, both ways (dn)",
      "grid 12x8x5 at irregular levels, serpentine both ways (dx dy dz)",
      "four body diagonals, 5 runs both ways (along the line)"};
  return names[static_cast<int>(d)];
}

struct Sample {
  sim::TipState tip;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  // zero: dx dy dz (or dx dy on the plate)
  // A ballbar reading: its circle (plane, centre), direction and angle (°).
  std::string plane;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int way = 0;
  double angle_deg = 0.0;
};

// The ballbar's length: 150 mm, or ABBE_DESIGNS_BALLBAR_RADIUS (mm; the
// usual bars are 50, 100, 150 and 300 mm).
double ballbar_radius() {
  static const double r = env_positive("ABBE_DESIGNS_BALLBAR_RADIUS", 150.0, "a radius in mm");
  return r;
}

// The ballbar readings as the documented CSV of `abbe import ballbar`
// (docs/formats.md), read back by its importer: the harness's circular
// tests reach the diagnosis the way a user's do. `dr`: the radial
// deviation of each reading (µm).
io::MeasuredData import_ballbar(const std::vector<Sample>& design, const std::vector<double>& dr) {
  std::string csv = "plane,radius,cx,cy,cz,feed,direction,angle,dr,t,set\n";
  for (std::size_t i = 0; i < design.size(); ++i) {
    const Sample& s = design[i];
    csv += fmt::format("{},{},{:.17g},{:.17g},{:.17g},1000,{},{:.17g},{:.17g},{:.17g},{}\n",
                       s.plane, ballbar_radius(), s.centre.x(), s.centre.y(), s.centre.z(),
                       s.way > 0 ? "ccw" : "cw", s.angle_deg, dr[i], s.tip.time, s.tip.set);
  }
  std::istringstream in(csv);
  return io::read_ballbar(in, "<ballbar>");
}

struct Box {
  Eigen::Vector3d lo, hi;
};
Box box() {
  Box b;
  sim::default_box(noisy_vm().generated.truth, noisy_vm().generated.truth.tool_length, b.lo, b.hi);
  return b;
}

void set_dirs(std::vector<Sample>& v, Eigen::Vector3d prev) {
  std::array<int, 3> dir{0, 0, 0};
  for (Sample& s : v) {
    for (int i = 0; i < 3; ++i) {
      if (s.tip.p[i] > prev[i] + 1e-9) dir[static_cast<std::size_t>(i)] = 1;
      if (s.tip.p[i] < prev[i] - 1e-9) dir[static_cast<std::size_t>(i)] = -1;
    }
    s.tip.dir = dir;
    prev = s.tip.p;
  }
}

// A grid's levels per axis: 12 × 8 × 5 walked both ways, 9 × 7 × 3 once;
// ABBE_DESIGNS_GRID=NXxNYxNZ: other level counts, for a sweep on a grid the
// engine was not tuned on.
std::array<int, 3> grid_levels(Design d) {
  std::array<int, 3> n =
      d == Design::grid_one_pass ? std::array<int, 3>{9, 7, 3} : std::array<int, 3>{12, 8, 5};
  if (const char* g = std::getenv("ABBE_DESIGNS_GRID"))
    if (std::sscanf(g, "%dx%dx%d", &n[0], &n[1], &n[2]) != 3 || n[0] < 2 || n[1] < 2 || n[2] < 2)
      throw std::invalid_argument(fmt::format("ABBE_DESIGNS_GRID={}: want NXxNYxNZ", g));
  return n;
}

std::vector<Sample> make_design(Design d) {
  const Box b = box();
  const double L = noisy_vm().generated.truth.tool_length;
  std::vector<Sample> out;
  auto push = [&](const Eigen::Vector3d& p, const std::string& set,
                  const Eigen::Vector3d& n = Eigen::Vector3d::Zero()) {
    Sample s;
    s.tip.p = p;
    s.tip.tool_length = L;
    s.tip.set = set;
    s.n = n;
    out.push_back(s);
  };
  auto lerp = [&](int a, double f) { return b.lo[a] + (b.hi[a] - b.lo[a]) * f; };
  switch (d) {
    case Design::grid:
    case Design::grid_irregular:
    case Design::grid_one_pass: {
      // 12 × 8 × 5 levels, serpentine, then the same walk backwards (the
      // levels regular, or each inner level moved by up to ±0.3 of the
      // spacing: "sample at irregular spacing"); or 9 × 7 × 3 regular levels
      // walked once (time then follows the Z levels).
      const bool both_ways = d != Design::grid_one_pass;
      const std::array<int, 3> n_levels = grid_levels(d);
      const int nx = n_levels[0], ny = n_levels[1], nz = n_levels[2];
      std::mt19937_64 levels_rng(77);
      std::uniform_real_distribution<double> jitter(-0.3, 0.3);
      std::array<std::vector<double>, 3> level;  // per axis: each level's position in steps
      const int n_of[3] = {nx, ny, nz};
      for (int a = 0; a < 3; ++a)
        for (int q = 0; q < n_of[a]; ++q)
          level[static_cast<std::size_t>(a)].push_back(
              q +
              (d == Design::grid_irregular && q > 0 && q < n_of[a] - 1 ? jitter(levels_rng) : 0.0));
      std::vector<Eigen::Vector3d> walk;
      bool xu = true, yu = true;
      for (int kz = nz - 1; kz >= 0; --kz) {
        for (int ky = 0; ky < ny; ++ky) {
          const int yy = yu ? ky : ny - 1 - ky;
          for (int kx = 0; kx < nx; ++kx) {
            const int xx = xu ? kx : nx - 1 - kx;
            walk.emplace_back(lerp(0, level[0][static_cast<std::size_t>(xx)] / (nx - 1.0)),
                              lerp(1, level[1][static_cast<std::size_t>(yy)] / (ny - 1.0)),
                              lerp(2, level[2][static_cast<std::size_t>(kz)] / (nz - 1.0)));
          }
          xu = !xu;
        }
        yu = !yu;
      }
      for (const auto& p : walk) push(p, "grid");
      if (both_ways)
        for (auto it = walk.rbegin(); it != walk.rend(); ++it) push(*it, "grid");
      break;
    }
    case Design::plane: {
      // A plate of 13 × 9 holes at 50 mm pitch on the table, z = top − 100
      // (ABBE_DESIGNS_PLATE_PITCH: another pitch, the plate within the travel).
      const double z = b.hi.z() - 100.0;
      const Eigen::Vector3d c = 0.5 * (b.lo + b.hi);
      static const double pitch =
          env_positive("ABBE_DESIGNS_PLATE_PITCH", 50.0, "a hole pitch in mm");
      for (int a = 0; a < 2; ++a)
        if (pitch * (a == 0 ? 6 : 4) > 0.5 * (b.hi[a] - b.lo[a]))
          throw std::invalid_argument(
              fmt::format("plate pitch {} mm: the plate leaves the travel of {}", pitch, "XY"[a]));
      for (int ky = 0; ky < 9; ++ky)
        for (int kx = 0; kx < 13; ++kx) {
          const int xx = ky % 2 == 0 ? kx : 12 - kx;
          push({c.x() + pitch * (xx - 6), c.y() + pitch * (ky - 4), z}, "plate");
        }
      break;
    }
    case Design::toolpath: {
      // A pocket at one Z: raster in X with a 23 mm stepover, a point every
      // 3.7 mm of path, then a circular contour of r = 180 mm.
      const double z = b.hi.z() - 150.0;
      const Eigen::Vector3d c = 0.5 * (b.lo + b.hi);
      const double x0 = b.lo.x() + 60.0, x1 = b.hi.x() - 60.0;
      bool up = true;
      for (double y = b.lo.y() + 40.0; y <= b.hi.y() - 40.0; y += 23.0) {
        for (double s = 0.0; s <= x1 - x0; s += 3.7) push({up ? x0 + s : x1 - s, y, z}, "path");
        up = !up;
      }
      for (double a = 0.0; a < units::kTwoPi; a += 3.7 / 180.0)
        push({c.x() + 180.0 * std::cos(a), c.y() + 180.0 * std::sin(a), z}, "path");
      break;
    }
    case Design::ballbar:
    case Design::ballbar_xy: {
      // r = 150 mm (ballbar_radius()) about the box centre, a reading every 2°, CCW then CW,
      // one set per plane (the ballbar is re-placed); or the XY plane only
      // (the shop's usual test).
      const Eigen::Vector3d c = 0.5 * (b.lo + b.hi);
      const int planes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
      const char* names[3] = {"XY", "XZ", "YZ"};
      const int n_planes = d == Design::ballbar_xy ? 1 : 3;
      for (int pl = 0; pl < n_planes; ++pl)
        for (int a : planes[pl])
          if (ballbar_radius() > 0.5 * (b.hi[a] - b.lo[a]))
            throw std::invalid_argument(fmt::format(
                "ballbar radius {} mm: the {} circle leaves the travel of {} ({:.0f} mm)",
                ballbar_radius(), names[pl], "XYZ"[a], b.hi[a] - b.lo[a]));
      for (int pl = 0; pl < n_planes; ++pl)
        for (int way : {1, -1})
          for (int k = 0; k < 180; ++k) {
            const double a = way * units::kTwoPi * k / 180.0;
            Eigen::Vector3d n = Eigen::Vector3d::Zero();
            n[planes[pl][0]] = std::cos(a);
            n[planes[pl][1]] = std::sin(a);
            push(c + ballbar_radius() * n, names[pl], n);
            out.back().plane = names[pl];
            out.back().centre = c;
            out.back().way = way;
            out.back().angle_deg = way * 2.0 * k;
          }
      break;
    }
    case Design::diagonals:
    case Design::diagonals_runs: {
      // ISO 230-6: each body diagonal of the box (inset 30 mm), a target every
      // 37 mm (ABBE_DESIGNS_DIAGONAL_STEP: another spacing), there and back
      // once, or in five runs as the laser lines' (ISO 230-2); one set per
      // line (the laser is re-aligned).
      const Eigen::Vector3d lo = b.lo + Eigen::Vector3d::Constant(30.0);
      const Eigen::Vector3d hi = b.hi - Eigen::Vector3d::Constant(30.0);
      for (int k = 0; k < 4; ++k) {
        Eigen::Vector3d a = lo, e = hi;
        if (k & 1) std::swap(a.x(), e.x());
        if (k & 2) std::swap(a.y(), e.y());
        const Eigen::Vector3d u = (e - a).normalized();
        const double len = (e - a).norm();
        static const double step =
            env_positive("ABBE_DESIGNS_DIAGONAL_STEP", 37.0, "a target spacing in mm");
        const int m = std::max(2, static_cast<int>(len / step));
        const int runs = d == Design::diagonals_runs ? 5 : 1;
        const std::string set = fmt::format("diag{}", k + 1);
        for (int run = 0; run < runs; ++run) {
          for (int i = 0; i <= m; ++i) push(a + u * (len * i / m), set, u);
          for (int i = m; i >= 0; --i) push(a + u * (len * i / m), set, u);
        }
      }
      break;
    }
    case Design::axis_lines: {
      // ISO 230-2: a laser line along each axis through the box centre
      // (inset 20 mm), 21 targets at irregular spacing (each step 0.7–1.3 ×
      // the mean, the same targets in every run), five runs there and back;
      // one set per line (the laser is re-aligned for each axis).
      const Eigen::Vector3d c = 0.5 * (b.lo + b.hi);
      std::mt19937_64 targets_rng(230);
      std::uniform_real_distribution<double> jitter(-0.3, 0.3);
      for (int a = 0; a < 3; ++a) {
        const double lo = b.lo[a] + 20.0, hi = b.hi[a] - 20.0;
        std::vector<double> steps(20);
        double sum = 0.0;
        for (double& st : steps) sum += st = 1.0 + jitter(targets_rng);
        std::vector<double> pos{lo};
        for (double st : steps) pos.push_back(pos.back() + (hi - lo) * st / sum);
        const std::string set = fmt::format("line{}", "XYZ"[a]);
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        n[a] = 1.0;
        for (int run = 0; run < 5; ++run) {
          for (double x : pos) {
            Eigen::Vector3d p = c;
            p[a] = x;
            push(p, set, n);
          }
          for (auto it = pos.rbegin(); it != pos.rend(); ++it) {
            Eigen::Vector3d p = c;
            p[a] = *it;
            push(p, set, n);
          }
        }
      }
      break;
    }
  }
  set_dirs(out, Eigen::Vector3d(0.0, 0.0, -L));
  double t = 0.0;
  // A plate report has no time column (t = 0).
  const double dt = d == Design::plane                                ? 0.0
                    : d == Design::ballbar || d == Design::ballbar_xy ? 8.0
                    : d == Design::toolpath                           ? 2.0
                                                                      : 5.0;
  // ABBE_DESIGNS_DT_SCALE: every design's time between readings scaled.
  const char* dt_scale = std::getenv("ABBE_DESIGNS_DT_SCALE");
  const double dt_used = dt * (dt_scale ? std::atof(dt_scale) : 1.0);
  for (Sample& s : out) {
    s.tip.time = t;
    t += dt_used;
  }
  if (d == Design::ballbar || d == Design::ballbar_xy) {
    // The motion the importer gives each reading (the plane's two axes, from
    // the direction of travel) is the motion the truth is measured with.
    const io::MeasuredData nominal = import_ballbar(out, std::vector<double>(out.size(), 0.0));
    for (std::size_t i = 0; i < out.size(); ++i) {
      const io::MeasuredRow& r = nominal.rows[i];
      if ((r.p - out[i].tip.p).norm() > 1e-9 || (r.n - out[i].n).norm() > 1e-12)
        throw std::logic_error(fmt::format("ballbar import moved reading {}", i));
      for (std::size_t k = 0; k < 3; ++k) out[i].tip.dir[k] = r.v[k];
    }
  }
  return out;
}

// ---------------------------------------------------------- hidden shapes
enum class Shape { none, scale, squareness, reversal, pitch, drift, coupling };
const char* shape_name(Shape s) {
  static const char* const names[] = {
      "none",           "scale",           "squareness",         "reversal",
      "pitch+harmonic", "drift t/(t+tau)", "coupling off-centre"};
  return names[static_cast<int>(s)];
}

struct Hidden {
  Shape shape = Shape::none;
  int axis = 0, with = -1, dir = 0;  // driving axis, coupling partner, deviation direction
  double a = 0.0;                    // magnitude (µm at the reach of the data)
  double zero = 0.0, zero2 = 0.0;    // datum of scale/squareness, coupling centre
  double period = 0.0, ph1 = 0.0, ph2 = 0.0, tau = 0.0;
  bool proportional = false;  // drift ∝ s_dir
  double sign = 1.0;
  std::string text;
  std::vector<Hidden> also;  // further effects hidden in the same data

  Eigen::Vector3d at(const sim::TipState& tip, const Box& b) const {
    Eigen::Vector3d s = tip.p;
    s.z() += tip.tool_length;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    const Eigen::Vector3d half = 0.5 * (b.hi - b.lo);
    switch (shape) {
      case Shape::none:
        break;
      case Shape::scale:
      case Shape::squareness:
        d[dir] = a * (s[axis] - zero) / (2.0 * half[axis]);
        break;
      case Shape::reversal: {
        const double mid = 0.5 * (b.lo[axis] + b.hi[axis]) + (axis == 2 ? tip.tool_length : 0.0);
        d[dir] = 0.5 * a * tip.dir[static_cast<std::size_t>(axis)] *
                 (1.0 + 0.2 * (s[axis] - mid) / half[axis]);
        break;
      }
      case Shape::pitch: {
        const double w = units::kTwoPi * s[axis] / period;
        d[dir] = a * (std::sin(w + ph1) + 0.35 * std::sin(2.0 * w + ph2)) / 1.2;
        break;
      }
      case Shape::drift: {
        double g = a * tip.time / (tip.time + tau);
        if (proportional) g *= (s[dir] - zero) / (2.0 * half[dir]);
        d[dir] = g;
        break;
      }
      case Shape::coupling:
        d[dir] = a * (s[axis] - zero) * (s[with] - zero2) / (4.0 * half[axis] * half[with]);
        break;
    }
    for (const Hidden& other : also) d += other.at(tip, b);
    return d;
  }
};

Hidden draw(std::mt19937_64& rng, const Box& b, double L) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Hidden h;
  h.shape = static_cast<Shape>(1 + rng() % 6);
  h.axis = static_cast<int>(rng() % 3);
  h.dir = h.axis;
  h.sign = u(rng) < 0.5 ? -1.0 : 1.0;
  h.a = h.sign * (3.0 + 17.0 * u(rng)) * noise_level();
  auto axis_range = [&](int a, double f) {
    return (a == 2 ? L : 0.0) + b.lo[a] + (b.hi[a] - b.lo[a]) * f;
  };
  switch (h.shape) {
    case Shape::scale:
      h.zero = axis_range(h.axis, u(rng));  // the measurement's datum, anywhere
      break;
    case Shape::squareness:
      h.dir = (h.axis + 1 + static_cast<int>(rng() % 2)) % 3;
      h.zero = axis_range(h.axis, u(rng));
      break;
    case Shape::pitch:
      h.period = 8.0 + 32.0 * u(rng);
      h.ph1 = units::kTwoPi * u(rng);
      h.ph2 = units::kTwoPi * u(rng);
      break;
    case Shape::drift:
      h.tau = 600.0 + 2400.0 * u(rng);
      h.proportional = u(rng) < 0.5;
      h.zero = axis_range(h.dir, u(rng));
      break;
    case Shape::coupling:
      h.with = (h.axis + 1 + static_cast<int>(rng() % 2)) % 3;
      if (h.with < h.axis) std::swap(h.with, h.axis);
      h.dir = static_cast<int>(rng() % 3);
      h.zero = axis_range(h.axis, 0.2 + 0.6 * u(rng));
      h.zero2 = axis_range(h.with, 0.2 + 0.6 * u(rng));
      break;
    default:
      break;
  }
  h.text =
      fmt::format("{} axis {} dir {}{} {:+.2f} µm", shape_name(h.shape), "XYZ"[h.axis],
                  "XYZ"[h.dir], h.with >= 0 ? fmt::format(" with {}", "XYZ"[h.with]) : "", h.a);
  if (h.shape == Shape::pitch) h.text += fmt::format(" period {:.1f} mm", h.period);
  if (h.shape == Shape::drift)
    h.text += fmt::format(" tau {:.0f} s{}", h.tau, h.proportional ? " x s" : "");
  return h;
}

// Can the design tell this effect apart from the others of the catalogue
// (and from its datum)? The design's geometry decides (docs/diagnosis.md).
bool identifiable(Design d, const Hidden& h) {
  switch (d) {
    case Design::grid:
      // Regular levels ≥ 50 mm apart alias every period of 8–40 mm; on 4
      // levels or fewer a cycle with its period free fits any function of
      // the levels, a scale or squareness along that axis too.
      if ((h.shape == Shape::scale || h.shape == Shape::squareness) &&
          grid_levels(d)[static_cast<std::size_t>(h.axis)] <= 4)
        return false;
      return h.shape != Shape::pitch;
    case Design::grid_irregular:
      // Irregular levels do not alias a period; 12 of them resolve a pitch
      // error of X, 8 of Y and 5 of Z do not (its period fits among others).
      return h.shape != Shape::pitch || h.axis == 0;
    case Design::grid_one_pass:
      // And on 3 levels of Z a cycle of Z fits any function of z: a scale
      // or squareness of Z is a pitch error as much. (Walked once, time
      // follows the Z levels: a drift and a function of z are told apart
      // only by the drift's course within each level, which the diagnosis
      // tests case by case — design_ambiguity.hpp — and the sweep measures
      // on the fresh measurement: course_unresolved().)
      if ((h.shape == Shape::scale || h.shape == Shape::squareness) && h.axis == 2) return false;
      // Z is driven one way only (down from level to level): a reversal of Z
      // is a constant of the datum, its growth a scale of Z.
      if (h.shape == Shape::reversal && h.axis == 2) return false;
      return h.shape != Shape::pitch;
    case Design::plane:
      // z fixed, dz not measured, plate placement (offset + rotation) unknown.
      if (h.dir == 2 || h.axis == 2 || h.with == 2) return false;
      if (h.shape == Shape::squareness) return false;  // X→Y and Y→X differ by a rotation
      if (h.shape == Shape::drift) return false;       // no time on a plate report
      if (h.shape == Shape::pitch) return false;       // 50 mm pitch aliases the period
      return true;
    case Design::toolpath:
      // z fixed: nothing driven by z (a drift in time of Z is measured in
      // dz at any z; one ∝ z − z0 is there a uniform drift).
      if (h.shape != Shape::drift && (h.axis == 2 || h.with == 2)) return false;
      // d_z ∝ x (or y) at one z is a rotation of the datum about Y (or X).
      if (h.shape == Shape::squareness && h.dir == 2) return false;
      if (h.shape == Shape::scale && h.dir == 2) return false;
      return true;
    case Design::ballbar:
      // Only the symmetric part of a squareness reaches dn.
      return h.shape != Shape::squareness;
    case Design::ballbar_xy:
      // One circle at one z: nothing of Z, and a coupling x·y is on the
      // circle a sum of harmonics the other shapes share.
      if (h.dir == 2 || h.axis == 2 || h.with == 2) return false;
      return h.shape != Shape::squareness && h.shape != Shape::coupling;
    case Design::diagonals:
    case Design::diagonals_runs:
      // Along a body diagonal the three scales give the same slope, the three
      // reversals the same step, i→j and j→i squareness the same line, every
      // coupling a parabola, and 37 mm targets alias the periods; a drift
      // in time (there and back) is told apart. (A drift proportional to
      // the position is a scale growing in time: not told apart either.)
      // A reversal is told by its growth along the travel: the growth of
      // axis j along diagonal k has the sign of the diagonal's slope in s_j,
      // a pattern over the four diagonals that differs from axis to axis —
      // where that growth is resolved (growth_unresolved()). Whose jump it
      // is the diagonals do not tell: a growing reversal named with the
      // other axes' jumps as its only alternatives is named by its growth.
      return (h.shape == Shape::drift && !h.proportional) || h.shape == Shape::reversal;
    case Design::axis_lines:
      // Each line measures its own axis's displacement at fixed other
      // coordinates: a squareness (d_j ∝ s_i, i ≠ j) is not measured or is a
      // constant of the line's datum and a coupling is a scale of the line's
      // axis. Scale, reversal, a pitch error (the targets' irregular spacing
      // is there to resolve it) and a drift (five runs spread in time) are
      // told apart.
      return h.shape != Shape::squareness && h.shape != Shape::coupling;
  }
  return false;
}

// ------------------------------------------------------------- measuring
// `noise` < 0: the harness's reading noise (noise_level()).
io::MeasuredData measure(const std::vector<Sample>& design, const Hidden& h, std::uint64_t seed,
                         bool plane, double noise = -1.0) {
  const auto& vm = noisy_vm();
  const Box b = box();
  std::vector<sim::TipState> tips;
  for (const Sample& s : design) tips.push_back(s.tip);
  const auto pts =
      sim::measure(vm.generated.truth, tips, noise < 0.0 ? noise_level() : noise, seed);
  // The measurement's datum: an unknown offset per set and direction.
  std::mt19937_64 rng(seed * 7919 + 13);
  std::normal_distribution<double> datum(0.0, 15.0);
  std::map<std::string, Eigen::Vector3d> offset;
  if (!design.front().plane.empty()) {  // ballbar: through its importer
    std::vector<double> dr;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const sim::TipState& tip = pts[i].tip;
      if (!offset.count(tip.set)) offset[tip.set] = {datum(rng), datum(rng), datum(rng)};
      dr.push_back(design[i].n.dot(pts[i].deviation_um + h.at(tip, b) + offset[tip.set]));
    }
    return import_ballbar(design, dr);
  }
  io::MeasuredData d;
  d.file = "<design>";
  d.has_column = {!design.front().n.any(), !design.front().n.any(),
                  !plane && !design.front().n.any()};
  d.has_dn = design.front().n.any();
  std::size_t line = 2;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const sim::TipState& tip = pts[i].tip;
    if (!offset.count(tip.set)) offset[tip.set] = {datum(rng), datum(rng), datum(rng)};
    const Eigen::Vector3d dev = pts[i].deviation_um + h.at(tip, b) + offset[tip.set];
    io::MeasuredRow r;
    r.p = tip.p;
    r.t = tip.time;
    for (std::size_t k = 0; k < 3; ++k) r.v[k] = static_cast<std::int8_t>(tip.dir[k]);
    r.tool_length = tip.tool_length;
    r.set = tip.set;
    r.line = line++;
    if (d.has_dn) {
      r.n = design[i].n;
      r.dn = r.n.dot(dev);
    } else {
      for (int k = 0; k < (plane ? 2 : 3); ++k) r.d[static_cast<std::size_t>(k)] = dev[k];
    }
    d.rows.push_back(r);
  }
  return d;
}

// Least-squares removal of the datum (offset per set and direction; plates
// also a rotation about Z) from per-observation residuals.
Eigen::VectorXd remove_datum(const Problem& pb, const Eigen::VectorXd& r, bool plate) {
  const int per = plate ? 4 : 3;
  const auto ns = static_cast<Eigen::Index>(pb.sets.size());
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(r.size(), per * ns);
  std::map<std::string, Eigen::Vector3d> centre;
  std::map<std::string, double> count;
  for (const auto& pc : pb.points) {
    // (A map's new Eigen vector is not zeroed: it starts from Zero().)
    centre.try_emplace(pc.set, Eigen::Vector3d::Zero()).first->second += pc.p;
    count[pc.set] += 1.0;
  }
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const auto& ob = pb.obs[o];
    const PointContext& pc = pb.points[ob.point];
    const auto si = static_cast<Eigen::Index>(std::find(pb.sets.begin(), pb.sets.end(), pc.set) -
                                              pb.sets.begin());
    const auto row = static_cast<Eigen::Index>(o);
    for (int i = 0; i < 3; ++i) X(row, per * si + i) = ob.u[i];
    if (plate) {
      const Eigen::Vector3d q = pc.p - centre[pc.set] / count[pc.set];
      X(row, per * si + 3) = 1e-3 * (-q.y() * ob.u.x() + q.x() * ob.u.y());
    }
  }
  const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(r);
  return r - X * beta;
}

double rms(const Eigen::VectorXd& r) {
  return std::sqrt(r.squaredNorm() / std::max<double>(static_cast<double>(r.size()), 1.0));
}

bool is_datum(const Term& t) {
  return t.kind == TermKind::setup_offset || t.kind == TermKind::setup_rotation;
}

// Is the term the hidden effect, or a part of its shape (the linear part of
// an off-centre coupling is a squareness/scale along its axes; a drift
// proportional to s_dir may be named with or without the axis)? A cycle
// whose period the diagnosis reports unresolved (`period_unresolved`:
// SelectedTerm::other_periods_mm) is graded on kind, axis and direction.
bool consistent(const Term& t, const Hidden& h, bool period_unresolved = false) {
  if (t.direction != h.dir && t.kind != TermKind::unexplained) return false;
  switch (h.shape) {
    case Shape::scale:
      return t.kind == TermKind::scale && t.axis == h.axis;
    case Shape::squareness:
      return t.kind == TermKind::squareness && t.axis == h.axis;
    case Shape::reversal:
      return t.kind == TermKind::reversal && t.axis == h.axis;
    case Shape::pitch: {
      // Its period too: the fundamental or its second harmonic, within 10 %
      // (a cycle at another period is an alias, not this pitch error).
      if (t.kind != TermKind::cyclic || t.axis != h.axis) return false;
      if (period_unresolved) return true;
      auto near = [&](double p) { return std::abs(t.period_mm - p) <= 0.1 * p; };
      return near(h.period) || near(0.5 * h.period);
    }
    case Shape::drift:
      // A scale that grows in time has a mean scale over the measurement.
      if (h.proportional && t.kind == TermKind::scale) return t.axis == h.dir;
      return t.kind == TermKind::thermal_drift;
    case Shape::coupling:
      if (t.kind == TermKind::coupling) return t.axis == h.axis && t.with_axis == h.with;
      return (t.kind == TermKind::scale || t.kind == TermKind::squareness) &&
             (t.axis == h.axis || t.axis == h.with);
    case Shape::none:
      return false;
  }
  return false;
}

// An alternative the diagnosis names beside a drift that is one form of the
// same drift: a thermal drift of the hidden direction, uniform or
// proportional to a position, at any time constant (consistent() does not
// tell these forms apart: the catalogue's proportional drift is about the
// machine's zero, so far from the zero it is mostly the uniform drift).
// A drift ∝ a position also has its mean scale over the measurement as a
// form (as consistent() grades a named scale of its direction).
// Labels as Term::label() writes them: "thermal_drift x·t→Y (τ 900 s)",
// "thermal_drift t→Y (at 3 time constants, 900 s – 1800 s)", "scale Y".
bool same_drift_form(const std::string& alternative, const Hidden& h) {
  if (h.shape != Shape::drift) return false;
  if (h.proportional && alternative == std::string("scale ") + "XYZ"[h.dir]) return true;
  if (alternative.rfind("thermal_drift ", 0) != 0) return false;
  const std::string arrow = std::string("→") + "XYZ"[h.dir];
  const auto at = alternative.find(arrow);
  return at != std::string::npos && alternative.find("→", at + 1) == std::string::npos &&
         (at + arrow.size() == alternative.size() || alternative[at + arrow.size()] == ' ');
}

// The named term that is the hidden effect itself (not only a part).
bool is_truth(const Term& t, const Hidden& h, bool period_unresolved = false) {
  if (!consistent(t, h, period_unresolved)) return false;
  if (h.shape == Shape::coupling) return t.kind == TermKind::coupling;
  return true;
}

// Sign check: the fitted first parameter has the sign of the hidden one
// (only for the shapes whose sign the catalogue's parameter carries).
bool sign_right(const Term& t, const Hidden& h) {
  if (t.coef.empty()) return true;
  switch (h.shape) {
    case Shape::scale:
    case Shape::squareness:
    case Shape::reversal:
      return t.coef[0] * h.sign > 0.0;
    default:
      return true;
  }
}

enum class Verdict { right, ambiguous, wrong, none };

// An effect that even the oracle cannot use (held-out gain below 5 % on the
// fresh measurement) is below what this design resolves: counted with the
// not identifiable ones (a name is then wrong, silence or `ambiguous` right).
constexpr double kResolvable = 0.05;

struct Case {
  Verdict verdict = Verdict::none;
  bool gain_ok = false;
  double gain = 0.0, oracle = 0.0;
  std::string found;
  // Names that are not the hidden effect's but the truth machine's own
  // error against its model (of_the_machine()): neither right nor wrong.
  int machine_names = 0;
  std::vector<bool> of_machine;  // per entry of `effects`
  // With gross outliers: how many were put in, flagged right, flagged wrongly.
  std::size_t injected = 0, flagged = 0, false_flags = 0;
  double noise_um = 0.0, noise_independent_um = 0.0;
  // With two hidden shapes (Hidden::also): each one's own oracle gain, on
  // the fresh measurement with the other shape taken out.
  std::vector<double> part_oracle;
  // An off-centre coupling (alone): what its product part adds, on the
  // fresh measurement, to its best linear part (the scale and squareness
  // of its direction along its two axes, fitted to the hidden deviation);
  // and whether a linear part was named, unambiguous, with that part's sign.
  double product_oracle = -1.0;  // -1: not a single coupling
  // A drift on the one-pass grid (alone): what its course within each Z
  // level adds, on the fresh measurement, to its best function of the
  // levels (a value per level, and for a drift ∝ s_dir a slope per level);
  // -1: not such a case.
  double course_oracle = -1.0;
  bool linear_part_named = false;
  // What the coupling adds beyond its linear parts of kinds the design
  // cannot identify (identifiable_parts_unresolved()); -1: not a single
  // coupling, or none of its linear parts is such a kind.
  double identifiable_parts_oracle = -1.0;
  // A reversal along the body diagonals (alone): what its growth along the
  // travel adds, on the fresh measurement, to its jump (the part every axis
  // shares there); -1: not such a case.
  double growth_oracle = -1.0;
  // A uniform drift along the body diagonals (alone): what it adds, on the
  // fresh measurement, beyond the same course in time in another direction
  // (the least over the two others); -1: not such a case.
  double direction_oracle = -1.0;
  // A drift named with alternatives that are all forms of the same drift
  // (same_drift_form): counted right, and apart in the table.
  bool by_form = false;
  // A growing reversal named with alternatives that are all other axes'
  // jumps ("reversal Z→Z (its jump)": every axis reverses at once, the
  // growth tells the axis, the jump does not): counted right by its growth,
  // and apart in the table.
  bool by_jump = false;
  // A cycle named with its period unresolved (other_periods_mm), graded on
  // kind, axis and direction (consistent()).
  bool by_period = false;
  std::vector<std::string> log;       // the diagnosis's selection log
  std::vector<SelectedTerm> effects;  // what the diagnosis selected
};

// The tool tip a measured point stands for (to evaluate a hidden shape there).
sim::TipState tip_at(const PointContext& pc) {
  sim::TipState tip;
  tip.p = pc.p;
  tip.tool_length = pc.s.z() - pc.p.z();
  tip.dir = pc.dir;
  tip.time = pc.t;
  return tip;
}

// What the hidden deviation adds, on the fresh measurement `fp`, beyond its
// best fit by the columns L beside the datum: 1 − rms(data − truth) /
// rms(data − that fit), the datum removed from both (`orc`: the data less
// the truth). `coef`: the fit's coefficients.
double oracle_beyond(const Problem& fp, const Eigen::VectorXd& orc, const Eigen::MatrixXd& L,
                     bool plane, Eigen::VectorXd* coef = nullptr) {
  Eigen::MatrixXd Ld(L.rows(), L.cols());
  for (Eigen::Index k = 0; k < L.cols(); ++k) Ld.col(k) = remove_datum(fp, L.col(k), plane);
  const Eigen::VectorXd beta = Ld.colPivHouseholderQr().solve(remove_datum(fp, fp.y - orc, plane));
  if (coef) *coef = beta;
  return 1.0 - rms(remove_datum(fp, orc, plane)) / rms(remove_datum(fp, fp.y - L * beta, plane));
}

// Gross outliers: `fraction` of the points get one measured component
// (dn on the ballbar) 20–50 µm off, sign at random. Returns their lines.
std::set<std::size_t> add_outliers(io::MeasuredData& data, std::uint64_t seed, double fraction) {
  std::mt19937_64 rng(seed * 104729 + 3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::set<std::size_t> lines;
  const auto n =
      static_cast<std::size_t>(std::lround(fraction * static_cast<double>(data.rows.size())));
  while (lines.size() < n) {
    io::MeasuredRow& r = data.rows[static_cast<std::size_t>(rng() % data.rows.size())];
    if (!lines.insert(r.line).second) continue;
    const double off = (u(rng) < 0.5 ? -1.0 : 1.0) * (20.0 + 30.0 * u(rng));
    if (r.has_dn()) {
      r.dn += off;
      continue;
    }
    std::vector<std::size_t> present;
    for (std::size_t k = 0; k < 3; ++k)
      if (r.has(static_cast<int>(k))) present.push_back(k);
    r.d[present[static_cast<std::size_t>(rng() % present.size())]] += off;
  }
  return lines;
}

// The truth machine differs from its model by more than the hidden effect:
// its tables were measured by a laser campaign with its own noise, so the
// model leaves the machine's own error at every point (0.28–0.32 µm rms on
// the grid's and the plate's points after the datum: below the tuned noise,
// above a laser tracer's). A diagnosis that names it
// names what the simulation gets wrong, which is its task. A name that is
// not the hidden effect's counts as the machine's own where that error —
// the truth without noise and without the hidden effect, against the
// model, at the same points, datum removed (`own`) — holds at least
// kMachineShare of the named shape as fitted, with its sign: the least-
// squares coefficient of `own` on the fitted term's values is ≥ 0.5.
constexpr double kMachineShare = 0.5;
bool of_the_machine(const Problem& pb, const Eigen::VectorXd& own, const Term& t, bool plane) {
  if (own.size() != static_cast<Eigen::Index>(pb.obs.size())) return false;
  Eigen::VectorXd v(own.size());
  for (std::size_t o = 0; o < pb.obs.size(); ++o)
    v[static_cast<Eigen::Index>(o)] = pb.obs[o].u.dot(t.evaluate(pb.points[pb.obs[o].point]));
  const Eigen::VectorXd vd = remove_datum(pb, v, plane);
  const double vv = vd.squaredNorm();
  return vv > 0.0 && vd.dot(own) / vv >= kMachineShare;
}

// `no_directions`: the measured file without vx vy vz, diagnosed with the
// approach directions inferred from the order of the points.
Case run_case(Design design, const Hidden& h, std::uint64_t seed, double outliers = 0.0,
              const SelectionOptions* selection = nullptr, bool no_directions = false,
              const DesignAmbiguityOptions* design_options = nullptr,
              const RivalOptions* rival_options = nullptr) {
  const auto& vm = noisy_vm();
  const auto samples = make_design(design);
  const bool plane = design == Design::plane;
  io::MeasuredData data = measure(samples, h, seed, plane);
  if (no_directions)
    for (io::MeasuredRow& r : data.rows) r.v = {0, 0, 0};
  std::set<std::size_t> bad;
  if (outliers > 0.0) bad = add_outliers(data, seed, outliers);
  if (no_directions) io::infer_approach_directions(data);
  const Problem pb = build_problem(vm.machine, data, model::ModelKind::ae_arm, nullptr);
  DiagnoseOptions opt;
  if (selection) opt.selection = *selection;
  if (design_options) opt.design = *design_options;
  if (rival_options) opt.rivals = *rival_options;
  opt.selection.seed = seed;
  const Diagnosis d = diagnose_problem(pb, opt);
  // The machine's own error at these points (of_the_machine()).
  io::MeasuredData own_data = measure(samples, Hidden{}, seed, plane, 0.0);
  if (no_directions) {
    for (io::MeasuredRow& r : own_data.rows) r.v = {0, 0, 0};
    io::infer_approach_directions(own_data);
  }
  const Problem own_pb = build_problem(vm.machine, own_data, model::ModelKind::ae_arm, nullptr);
  const Eigen::VectorXd own = remove_datum(own_pb, own_pb.y, plane);

  Case c;
  c.log = d.log;
  c.effects = d.effects;
  c.injected = bad.size();
  for (const Outlier& o : d.outliers) (bad.count(o.line) ? c.flagged : c.false_flags) += 1;
  c.noise_um = d.noise_um;
  c.noise_independent_um = d.noise_independent_um;
  bool truth_named = false, truth_ambiguous = false, wrong = false, any = false;
  bool truth_named_by_form = false;
  bool truth_named_by_growth = false;
  std::vector<std::pair<int, double>> linear_parts;  // named linear parts: axis, coefficient
  for (const SelectedTerm& st : d.effects) {
    double ss = 0.0;
    for (const Observation& ob : pb.obs) {
      const double v = ob.u.dot(st.term.evaluate(pb.points[ob.point]));
      ss += v * v;
    }
    std::string alt;
    for (const auto& a : st.ambiguous_with) alt += (alt.empty() ? " ~ " : " | ") + a;
    for (double p : st.other_periods_mm) alt += fmt::format(" or period {:.4g} mm", p);
    const bool by_period = !st.other_periods_mm.empty();
    bool hidden_part = h.shape != Shape::none && consistent(st.term, h, by_period);
    for (const Hidden& other : h.also)
      hidden_part = hidden_part || consistent(st.term, other, by_period);
    const bool machine = !is_datum(st.term) && st.term.kind != TermKind::unexplained &&
                         !hidden_part && of_the_machine(pb, own, st.term, plane);
    c.of_machine.push_back(machine);
    c.found += fmt::format(" [{} {:.2f}{}{}]", st.term.label(),
                           std::sqrt(ss / static_cast<double>(pb.obs.size())), alt,
                           machine ? " (the machine's)" : "");
    if (is_datum(st.term)) continue;
    if (st.term.kind == TermKind::unexplained) continue;
    if (!st.significant) continue;  // its uncertainty exceeds its value: not a name
    if (machine) {
      ++c.machine_names;
      continue;
    }
    any = true;
    if (h.shape != Shape::none && consistent(st.term, h, by_period)) {
      if (!sign_right(st.term, h)) {
        wrong = true;
      } else if (st.ambiguous_with.empty() && is_truth(st.term, h, by_period)) {
        truth_named = true;
        c.by_period = c.by_period || by_period;
      } else if (is_truth(st.term, h, by_period) &&
                 std::all_of(st.ambiguous_with.begin(), st.ambiguous_with.end(),
                             [&](const std::string& a) { return same_drift_form(a, h); })) {
        // Ambiguous only in the drift's form: its kind and direction named.
        truth_named_by_form = true;
      } else if (h.shape == Shape::reversal && st.term.degree >= 1 &&
                 is_truth(st.term, h, by_period) &&
                 std::all_of(st.ambiguous_with.begin(), st.ambiguous_with.end(),
                             [](const std::string& a) {
                               return a.find(" (its jump)") != std::string::npos;
                             })) {
        // Ambiguous only in whose jump it is: the growth's axis named.
        truth_named_by_growth = true;
      } else {
        if (h.shape == Shape::coupling && st.ambiguous_with.empty() && !st.term.coef.empty())
          linear_parts.emplace_back(st.term.axis, st.term.coef[0]);
        truth_ambiguous = true;
      }
      continue;
    }
    // A name that is not the truth: ambiguous when it says so, wrong when not.
    if (!st.ambiguous_with.empty()) {
      truth_ambiguous = true;
    } else {
      wrong = true;
    }
  }
  if (wrong) {
    c.verdict = Verdict::wrong;
  } else if (truth_named || truth_named_by_form || truth_named_by_growth) {
    c.verdict = Verdict::right;
    c.by_form = !truth_named && truth_named_by_form;
    c.by_jump = !truth_named && !truth_named_by_form;
  } else if (truth_ambiguous || any) {
    c.verdict = Verdict::ambiguous;
  } else {
    c.verdict = Verdict::none;
  }

  // Gain on a fresh measurement of the same truth machine (new noise, new datum).
  const io::MeasuredData fresh = measure(samples, h, seed + 100000, plane);
  const Problem fp = build_problem(vm.machine, fresh, model::ModelKind::ae_arm, nullptr);
  Eigen::VectorXd ext = fp.y, orc = fp.y;
  const Box b = box();
  std::vector<Hidden> parts;
  if (!h.also.empty()) {
    parts.push_back(h);
    parts.front().also.clear();
    for (const Hidden& other : h.also) parts.push_back(other);
  }
  std::vector<Eigen::VectorXd> part_orc(parts.size(), fp.y);
  for (std::size_t o = 0; o < fp.obs.size(); ++o) {
    const auto& ob = fp.obs[o];
    const PointContext& pc = fp.points[ob.point];
    Eigen::Vector3d pred = Eigen::Vector3d::Zero();
    for (const SelectedTerm& st : d.effects)
      if (!is_datum(st.term)) pred += st.term.evaluate(pc);
    const auto row = static_cast<Eigen::Index>(o);
    ext[row] -= ob.u.dot(pred);
    const sim::TipState tip = tip_at(pc);
    orc[row] -= ob.u.dot(h.at(tip, b));
    for (std::size_t k = 0; k < parts.size(); ++k)
      part_orc[k][row] -= ob.u.dot(parts[k].at(tip, b));
  }
  const double base = rms(remove_datum(fp, fp.y, plane));
  // Part k's own gain: the data with every other part taken out, then k.
  if (parts.size() == 2) {
    const double both_out = rms(remove_datum(fp, orc, plane));
    c.part_oracle.push_back(1.0 - both_out / rms(remove_datum(fp, part_orc[1], plane)));
    c.part_oracle.push_back(1.0 - both_out / rms(remove_datum(fp, part_orc[0], plane)));
  }
  c.gain = 1.0 - rms(remove_datum(fp, ext, plane)) / base;
  c.oracle = 1.0 - rms(remove_datum(fp, orc, plane)) / base;
  c.gain_ok = c.gain >= 0.7 * c.oracle;
  if (design == Design::grid_one_pass && h.shape == Shape::drift && h.also.empty()) {
    // Walked once, time follows the Z levels: the drift's best function of
    // the levels, fitted to the hidden deviation beside the datum.
    std::vector<double> levels;          // distinct z
    std::vector<Eigen::Index> level_of;  // per point
    for (const PointContext& pc : fp.points) {
      auto at = std::find_if(levels.begin(), levels.end(),
                             [&](double z) { return std::abs(z - pc.s.z()) < 1e-6; });
      if (at == levels.end()) at = levels.insert(levels.end(), pc.s.z());
      level_of.push_back(static_cast<Eigen::Index>(at - levels.begin()));
    }
    const Eigen::Index per = h.proportional ? 2 : 1;
    Eigen::MatrixXd L =
        Eigen::MatrixXd::Zero(fp.y.size(), per * static_cast<Eigen::Index>(levels.size()));
    for (std::size_t o = 0; o < fp.obs.size(); ++o) {
      const auto& ob = fp.obs[o];
      const PointContext& pc = fp.points[ob.point];
      const Eigen::Index q = level_of[ob.point];
      const auto row = static_cast<Eigen::Index>(o);
      L(row, per * q) = ob.u[h.dir];
      if (h.proportional) L(row, per * q + 1) = ob.u[h.dir] * (pc.s[h.dir] - fp.travel_mid[h.dir]);
    }
    c.course_oracle = oracle_beyond(fp, orc, L, plane);
  }
  if (along_diagonals(design) && h.shape == Shape::reversal && h.also.empty()) {
    // The jump alone (the same for X, Y and Z along a body diagonal),
    // fitted to the hidden deviation beside the datum.
    Eigen::MatrixXd L(fp.y.size(), 1);
    for (std::size_t o = 0; o < fp.obs.size(); ++o) {
      const auto& ob = fp.obs[o];
      L(static_cast<Eigen::Index>(o), 0) =
          ob.u[h.dir] * 0.5 * fp.points[ob.point].dir[static_cast<std::size_t>(h.axis)];
    }
    c.growth_oracle = oracle_beyond(fp, orc, L, plane);
  }
  if (along_diagonals(design) && h.shape == Shape::drift && !h.proportional && h.also.empty()) {
    // The hidden course in time, moved to each other direction and fitted
    // to the hidden deviation beside the datum.
    std::vector<double> course(fp.points.size());
    for (std::size_t q = 0; q < fp.points.size(); ++q)
      course[q] = h.at(tip_at(fp.points[q]), b)[h.dir];
    c.direction_oracle = 1.0;
    for (int j = 0; j < 3; ++j) {
      if (j == h.dir) continue;
      Eigen::MatrixXd L(fp.y.size(), 1);
      for (std::size_t o = 0; o < fp.obs.size(); ++o)
        L(static_cast<Eigen::Index>(o), 0) = fp.obs[o].u[j] * course[fp.obs[o].point];
      c.direction_oracle = std::min(c.direction_oracle, oracle_beyond(fp, orc, L, plane));
    }
  }
  if (h.shape == Shape::coupling && h.also.empty()) {
    // The best linear part: slopes along the coupling's two axes (about the
    // travel's middle), fitted to the hidden deviation beside the datum.
    Eigen::MatrixXd L(fp.y.size(), 2);
    for (std::size_t o = 0; o < fp.obs.size(); ++o) {
      const auto& ob = fp.obs[o];
      const PointContext& pc = fp.points[ob.point];
      const auto row = static_cast<Eigen::Index>(o);
      L(row, 0) = ob.u[h.dir] * (pc.s[h.axis] - fp.travel_mid[h.axis]);
      L(row, 1) = ob.u[h.dir] * (pc.s[h.with] - fp.travel_mid[h.with]);
    }
    Eigen::VectorXd slope;
    c.product_oracle = oracle_beyond(fp, orc, L, plane, &slope);
    for (const auto& [axis, coef] : linear_parts)
      if (coef * slope[axis == h.axis ? 0 : 1] > 0.0) c.linear_part_named = true;
    // Its linear parts of kinds the design cannot identify (a scale along
    // the direction's own axis, else a squareness, by identifiable()): what
    // the coupling adds beyond their best fit beside the datum, on the
    // fresh measurement (on a circle with one coordinate fixed the product
    // is itself such a linear part).
    Eigen::MatrixXd U(fp.y.size(), 2);
    Eigen::Index unnamed = 0;
    for (Eigen::Index k = 0; k < 2; ++k) {
      Hidden part;
      part.axis = k == 0 ? h.axis : h.with;
      part.dir = h.dir;
      part.shape = part.axis == h.dir ? Shape::scale : Shape::squareness;
      if (!identifiable(design, part)) U.col(unnamed++) = L.col(k);
    }
    if (unnamed > 0)
      c.identifiable_parts_oracle = oracle_beyond(fp, orc, U.leftCols(unnamed), plane);
  }
  return c;
}

// The verdict a case is scored with. An off-centre coupling whose product
// part the design does not resolve (the oracle gains less than kResolvable
// from it beyond the coupling's best linear part, product_oracle) is a
// scale and squareness to these data: named by an unambiguous linear part
// with that part's sign, it counts as named right, as a drift that grows
// with the position does by its mean scale (consistent()). Every such case
// is counted apart in the table (Rates::by_linear_part).
// A part's oracle (product, course, beyond the unnamed parts) that was
// measured for the case (not -1) and is below what the design resolves.
bool measured_below_resolution(double part_oracle) {
  return part_oracle > -0.5 && part_oracle < kResolvable;
}

Verdict scored(const Case& c, const Hidden& h, bool* by_linear_part = nullptr) {
  const bool upgrade = h.shape == Shape::coupling && measured_below_resolution(c.product_oracle) &&
                       c.verdict == Verdict::ambiguous && c.linear_part_named;
  if (by_linear_part) *by_linear_part = upgrade;
  return upgrade ? Verdict::right : c.verdict;
}

// Walked once, time follows the Z levels (grid_one_pass): a drift whose
// course within each level adds less than kResolvable to its best function
// of the levels (course_oracle) is such a function to these data, as
// identifiable() says — counted with the cases the design cannot identify
// (a drift named there is named by luck, a name of a function of z wrong).
bool course_unresolved(const Case& c) { return measured_below_resolution(c.course_oracle); }

// Along the body diagonals a reversal's axis is told only by its growth
// along the travel: where the growth adds less than kResolvable to the
// jump (growth_oracle) the case is counted with those the design cannot
// identify.
bool growth_unresolved(const Case& c) { return measured_below_resolution(c.growth_oracle); }

// Along the body diagonals a uniform drift's axis is told only by the sign
// pattern of its projection over the four lines: where the drift adds less
// than kResolvable beyond the same course in time in another direction
// (direction_oracle, the least over the two) the case is counted with
// those the design cannot identify, as a reversal whose growth is not
// resolved is.
bool direction_unresolved(const Case& c) { return measured_below_resolution(c.direction_oracle); }

// An off-centre coupling is a product part plus a scale or squareness along
// each of its axes. Where it adds less than kResolvable beyond its linear
// parts of kinds the design cannot identify (identifiable_parts_oracle: on
// the ballbar's circles a squareness, on a plate a squareness, at one Z a
// d_z ∝ x or y), what the design resolves of the coupling is a kind it
// cannot name: the case is counted with the cases it cannot identify.
bool identifiable_parts_unresolved(const Case& c) {
  return measured_below_resolution(c.identifiable_parts_oracle);
}

int seeds() {
  const char* s = std::getenv("ABBE_DIAGNOSE_SEEDS");  // the `slow` sweep sets 200
  return s ? std::max(1, std::atoi(s)) : 40;
}

// ABBE_DIAGNOSE_CASE=i: run only case i of the sweep and print the
// diagnosis's selection log (to look into one case of the table).
int only_case() {
  const char* s = std::getenv("ABBE_DIAGNOSE_CASE");
  return s ? std::atoi(s) : -1;
}

struct Rates {
  int n_id = 0, id_right = 0, id_wrong = 0;
  int by_linear_part = 0;    // of id_right: a coupling by its linear part (scored())
  int by_course = 0;         // of n_un: a drift whose course within a level is not resolved
  int by_growth = 0;         // of n_un: a reversal whose growth is not resolved (diagonals)
  int by_direction = 0;      // of n_un: a drift whose direction is not resolved (diagonals)
  int by_form = 0;           // of id_right: a drift ambiguous only in its form (Case::by_form)
  int by_jump = 0;           // of id_right: a reversal ambiguous only in its jump (Case::by_jump)
  int by_period = 0;         // of id_right: a cycle named with its period unresolved
  int by_unnamed_parts = 0;  // of n_un: identifiable_parts_unresolved()
  int n_un = 0, un_ambiguous = 0, un_wrong = 0;  // "ambiguous" here: ambiguous or nothing named
  int n_null = 0, null_clean = 0;
  // Names of the truth machine's own error set apart (of_the_machine()), and
  // the cases with one.
  int machine_names = 0, machine_cases = 0;
  int gain_ok = 0, n_gain = 0;
  // Identifiable cases by the oracle's gain (the effect's size as the design
  // sees it): below 0.08, 0.08–0.12, from 0.12; named right in each.
  std::array<int, 3> n_band{}, right_band{};

  // Counts a null case; its tag for the log.
  std::string add_null(Verdict v) {
    ++n_null;
    const bool clean = v == Verdict::none;
    null_clean += clean ? 1 : 0;
    return clean ? "null ok" : "null NAMED";
  }
  // Counts a case whose effect the design can name; its tag for the log.
  std::string add_identifiable(Verdict v) {
    ++n_id;
    id_right += v == Verdict::right ? 1 : 0;
    id_wrong += v == Verdict::wrong ? 1 : 0;
    return v == Verdict::right ? "right" : v == Verdict::wrong ? "WRONG" : "missed";
  }
};

// Case i of a design's sweep: its hidden shape (none every fourth case)
// and its measurement seed.
std::pair<Hidden, std::uint64_t> sweep_case(Design design, int i) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(7000 + 31 * i + static_cast<int>(design)));
  Hidden h;
  if (i % 4 != 3) h = draw(rng, box(), noisy_vm().generated.truth.tool_length);
  return {h, static_cast<std::uint64_t>(100 + i)};
}

Rates sweep(Design design, bool no_directions = false) {
  const std::string label =
      std::string(design_name(design)) + (no_directions ? ", no vx vy vz (inferred)" : "") +
      (current_vm_label.empty() ? "" : ", " + current_vm_label) +
      (std::getenv("ABBE_DESIGNS_GRID") ? ", levels overridden" : "") +
      (std::getenv("ABBE_DESIGNS_NOISE") ? ", noise overridden" : "") +
      (std::getenv("ABBE_DESIGNS_DT_SCALE") ? ", time scaled" : "") +
      (std::getenv("ABBE_DESIGNS_BALLBAR_RADIUS") ? ", ballbar radius overridden" : "") +
      (std::getenv("ABBE_DESIGNS_DIAGONAL_STEP") ? ", diagonal step overridden" : "") +
      (std::getenv("ABBE_DESIGNS_PLATE_PITCH") ? ", plate pitch overridden" : "");
  const int n = seeds();
  Rates r;
  const int only = only_case();
  for (int i = only >= 0 ? only : 0; i < (only >= 0 ? only + 1 : n); ++i) {
    const auto [h, seed] = sweep_case(design, i);
    const Case c = run_case(design, h, seed, 0.0, nullptr, no_directions);
    r.machine_names += c.machine_names;
    r.machine_cases += c.machine_names > 0 ? 1 : 0;
    if (only >= 0)
      for (const std::string& line : c.log) std::cerr << "  log: " << line << "\n";
    std::string tag;
    if (h.shape == Shape::none) {
      tag = r.add_null(c.verdict);
    } else if (const bool resolvable = identifiable(design, h) && c.oracle >= kResolvable;
               resolvable && !course_unresolved(c) && !identifiable_parts_unresolved(c) &&
               !growth_unresolved(c) && !direction_unresolved(c)) {
      bool by_part = false;
      const Verdict v = scored(c, h, &by_part);
      tag = r.add_identifiable(v);
      r.by_linear_part += by_part ? 1 : 0;
      if (by_part) tag += " (linear part)";
      r.by_form += c.by_form ? 1 : 0;
      if (c.by_form) tag += " (form)";
      r.by_jump += v == Verdict::right && c.by_jump ? 1 : 0;
      if (v == Verdict::right && c.by_jump) tag += " (growth)";
      r.by_period += v == Verdict::right && c.by_period ? 1 : 0;
      if (v == Verdict::right && c.by_period) tag += " (period)";
      const std::size_t band = c.oracle < 0.08 ? 0 : c.oracle < 0.12 ? 1 : 2;
      ++r.n_band[band];
      r.right_band[band] += v == Verdict::right ? 1 : 0;
      ++r.n_gain;
      r.gain_ok += c.gain_ok ? 1 : 0;
    } else {
      ++r.n_un;
      r.by_course += resolvable && course_unresolved(c);
      r.by_growth += resolvable && growth_unresolved(c);
      r.by_direction += resolvable && direction_unresolved(c);
      r.by_unnamed_parts += resolvable && identifiable_parts_unresolved(c);
      const bool amb = c.verdict == Verdict::ambiguous || c.verdict == Verdict::none;
      r.un_ambiguous += amb ? 1 : 0;
      r.un_wrong += c.verdict == Verdict::wrong ? 1 : 0;
      tag = c.verdict == Verdict::wrong ? "unidentifiable, WRONG NAME"
            : amb                       ? "unidentifiable, not named"
                                        : "unidentifiable";
      if (c.verdict == Verdict::right) tag = "unidentifiable, named (lucky)";
    }
    std::cerr << fmt::format(
        "{} | seed {:3d} | {:<55} | {:<28} | gain {:5.2f} oracle {:5.2f}{} | noise {:.2f} ({:.2f}) "
        "|{}\n",
        label, i, h.text, tag, c.gain, c.oracle,
        c.product_oracle >= -0.5
            ? fmt::format(" product {:5.2f}{}{}", c.product_oracle,
                          c.linear_part_named ? " lin" : "",
                          c.identifiable_parts_oracle >= -0.5
                              ? fmt::format(" beyond-unnamed {:5.2f}", c.identifiable_parts_oracle)
                              : "")
        : c.course_oracle >= -0.5    ? fmt::format(" course {:5.2f}", c.course_oracle)
        : c.growth_oracle >= -0.5    ? fmt::format(" growth {:5.2f}", c.growth_oracle)
        : c.direction_oracle >= -0.5 ? fmt::format(" direction {:5.2f}", c.direction_oracle)
                                     : "",
        c.noise_um, c.noise_independent_um, c.found);
  }
  auto pct = [](int a, int b) { return b ? 100.0 * a / b : 0.0; };
  std::cerr << fmt::format(
      "RATES | {} | identifiable: right {}/{} ({:.0f} %){}, wrong {} | not identifiable: "
      "ambiguous or silent {}/{} ({:.0f} %){}, wrong {} ({:.0f} %) | null clean {}/{} | gain >= "
      "0.7 oracle "
      "{}/{} ({:.0f} %) | the machine's own names set apart {} in {} cases\n",
      label, r.id_right, r.n_id, pct(r.id_right, r.n_id),
      fmt::format(
          "{}{}{}{}",
          r.by_linear_part ? fmt::format(" ({} couplings by their linear part)", r.by_linear_part)
                           : "",
          r.by_form ? fmt::format(" ({} drifts ambiguous only in their form)", r.by_form) : "",
          r.by_jump ? fmt::format(" ({} reversals named by their growth, the jump's axis "
                                  "unresolved)",
                                  r.by_jump)
                    : "",
          r.by_period ? fmt::format(" ({} cycles with their period unresolved)", r.by_period) : ""),
      r.id_wrong, r.un_ambiguous, r.n_un, pct(r.un_ambiguous, r.n_un),
      fmt::format(
          "{}{}{}{}",
          r.by_growth ? fmt::format(" ({} reversals whose growth is below resolution)", r.by_growth)
                      : "",
          r.by_direction
              ? fmt::format(" ({} drifts whose direction is below resolution)", r.by_direction)
              : "",
          r.by_course ? fmt::format(" ({} drifts whose course within a level is below resolution)",
                                    r.by_course)
                      : "",
          r.by_unnamed_parts
              ? fmt::format(" ({} couplings resolved only in parts the design cannot name)",
                            r.by_unnamed_parts)
              : ""),
      r.un_wrong, pct(r.un_wrong, r.n_un), r.null_clean, r.n_null, r.gain_ok, r.n_gain,
      pct(r.gain_ok, r.n_gain), r.machine_names, r.machine_cases);
  std::cerr << fmt::format(
      "POWER | {} | identifiable named right by the oracle's gain: 0.05–0.08 {}/{} | 0.08–0.12 "
      "{}/{} | from 0.12 {}/{} ({:.1f} %)\n",
      label, r.right_band[0], r.n_band[0], r.right_band[1], r.n_band[1], r.right_band[2],
      r.n_band[2], pct(r.right_band[2], r.n_band[2]));
  return r;
}

// The assertions hold the rates measured at the last change of the engine
// (docs/diagnosis.md, "Measured rates"), as fractions with a small margin
// for the seed count: the issue's targets are not all reached yet and the
// table says which.
struct Floor {
  double id_right, id_wrong_max, un_wrong_max, null_clean, gain_ok;
};

void check(const Rates& r, const Floor& f) {
  // A rate over no cases holds no claim: 1 for the floors, 0 for the ceilings.
  auto frac = [](int a, int b) { return b ? static_cast<double>(a) / b : 1.0; };
  auto frac_max = [](int a, int b) { return b ? static_cast<double>(a) / b : 0.0; };
  EXPECT_GE(frac(r.id_right, r.n_id), f.id_right);
  EXPECT_LE(frac_max(r.id_wrong, r.n_id), f.id_wrong_max);
  EXPECT_LE(frac_max(r.un_wrong, r.n_un), f.un_wrong_max);
  EXPECT_GE(frac(r.null_clean, r.n_null), f.null_clean);
  EXPECT_GE(frac(r.gain_ok, r.n_gain), f.gain_ok);
}

// Floors: {identifiable named right ≥, identifiable wrong ≤, not identifiable
// wrong ≤, null clean ≥, gain ≥ 70 % of the oracle ≥}: the rates measured
// with 40 and with 200 seeds (docs/diagnosis.md), less a margin of about one
// case in ten. They hold what the engine does today; where they are looser
// than the issue's targets (grid and plate) the table says so.
// With the practical floor as a test (min_effect_test) the plate's wrong
// names and false names in null data fell, and with the outlier group
// check (group_check) the toolpath's reversals came back
// (docs/diagnosis.md): the plate's and the toolpath's floors rose. With
// what the design cannot tell apart (design_ambiguity.hpp: a cycle beside
// other functions of a levelled axis, an effect that is a reversal's
// growth) and the drift scan without the column's mean, the grid's
// unidentifiable wrong names fell 5/20 → 1/20 and the plate's 3/120 → 0
// (its identifiable wrong 1/30 → 0), the toolpath's named right rose
// 71/77 → 74/77 (200 seeds): their ceilings fell and floors rose. With a
// winning combination entering whole and the swap test after the fit
// (rival_check.hpp) the grid's named right rose 120/130 → 126/130, the
// ballbar's wrong names fell 1 → 0 and the diagonals' 3/147 → 1/147
// (200 seeds; 40 seeds: grid 25/26, toolpath 17/18 with 1 wrong, ballbar
// 22/23, diagonals 1 wrong in 30): every floor rose, none fell. The
// ballbar read through its importer: 1 wrong name in 50 cases it cannot
// identify (200 seeds), at its ceiling (0 since an arm offset is preferred
// over a rival only beyond the practical floor, RivalOptions). With rivals the data reject no
// longer reported (rivals_by_test) the ballbar's named right rose 94/100 →
// 95/100 (200 seeds; 40 seeds unchanged), nothing else changed. With a
// drift of Z identifiable at one Z (ADriftOfZIsIdentifiableAtOneZ) the
// toolpath's named right 75/77 → 78/80 (200 seeds; 40: 17/18 → 18/19).
TEST(DiagnoseDesigns, Grid) { check(sweep(Design::grid), {0.94, 0.02, 0.06, 0.95, 0.95}); }
TEST(DiagnoseDesigns, Plane) { check(sweep(Design::plane), {0.93, 0.02, 0.02, 0.95, 0.9}); }
TEST(DiagnoseDesigns, Toolpath) { check(sweep(Design::toolpath), {0.92, 0.06, 0.05, 0.95, 0.95}); }
TEST(DiagnoseDesigns, Ballbar) { check(sweep(Design::ballbar), {0.9, 0.02, 0.02, 0.95, 0.9}); }
// With drifts in proportion to a position compared with their zero free
// (RivalOptions::zero_free_drifts) the diagonals' wrong names where not
// identifiable fell 1/147 → 0/147 (200 seeds; 1/30 → 0/30 with 40; 7/734
// → 1/734 with 1000): their ceiling fell 0.04 → 0.02. With the reversal
// that grows along its travel a reversal is identifiable where its growth
// is resolved (AReversalAlongTheDiagonalsIsToldByItsGrowth): named right
// 1/3 → 10/12 (200 seeds; 40: 0/0 → 2/2; 1000: 3/16 → 52/66), the floors
// 0 → 0.7. With a growing reversal's jump left open among the axes
// (AGrowingReversalsJumpAlongTheDiagonalsIsNotNamed) nothing moved at 200
// seeds (1000: wrong where not identifiable 1/692 → 0/692).
TEST(DiagnoseDesigns, Diagonals) { check(sweep(Design::diagonals), {0.7, 0.02, 0.02, 0.95, 0.7}); }
// The same lines measured as the laser lines are (ISO 230-2's five runs
// there and back on each): 5/5 named right, 0 wrong, 0/145 wrong where not
// identifiable (200 seeds; 40 seeds: 3/3, 0, 0/27; 1000 seeds: 50/50, 0,
// 0/700; 1/700, an off-centre coupling x·z→X named with an arm offset
// εZ×ΔY, before AnArmOffsetIsTheLinearPartOfACouplingOffItsCentre).
// Before AUniformDriftBesideAnAmbiguousProportionalDriftIsItsZeroAsMuch and
// AUniformDriftIsTheZeroOfEveryProportionalDriftThatFitsAsMuch, 4 more:
// drifts ∝ (x − x0)·t of X, their proportional part `ambiguous` among the
// three directions, named with a uniform drift of another direction.
TEST(DiagnoseDesigns, DiagonalsFiveRuns) {
  check(sweep(Design::diagonals_runs), {0.9, 0.02, 0.03, 0.95, 0.9});
}
// A grid walked once (9 × 7 × 3): 82/88 named right, 0 wrong, 0/62 wrong
// where not identifiable (200 seeds; 40 seeds: 16/18, 0, 0/12). ISO 230-2
// laser lines along the three axes: 94/96, 1 wrong (case 45: a cycle of Z
// at 13.15 mm beside the pitch error's 40.13 mm), 0/54 (40 seeds: 15/15,
// 0, 0/15). With the chosen cycles' periods refined on the fit
// (exact_period) 92 → 93/96 and 3 → 2 wrong; with the cycle period test's
// margin the levels' noise (level_noise_margin) 94/96 and 1 wrong. A ballbar in XY
// only: 64/69, 0 wrong, 0/81 (40 seeds: 12/14, 0, 0/16; the misses were
// drifts of Y that one circle pair cannot tell from a drift ∝ x); with a
// drift ambiguous only in its form counted as named (same_drift_form())
// 68/69 (40 seeds: 14/14; 1000 seeds: 297/318, 93.4 %): its floors rose
// from 0 to 0.9.
// With a drift identifiable only where its course within the levels is
// resolved (course_unresolved()): 72/75, 0 wrong, 0/75 wrong where not
// identifiable (200 seeds; 40 seeds: 14/15, 0, 0/15; 1000 seeds: 337/352,
// 1, 1/398), the floor for named right 0.85 → 0.88. With a coupling counted
// only beyond its parts the design cannot name
// (identifiable_parts_unresolved()): 72/74 (40 seeds: 14/14; 1000 seeds:
// 337/350); the ballbar 96/100 → 96/99 (1000 seeds: 471/500 → 471/495), the
// plate 163/172 → 163/171 and the toolpath 400/405 → 399/404 (1000 seeds).
TEST(DiagnoseDesigns, GridOnePass) {
  check(sweep(Design::grid_one_pass), {0.88, 0.02, 0.02, 0.95, 0.85});
}
// The grid's file without vx vy vz, the approach directions inferred from
// the order of the points (diagnose --infer-directions): 129/130 named right,
// 1/20 wrong where not identifiable, as with the file's own directions (200
// seeds). Without them the model takes the mean of its up and down tables,
// the machine's own reversal of Z is left as `unexplained` dZ(z, t) of about
// 4 µm rms in every case, and the oracle of most hidden shapes falls below
// what the design resolves.
TEST(DiagnoseDesigns, GridWithoutDirectionsInferred) {
  check(sweep(Design::grid, true), {0.94, 0.02, 0.06, 0.95, 0.95});
}
// The grid at irregular levels (what design_ambiguity recommends for a
// pitch error): 119/125 named right with the pitch errors of X, 1 wrong —
// case 22, a cycle of X at 10.89 mm for a pitch error of 39.9 mm — and 0/25
// where not identifiable (200 seeds; 40 seeds: 23/25, 1, 0/5). Before the
// cycle period test's margin was the levels' noise: 118/125, 3 wrong. A pitch error counts as named
// only at its period or its harmonic's (consistent()).
TEST(DiagnoseDesigns, GridIrregular) {
  check(sweep(Design::grid_irregular), {0.9, 0.05, 0.02, 0.95, 0.95});
}
TEST(DiagnoseDesigns, BallbarXY) { check(sweep(Design::ballbar_xy), {0.9, 0.02, 0.02, 0.95, 0.9}); }
TEST(DiagnoseDesigns, AxisLines) {
  check(sweep(Design::axis_lines), {0.93, 0.04, 0.02, 0.95, 0.95});
}

// The same designs on a machine the engine was not tuned on (gantry_vm():
// another profile, seed and chain), each with its floors: the rates there
// at 40 seeds (docs/diagnosis.md, "On machines it was not tuned on"), less
// a margin of about one case in ten. Not in the 200-seed sweeps (their
// 300-seed rates are in the docs).
struct GantrySweep {
  Design design;
  Floor floor;
};
class DiagnoseDesignsOnAGantry : public ::testing::TestWithParam<GantrySweep> {};
TEST_P(DiagnoseDesignsOnAGantry, Rates) {
  const OnMachine on(gantry_vm(), "gantry (generic, seed 11)");
  check(sweep(GetParam().design), GetParam().floor);
}
const GantrySweep kGantrySweeps[] = {{Design::grid, {0.94, 0.02, 0.06, 0.95, 0.95}},
                                     {Design::plane, {0.9, 0.02, 0.02, 0.8, 0.9}},
                                     {Design::toolpath, {0.92, 0.06, 0.05, 0.95, 0.95}},
                                     {Design::ballbar, {0.85, 0.05, 0.05, 0.95, 0.9}},
                                     {Design::diagonals, {0.5, 0.02, 0.05, 0.95, 0.5}},
                                     {Design::axis_lines, {0.9, 0.02, 0.05, 0.95, 0.95}},
                                     {Design::grid_one_pass, {0.85, 0.05, 0.05, 0.95, 0.85}},
                                     {Design::ballbar_xy, {0.85, 0.02, 0.02, 0.95, 0.9}},
                                     {Design::grid_irregular, {0.85, 0.05, 0.05, 0.95, 0.95}},
                                     {Design::diagonals_runs, {0.5, 0.02, 0.05, 0.95, 0.5}}};
std::string gantry_sweep_name(const ::testing::TestParamInfo<GantrySweep>& info) {
  static const char* const names[] = {
      "Grid",      "Plane",   "Toolpath",  "Ballbar",       "Diagonals",
      "AxisLines", "OnePass", "BallbarXY", "GridIrregular", "DiagonalsFiveRuns"};
  return names[static_cast<int>(info.param.design)];
}
INSTANTIATE_TEST_SUITE_P(Designs, DiagnoseDesignsOnAGantry, ::testing::ValuesIn(kGantrySweeps),
                         gantry_sweep_name);

// Two effects together on the grid (issue 16: "both named"): two
// identifiable hidden shapes of different kinds or axes, each 3–20× the
// noise, in the same data. A case is right when each is named (its kind,
// axis, direction and sign, not ambiguous); a name that is part of
// neither is wrong.
// Case i of the two-effect sweep: two identifiable hidden shapes of the
// harness (different kind, axis or direction) in the same grid data.
struct TwoEffects {
  Hidden h, h2;
  Case c;
  bool named[2] = {false, false};  // each named right, not ambiguous
  bool bad = false;                // a name that is part of neither, or a wrong sign
  bool resolvable = false;         // the oracle gains at least kResolvable
  bool each_resolvable = false;    // and each alone does (Case::part_oracle), not
                                   // two squarenesses of one plane
};

// Two squarenesses of one plane (d_i ∝ s_j and d_j ∝ s_i) span the same
// as one of them beside a rotation about the plane's normal, which is a
// candidate on the grid (the instrument's or the artefact's setup): the
// design cannot tell the pair from a rotation and one squareness, so
// neither is resolvable beside the other. (A squareness beside an
// off-centre coupling whose linear part is its partner is such a pair
// only where that part is large enough to be named: cases 273 and 324
// `ambiguous` with the rotation, 120, 128 and 254 both named. Those stay
// counted as resolvable.)
bool one_plane_squarenesses(const Hidden& a, const Hidden& b) {
  return a.shape == Shape::squareness && b.shape == Shape::squareness && a.axis == b.dir &&
         a.dir == b.axis;
}

TwoEffects two_effects_case(int i, const SelectionOptions* selection = nullptr,
                            const RivalOptions* rivals = nullptr,
                            const DesignAmbiguityOptions* design_options = nullptr) {
  const Box b = box();
  const double L = noisy_vm().generated.truth.tool_length;
  TwoEffects r;
  std::mt19937_64 rng(static_cast<std::uint64_t>(11000 + 41 * i));
  do {
    r.h = draw(rng, b, L);
  } while (!identifiable(Design::grid, r.h));
  do {
    r.h2 = draw(rng, b, L);
  } while (!identifiable(Design::grid, r.h2) ||
           (r.h2.shape == r.h.shape && r.h2.axis == r.h.axis && r.h2.dir == r.h.dir));
  Hidden pair = r.h;
  pair.also = {r.h2};
  r.c = run_case(Design::grid, pair, static_cast<std::uint64_t>(700 + i), 0.0, selection, false,
                 design_options, rivals);
  // Each effect alone must be within what the design resolves: the
  // oracle of the pair is checked, and each part's share below.
  for (std::size_t e = 0; e < r.c.effects.size(); ++e) {
    const SelectedTerm& st = r.c.effects[e];
    const Term& t = st.term;
    if (is_datum(t) || t.kind == TermKind::unexplained || !st.significant) continue;
    if (r.c.of_machine[e]) continue;  // the truth machine's own error (of_the_machine())
    bool part = false;
    for (int k = 0; k < 2; ++k) {
      const Hidden& hk = k == 0 ? r.h : r.h2;
      const bool by_period = !st.other_periods_mm.empty();
      if (!consistent(t, hk, by_period)) continue;
      part = true;
      if (!sign_right(t, hk)) r.bad = true;
      if (st.ambiguous_with.empty() && is_truth(t, hk, by_period) && sign_right(t, hk))
        r.named[k] = true;
    }
    if (!part && st.ambiguous_with.empty()) r.bad = true;
  }
  r.resolvable = r.c.oracle >= kResolvable;
  r.each_resolvable = r.resolvable && r.c.part_oracle.size() == 2 &&
                      r.c.part_oracle[0] >= kResolvable && r.c.part_oracle[1] >= kResolvable &&
                      !one_plane_squarenesses(r.h, r.h2);
  return r;
}

TEST(DiagnoseDesigns, GridTwoEffects) {
  const int n = std::max(8, seeds() / 2);
  int both = 0, one = 0, wrong = 0, resolvable = 0;
  int each = 0, both_each = 0;  // cases where each shape alone is resolvable
  const int only = only_case();
  for (int i = only >= 0 ? only : 0; i < (only >= 0 ? only + 1 : n); ++i) {
    const TwoEffects r = two_effects_case(i);
    if (only >= 0)
      for (const std::string& line : r.c.log) std::cerr << "  log: " << line << "\n";
    const bool ok = r.resolvable;
    resolvable += ok ? 1 : 0;
    both += ok && r.named[0] && r.named[1] ? 1 : 0;
    one += ok && (r.named[0] != r.named[1]) ? 1 : 0;
    wrong += r.bad ? 1 : 0;
    each += r.each_resolvable ? 1 : 0;
    both_each += r.each_resolvable && r.named[0] && r.named[1] ? 1 : 0;
    std::cerr << fmt::format(
        "two effects | seed {:3d} | {} + {} | {}{} | gain {:5.2f} oracle {:5.2f} (each {:5.2f} "
        "{:5.2f}) |",
        i, r.h.text, r.h2.text,
        r.named[0] && r.named[1]   ? "both"
        : r.named[0] || r.named[1] ? "one"
                                   : "none",
        r.bad ? ", WRONG" : "", r.c.gain, r.c.oracle, r.c.part_oracle.at(0), r.c.part_oracle.at(1));
    for (const SelectedTerm& st : r.c.effects) {
      std::string alt;
      for (const auto& a : st.ambiguous_with) alt += (alt.empty() ? " ~ " : " | ") + a;
      std::cerr << fmt::format(" [{}{}]", st.term.label(), alt);
    }
    std::cerr << "\n";
  }
  std::cerr << fmt::format(
      "RATES | grid, two hidden effects | both named {}/{} , one {} , wrong names in {} cases | "
      "where each alone is resolvable: both named {}/{}\n",
      both, resolvable, one, wrong, both_each, each);
  // Measured: 17/20 both named with 20 cases, 91/100 with 100 (92/100
  // before a combination's lead had its rivals, 90/100 before the revisit
  // of the first step; the misses name one of the two:
  // the other smaller or a drift ∝ s left as a smooth function), no case
  // with a wrong name in either. Where each shape alone is resolvable (its
  // own oracle gain ≥ 5 % once the other is taken out, and not two
  // squarenesses of one plane): 17/18 and 91/98; 456/471 with 500 cases
  // (456/473 before such pairs were set apart: cases 124 and 398).
  EXPECT_GE(resolvable ? static_cast<double>(both) / resolvable : 1.0, 0.8);
  EXPECT_GE(each ? static_cast<double>(both_each) / each : 1.0, 0.8);
  EXPECT_LE(static_cast<double>(wrong) / std::max(resolvable, 1), 0.02);
}

// Two squarenesses of one plane on the grid (two-effect cases 124 and 398:
// dX ∝ y and dY ∝ x) are one span with a rotation about Z beside the datum: the
// three columns have rank 2 (and a rotation about X, not in that span,
// makes it 3). The engine names one squareness and reports the rest
// `ambiguous` between the other squareness and the setup rotation; the
// sweep does not count the pair among those each resolvable.
TEST(DiagnoseDesigns, TwoSquarenessesOfOnePlaneAreOneSpanWithARotation) {
  for (const int i : {124, 398}) {
    SCOPED_TRACE(i);
    const TwoEffects r = two_effects_case(i);
    ASSERT_TRUE(one_plane_squarenesses(r.h, r.h2));
    EXPECT_FALSE(r.each_resolvable);
    EXPECT_GE(r.c.part_oracle.at(0), kResolvable);  // each alone would count
    EXPECT_GE(r.c.part_oracle.at(1), kResolvable);
    EXPECT_FALSE(r.bad);
    bool rotation_alternative = false;
    for (const SelectedTerm& st : r.c.effects)
      for (const std::string& a : st.ambiguous_with)
        if ((st.term.kind == TermKind::setup_rotation &&
             a.find("squareness") != std::string::npos) ||
            (st.term.kind == TermKind::squareness && a.find("rotation") != std::string::npos))
          rotation_alternative = true;
    EXPECT_TRUE(rotation_alternative);
  }
  const TwoEffects r = two_effects_case(124);

  const io::MeasuredData data = measure(make_design(Design::grid), Hidden{}, 5, false);
  const Problem pb = build_problem(noisy_vm().machine, data, model::ModelKind::ae_arm, nullptr);
  const Box b = box();
  const Eigen::Vector3d c = 0.5 * (b.lo + b.hi);
  auto rank_with = [&](int about) {
    Eigen::MatrixXd M(pb.y.size(), 3);
    for (std::size_t o = 0; o < pb.obs.size(); ++o) {
      const auto& ob = pb.obs[o];
      const sim::TipState tip = tip_at(pb.points[ob.point]);
      const Eigen::Vector3d q = tip.p - c;
      const auto row = static_cast<Eigen::Index>(o);
      M(row, 0) = ob.u.dot(r.h.at(tip, b));
      M(row, 1) = ob.u.dot(r.h2.at(tip, b));
      M(row, 2) = ob.u.dot(Eigen::Vector3d::Unit(about).cross(q));
    }
    for (Eigen::Index k = 0; k < 3; ++k) {
      M.col(k) = remove_datum(pb, M.col(k), false);
      M.col(k).normalize();
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M);
    qr.setThreshold(1e-9);
    return qr.rank();
  };
  EXPECT_EQ(rank_with(2), 2);
  EXPECT_EQ(rank_with(0), 3);
}

// Whether one line of the selection log holds both texts.
bool logged(const Case& c, const std::string& what, const std::string& verdict) {
  return std::any_of(c.log.begin(), c.log.end(), [&](const std::string& line) {
    return line.find(what) != std::string::npos && line.find(verdict) != std::string::npos;
  });
}

// The revisit of the first step (SelectionOptions::revisit_paths). Case
// 51 (a drift of X at τ 2 099 s beside an off-centre coupling y·z→X) took
// the drift at τ 900 s first, which took a part of the coupling, and a
// smooth dX(z,t) the rest; case 68 (a scale of X beside the same kind of
// coupling) took a drift x·t→X at τ 300 s first for the scale, `ambiguous`
// with it. From the first step's near alternatives (the drift at 1 800 s;
// the scale) the coupling with its squareness parts is named, and those
// paths are better on the criterion and held out.
TEST(DiagnoseDesigns, TheFirstStepIsRevisited) {
  // With the best smooth function's variables only: those of another that
  // finds the structure as well name case 68 on the first path
  // (AStructureTwoSmoothFunctionsFindIsExplainedFromEither).
  SelectionOptions best_vars;
  best_vars.structure_near_share = 0.0;
  // And without the drift's course floor, which names case 68's scale at
  // the first step (ADriftWhoseCourseIsNotResolvedIsItsStaticForm).
  best_vars.drift_course_floor = false;
  // And with the drift at its grid's τ: with its τ refined (exact_tau)
  // case 51's first path names both (the drift at 900 s no longer takes a
  // part of the coupling).
  best_vars.exact_tau = false;
  best_vars.refine_tau = false;
  SelectionOptions without = best_vars;
  without.revisit_paths = 0;
  for (const int i : {51, 68}) {
    const TwoEffects with = two_effects_case(i, &best_vars);
    EXPECT_TRUE(with.named[0] && with.named[1]) << "case " << i;
    EXPECT_FALSE(with.bad) << "case " << i;
    EXPECT_TRUE(logged(with.c, "revisit:", ": taken")) << "case " << i;
    const TwoEffects off = two_effects_case(i, &without);
    EXPECT_FALSE(off.named[0] && off.named[1]) << "case " << i;
    for (const std::string& line : off.c.log) EXPECT_NE(line.rfind("revisit:", 0), 0u) << line;
  }
}

// A drift that grows with the position, t/(t+τ)·(s − s0), beside another
// effect: the first significant part of the structure (an aliased cycle or
// a scale) leads no combination that explains it, but the drift ∝ s with a
// drift of its own time constant does (SelectionOptions::combination_leads;
// cases 36 and 90 of the two-effect sweep, both named only with it).
// Two-effect cases that name both effects with the default rules and not
// with `without` (a rule switched off): the rule is what names them.
void expect_both_named_only_with_the_rule(const std::vector<int>& cases,
                                          const SelectionOptions& without,
                                          const SelectionOptions* rules = nullptr) {
  for (int i : cases) {
    const TwoEffects with = two_effects_case(i, rules);
    EXPECT_TRUE(with.named[0] && with.named[1]) << "case " << i << ": " << with.c.found;
    EXPECT_FALSE(with.bad) << "case " << i;
    const TwoEffects off = two_effects_case(i, &without);
    EXPECT_FALSE(off.named[0] && off.named[1]) << "case " << i << ": " << off.c.found;
  }
}

// Case i of the two-effect sweep logs one line that holds both texts.
void expect_logged(int i, const std::string& what, const std::string& verdict,
                   const SelectionOptions* rules = nullptr) {
  const TwoEffects t = two_effects_case(i, rules);
  EXPECT_TRUE(logged(t.c, what, verdict)) << "case " << i << ": " << t.c.found;
}

// The revisit from a static first pick in place of a drift
// (SelectionOptions::revisit_searched_first). Case 249 of the two-effect
// sweep (a squareness dY ∝ z beside a drift of Y, t/(t+τ) at τ 2 797 s):
// on the grid, walked level by level, a drift z·t→Y at τ 1 800 s took the
// squareness and part of the drift at the first step (ΔRSS 4 808 against
// the squareness's 4 562), a drift t→Y at 600 s the rest. Case 483 (a
// scale of Z beside a drift of Z): a drift z·t→Z at 900 s for both. From
// the squareness (the scale) both are named, and those paths are better on
// the criterion (1 009.6 against 1 058.4; 1 000.2 against 1 084.7) and held
// out. Case 409 (an off-centre coupling x·z→X beside a drift ∝ y of Y):
// the path from a scale of Y is better on both too, but ends with two
// drifts for the kept path's one and names an arm offset that is part of
// neither effect: it is not taken.
TEST(DiagnoseDesigns, AStaticFirstPickInPlaceOfADriftIsRevisited) {
  // Without the drift's course floor, which names case 483's scale at the
  // first step and case 409's scale of Y
  // (ADriftWhoseCourseIsNotResolvedIsItsStaticForm).
  SelectionOptions rules;
  rules.drift_course_floor = false;
  SelectionOptions drift_kept = rules;
  drift_kept.revisit_searched_first = false;
  expect_both_named_only_with_the_rule({249, 483}, drift_kept, &rules);
  EXPECT_FALSE(two_effects_case(409, &rules).bad);
  expect_logged(409, "first step scale Y in place of thermal_drift y·t→Y",
                "not taken, 2 effects with a searched parameter against 1", &rules);
}

// A revisited drift that grows with a position wins in place of its own
// static form only by a course above the floor
// (SelectionOptions::revisit_course_floor). Irregular grid case 124 on the
// gantry (a scale of Z, −3.0 µm): the kept path names the scale of Z and
// ends with a smooth dX(z, t); the path from a drift z·t→Z at τ 600 s (a
// scale of Z but for the first minutes of the walk) ends with the same
// smooth function and was better on the criterion by 1.9 and held out, by
// the model's own error in those minutes: taken, a wrong name.
TEST(DiagnoseDesigns, ARevisitedDriftMustGainItsCourseBesideItsStaticForm) {
  const OnMachine on(gantry_vm(), "gantry (generic, seed 11)");
  const auto [h, seed] = sweep_case(Design::grid_irregular, 124);
  const Case c = run_case(Design::grid_irregular, h, seed);
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  EXPECT_TRUE(logged(c, "first step thermal_drift z·t→Z (τ 600 s) in place of scale Z",
                     "not taken, its course adds less than the floor"));
  SelectionOptions without;
  without.revisit_course_floor = false;
  const Case w = run_case(Design::grid_irregular, h, seed, 0.0, &without);
  EXPECT_EQ(w.verdict, Verdict::wrong) << w.found;
}

// An effect is a function of a levelled axis only where it is one beside
// the datum too (DesignAmbiguityOptions::level_share_left_beside_datum).
// Five-run diagonals case 0 on the gantry (a uniform drift of X, +7.2 µm):
// the drift t→X is named beside a 0.2 µm cycle of Z in X (the machine's
// own); its raw column kept 7 % outside the 30 levels of z — it is mostly
// its mean, an offset of each line — and so the two were "one function of
// z", the drift `ambiguous`. Beside the datum none of it lies in the
// levels' span, and the drift is named.
TEST(DiagnoseDesigns, ADriftIsNotAFunctionOfTheLevelsByItsMean) {
  const OnMachine on(gantry_vm(), "gantry (generic, seed 11)");
  const auto [h, seed] = sweep_case(Design::diagonals_runs, 0);
  ASSERT_EQ(h.shape, Shape::drift);
  const Case c = run_case(Design::diagonals_runs, h, seed);
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  DesignAmbiguityOptions raw;
  raw.level_share_left_beside_datum = 1.0;
  const Case w = run_case(Design::diagonals_runs, h, seed, 0.0, nullptr, false, &raw);
  EXPECT_EQ(w.verdict, Verdict::ambiguous) << w.found;
  EXPECT_NE(w.found.find("any function of z on its 30 levels"), std::string::npos) << w.found;
}

// A revisited path wins only where its alternative takes the first pick's
// place (SelectionOptions::revisit_alternative_replaces). Case 31 of the
// two-effect sweep (a scale of Y beside a drift ∝ z of Z): the kept path
// names the scale first and ends with a smooth function; the path from a
// cycle of Y at 4.18 mm (on the 8 regular levels of Y its samples are
// nearly a line) names the scale of Y at its fourth step beside the cycle,
// and is better on the criterion by 1.7 (1 078.5 against 1 080.2) and held
// out; taken, both were `ambiguous` as one function of y on its levels.
// Case 313 (a squareness dZ ∝ x beside an off-centre coupling x·z→Z): the
// same with a cycle of X in Z at 4.51 mm beside the squareness.
// (With the drifts at their grid's τ: with the τ refined, exact_tau, both
// cases name both effects on the kept path without the rule. And with the
// cycles at their chosen periods: with the final fit's period refinement,
// refine_periods, case 31's revisited path ends elsewhere.)
TEST(DiagnoseDesigns, ARevisitedAlternativeMustTakeThePicksPlace) {
  SelectionOptions rules;
  rules.exact_tau = false;
  rules.refine_tau = false;
  rules.refine_periods = false;
  SelectionOptions joined_wins = rules;
  joined_wins.revisit_alternative_replaces = false;
  expect_both_named_only_with_the_rule({31, 313}, joined_wins, &rules);
  expect_logged(31, "first step cyclic Y→Y (4.18 mm) in place of scale Y",
                "not taken, 2 effects with a searched parameter against 1", &rules);
}

// The path without an arm offset picked first
// (SelectionOptions::revisit_without_arm_offset). Case 333 of the
// two-effect sweep (a scale of X and a squareness dZ ∝ x): an arm offset
// εX×ΔY moves X and Z at once, at the ratio of the model's angular tables of
// X, and took both lines at its ratio (ΔRSS 2 212); a 4.10 mm cycle of X and
// a smooth dZ(x) took the remainders, all `ambiguous` as functions of x on
// its 12 levels. Without it the path names the scale and the squareness
// (criterion 1 008.2 against 1 039.7; held out 1 005.3 against 1 002.6,
// within its resolution, 9.2). Case 197 (a squareness dZ ∝ x beside a drift
// ∝ x of X): the same arm offset, then the squareness and a smooth dX(x,t);
// without it the squareness and the drift.
TEST(DiagnoseDesigns, ThePathWithoutAnArmOffsetPickedFirstIsRun) {
  SelectionOptions arm_kept;
  arm_kept.revisit_without_arm_offset = false;
  expect_both_named_only_with_the_rule({333, 197}, arm_kept);
  expect_logged(333, "revisit: without arm_offset εX×ΔY", ": taken");
}

// A member of a combination is not `ambiguous` with a costlier drift that
// removes less in its place (SelectionOptions::member_rivals_by_cost).
// Case 45 of the two-effect sweep (a squareness dY ∝ z beside a drift of
// Y, t/(t+τ) at τ 985 s): the squareness and a drift t→Y at 1 200 s explain
// the structure, and a drift z·t→Y at τ 300 s — the squareness but for
// the first minutes, with its time constant searched — removed nearly as
// much in the squareness's place, so the squareness was `ambiguous`.
TEST(DiagnoseDesigns, AMemberIsNotAmbiguousWithACostlierDriftThatRemovesLess) {
  SelectionOptions any_rival;
  any_rival.member_rivals_by_cost = false;
  expect_both_named_only_with_the_rule({45}, any_rival);
}

// A drift that grows with a position is named only where its course in
// time adds, beside its static form, more than the floor a name must pass
// (SelectionOptions::drift_course_floor). Case 565 of the irregular grid
// (a squareness dX ∝ z): a drift z·t→X at τ 300 s — the squareness but
// for the first minutes — removed 13 096.3 against the squareness's
// 13 090.1, and its criterion beat the squareness's; the name was wrong.
// Case 662 of the grid without vx vy vz (a squareness dX ∝ z) the same.
// Case 266 of the two-effect sweep (a reversal of Y and a squareness
// dX ∝ z): the drift z·t→X at τ 600 s took the squareness's place at the
// second step. With the floor each is named as the squareness.
TEST(DiagnoseDesigns, ADriftWhoseCourseIsNotResolvedIsItsStaticForm) {
  SelectionOptions course_free;
  course_free.drift_course_floor = false;
  for (const bool inferred : {false, true}) {
    const Design design = inferred ? Design::grid : Design::grid_irregular;
    const int i = inferred ? 662 : 565;
    const auto [h, seed] = sweep_case(design, i);
    ASSERT_EQ(h.shape, Shape::squareness);
    const Case with = run_case(design, h, seed, 0.0, nullptr, inferred);
    EXPECT_EQ(scored(with, h), Verdict::right) << "case " << i << ": " << with.found;
    const Case off = run_case(design, h, seed, 0.0, &course_free, inferred);
    EXPECT_EQ(scored(off, h), Verdict::wrong) << "case " << i << ": " << off.found;
  }
  const TwoEffects with = two_effects_case(266);
  EXPECT_TRUE(with.named[0] && with.named[1]) << with.c.found;
  EXPECT_FALSE(with.bad) << with.c.found;
  const TwoEffects off = two_effects_case(266, &course_free);
  EXPECT_TRUE(off.bad) << off.c.found;
}

// The backward check once more after the final fit moves a τ
// (SelectionOptions::backward_after_tau): case 174 of the two-effect
// sweep, a drift of Z beside a squareness dZ ∝ x, chose the drift at the
// grid's τ 1 200 s with a reversal of Z growing along z beside it (the
// grid's two passes drive Z opposite ways, so that reversal is a step in
// time). At the drift's own τ, 1 779 s, the reversal removes 2.8 µm²
// beside the rest, below its test (9.2): it is dropped, and no longer a
// wrong name. (Kept, it is now `ambiguous` in its jump: beside the drift
// the jump of X's reversal or of Y→Z's removes as much —
// DesignAmbiguityOptions::reversal_jump.)
TEST(DiagnoseDesigns, AnEffectMadeRedundantByADriftAtItsOwnTimeConstantIsDropped) {
  const TwoEffects with = two_effects_case(174);
  EXPECT_TRUE(with.named[0] && with.named[1]) << with.c.found;
  EXPECT_FALSE(with.bad) << with.c.found;
  EXPECT_EQ(with.c.found.find("reversal Z→Z"), std::string::npos) << with.c.found;
  SelectionOptions once;
  once.backward_after_tau = false;
  const TwoEffects off = two_effects_case(174, &once);
  EXPECT_NE(off.c.found.find("reversal Z→Z growing along z"), std::string::npos) << off.c.found;
  DesignAmbiguityOptions jump_named;
  jump_named.reversal_jump = false;
  EXPECT_TRUE(two_effects_case(174, &once, nullptr, &jump_named).bad);
}

// The swap test beside the smooth functions (RivalOptions::beside_smooth):
// case 68 of the two-effect sweep, a scale of X beside an off-centre
// coupling y·z→X, was named a drift x·t→X with τ = 300 s (settled within
// the first minutes: a scale but for them) with dX(z,t) for the coupling.
// Beside the named effects alone the drift removed more than the scale, as
// the coupling's part left to the smooth function favoured it; beside the
// smooth function the scale removes more, so the drift is `ambiguous`
// with it.
TEST(DiagnoseDesigns, ARivalIsAlsoSoughtBesideTheSmoothFunction) {
  auto drift_named = [](const TwoEffects& r) {
    for (const SelectedTerm& st : r.c.effects)
      if (st.term.kind == TermKind::thermal_drift) return st;
    return SelectedTerm{};
  };
  // Without the revisit of the first step, which names the scale there
  // (TheFirstStepIsRevisited).
  SelectionOptions first_pick_kept;
  first_pick_kept.revisit_paths = 0;
  first_pick_kept.structure_near_share = 0.0;  // else the first path names it
  first_pick_kept.drift_course_floor = false;  // else the scale is the first pick
  const TwoEffects with = two_effects_case(68, &first_pick_kept);
  EXPECT_FALSE(with.bad) << with.c.found;
  const SelectedTerm d = drift_named(with);
  ASSERT_EQ(d.term.kind, TermKind::thermal_drift) << with.c.found;
  EXPECT_NE(std::find(d.ambiguous_with.begin(), d.ambiguous_with.end(), "scale X"),
            d.ambiguous_with.end())
      << with.c.found;
  RivalOptions named_only;
  named_only.beside_smooth = false;
  const TwoEffects off = two_effects_case(68, &first_pick_kept, &named_only);
  EXPECT_TRUE(off.bad) << off.c.found;
  EXPECT_TRUE(drift_named(off).ambiguous_with.empty()) << off.c.found;
}

TEST(DiagnoseDesigns, AnotherLeadCombinesADriftThatGrowsWithPosition) {
  SelectionOptions from_the_lead;
  from_the_lead.combination_leads = 1;
  expect_both_named_only_with_the_rule({36, 90}, from_the_lead);
}

// A structure that two smooth functions find as well
// (SelectionOptions::structure_near_share). On the serpentine grid the
// time follows the rows and the levels, so a function of (z, t) or (x, t)
// fits what is a function of the positions nearly as well. Case 486 (a
// reversal of Y beside an off-centre coupling y·z→Y): after the reversal
// the best smooth function is dY(z, t) (ΔRSS 215), dY(y, z) removes 205,
// and the coupling y·z→Y with its scale part explains it; case 108 (a
// reversal of Z beside an off-centre coupling x·z→Y): dY(x, t) best, the
// coupling x·z→Y with its two squareness parts from dY(x, z). With only
// the best function's variables the coupling is left `unexplained`.
TEST(DiagnoseDesigns, AStructureTwoSmoothFunctionsFindIsExplainedFromEither) {
  SelectionOptions best_only;
  best_only.structure_near_share = 0.0;
  expect_both_named_only_with_the_rule({108, 486}, best_only);
}

// The lead of a combination has its rivals in the combination, as every
// partner has (SelectionOptions::lead_rivals_in_combination). Grid without
// vx vy vz, case 714 (a drift ∝ z − z0 of Z): a reversal Z→Z led a
// combination with a drift t→Z, and a reversal X→Z (the inferred
// directions of X and Z change together at a level's end) takes its place
// as well — `ambiguous` now, a wrong name before. Diagonals, case 956 (an
// off-centre coupling x·y→Y, which the diagonals cannot identify): an arm
// offset εX×ΔZ led a squareness, and a cycle of X fits in its place. (Case
// 956's arm offset is also `ambiguous` with the coupling off its centre,
// AnArmOffsetIsTheLinearPartOfACouplingOffItsCentre: that rule is off
// where the lead's rivals are, to show what each does alone.)
TEST(DiagnoseDesigns, ALeadOfACombinationHasItsRivalsToo) {
  SelectionOptions partners_only;
  partners_only.lead_rivals_in_combination = false;
  RivalOptions centred;
  centred.arm_offset_as_coupling_centre = false;
  for (const auto& [design, i, inferred] :
       {std::tuple{Design::grid, 714, true}, std::tuple{Design::diagonals, 956, false}}) {
    const auto [h, seed] = sweep_case(design, i);
    const Case with = run_case(design, h, seed, 0.0, nullptr, inferred);
    EXPECT_NE(with.verdict, Verdict::wrong) << "case " << i << ": " << with.found;
    bool lead_ambiguous = false;
    for (const SelectedTerm& st : with.effects)
      lead_ambiguous =
          lead_ambiguous ||
          ((st.term.kind == TermKind::reversal || st.term.kind == TermKind::arm_offset) &&
           !st.ambiguous_with.empty());
    EXPECT_TRUE(lead_ambiguous) << "case " << i << ": " << with.found;
    const Case off = run_case(design, h, seed, 0.0, &partners_only, inferred, nullptr, &centred);
    EXPECT_EQ(off.verdict, Verdict::wrong) << "case " << i << ": " << off.found;
  }
}

// Cases of a design's sweep named right with the engine's rules and, with
// `without` (one rule off), not right and not wrong either.
void expect_right_only_with_the_rule(Design design, std::initializer_list<int> cases,
                                     const SelectionOptions& without) {
  for (int i : cases) {
    const auto [h, seed] = sweep_case(design, i);
    const Case with = run_case(design, h, seed);
    EXPECT_EQ(scored(with, h), Verdict::right) << "case " << i << ": " << with.found;
    const Case off = run_case(design, h, seed, 0.0, &without);
    EXPECT_NE(scored(off, h), Verdict::right) << "case " << i << ": " << off.found;
    EXPECT_NE(scored(off, h), Verdict::wrong) << "case " << i << ": " << off.found;
  }
}

// The smooth function's surplus (SelectionOptions::smooth_surplus_test). On
// the XY ballbar the model's own table error of X leaves a structure below
// every floor; beside a small scale of X it lifts the best smooth function
// above its floors, and the scale explains only 0.6 of it. Case 425
// (1000-seed sweep): scale X removes 27.0 of the 42.7 dX(x, t) removes,
// which adds 15.9 beside it, below its own floor (24.8); case 766: scale X
// removes 32.9, and dX(y, t) — whose variables do not hold x, but which
// reproduces the scale on the circle — adds 20.4 beside it (floor 25.4).
// Both named right with the rule, `unexplained` without it.
TEST(DiagnoseDesigns, ANamedPartExplainsWhereTheSmoothFunctionAddsNothingAboveItsFloor) {
  SelectionOptions share_only;
  share_only.smooth_surplus_test = false;
  expect_right_only_with_the_rule(Design::ballbar_xy, {425, 766}, share_only);
}

// A drift the smooth function reproduces is a part of its structure
// (SelectionOptions::drift_parts_by_reproduction). On the XY ballbar every
// position is a function of the angle and the pass: a drift ∝ x − x0 of X
// is a uniform drift t→X and a drift x·t→X, and the best smooth function
// was one of (y, t), whose variables do not hold x. Case 528 (1000-seed
// sweep): t→X removes 26.2 of the 66.2 dX(y, t) removes, t→X with x·t→X
// 55.0; case 702: 131.0 with a reversal, 166.4 of 181.3 with x·t→X. Named
// right with the rule, `unexplained` without it.
TEST(DiagnoseDesigns, ADriftTheSmoothFunctionReproducesIsAPartOfItsStructure) {
  SelectionOptions by_variables;
  by_variables.drift_parts_by_reproduction = false;
  expect_right_only_with_the_rule(Design::ballbar_xy, {528, 702}, by_variables);
}

// The backward check (SelectionOptions::backward_check): an effect chosen
// early that later effects made redundant leaves the fit. Case 75 of the
// two-effect sweep (a reversal of Y and a scale Y): a 4.2 mm cycle of Y,
// aliased on the 8 levels, took the scale's line before the reversal was
// in, and the scale came in third; without the check both stood,
// `ambiguous` with each other. Case 96 (a reversal of Y and a squareness
// dY ∝ z): a drift z·t→Y led their combination and added nothing beside
// them; without the check the squareness stayed `ambiguous` beside it.
// (Without the revisit from a static first pick as well, which names case
// 75 from the scale: AStaticFirstPickInPlaceOfADriftIsRevisited.)
TEST(DiagnoseDesigns, TheBackwardCheckDropsWhatLaterEffectsMadeRedundant) {
  SelectionOptions forward_only;
  forward_only.backward_check = false;
  forward_only.revisit_searched_first = false;
  expect_both_named_only_with_the_rule({75, 96}, forward_only);
}

// A cycle as the third member of a combination must pass the whole
// practical floor in what it adds (SelectionOptions::cyclic_partner_full_floor):
// case 109 of the irregular grid, an off-centre coupling x·y→Z, is named
// as the coupling and its squareness part; with half the floor a cycle of
// X in Z (10.6 mm, 0.17 µm rms) joined them.
TEST(DiagnoseDesigns, ACyclicPartnerPassesTheWholeFloor) {
  const auto [h, seed] = sweep_case(Design::grid_irregular, 109);
  ASSERT_EQ(h.shape, Shape::coupling);
  SelectionOptions half;
  half.cyclic_partner_full_floor = false;
  half.coupling_parts_first = false;  // (which alone keeps the cycle out too)
  auto cycles = [](const Case& c) {
    return std::count_if(c.effects.begin(), c.effects.end(),
                         [](const SelectedTerm& st) { return st.term.kind == TermKind::cyclic; });
  };
  const Case with = run_case(Design::grid_irregular, h, seed);
  EXPECT_EQ(with.verdict, Verdict::right) << with.found;
  EXPECT_EQ(cycles(with), 0) << with.found;
  // With half the floor the cycle joins (now reported `ambiguous` with a
  // cycle at another period by the cycle period test, design_ambiguity.hpp;
  // before that test, a wrong name).
  const Case without = run_case(Design::grid_irregular, h, seed, 0.0, &half);
  EXPECT_EQ(cycles(without), 1) << without.found;
}

// A chosen cycle's period is refined on the exact ΔRSS
// (SelectionOptions::exact_period): on the laser lines, cases 69 (pitch
// error of X, 8.9 mm) and 142 (37.1 mm) are named as the pitch error and
// its harmonic, two cycles. With the periodogram's period alone, the
// fundamental a fraction of a lobe off beat against the data over the
// travel: a third cycle at a neighbouring period (69: 8.85 mm beside
// 8.92 mm, and an arm offset) or at an alias of the harmonic (142) came in
// (a wrong name, until the cycle period test's margin became the levels'
// noise: now 142's third cycle is `ambiguous`). The "periodogram only" runs
// also leave out the later rules that keep a third cycle away by
// themselves: no cycle within 1/span of a chosen one
// (resolve_chosen_cycles; with it 69's third cycle moves to 11.6 mm) and
// the final fit's period refinement (refine_periods).
TEST(DiagnoseDesigns, AChosenCyclesPeriodIsRefinedOnTheFit) {
  auto cycles = [](const Case& c) {
    return std::count_if(c.effects.begin(), c.effects.end(),
                         [](const SelectedTerm& st) { return st.term.kind == TermKind::cyclic; });
  };
  SelectionOptions periodogram_only;
  periodogram_only.exact_period = false;
  periodogram_only.resolve_chosen_cycles = false;
  periodogram_only.refine_periods = false;
  for (int i : {69, 142}) {
    const auto [h, seed] = sweep_case(Design::axis_lines, i);
    ASSERT_EQ(h.shape, Shape::pitch);
    const Case with = run_case(Design::axis_lines, h, seed);
    EXPECT_EQ(with.verdict, Verdict::right) << i << with.found;
    EXPECT_EQ(cycles(with), 2) << i << with.found;
    const Case without = run_case(Design::axis_lines, h, seed, 0.0, &periodogram_only);
    EXPECT_EQ(cycles(without), 3) << i << without.found;
  }
}

// What a cycle removes can have two maxima within one grid step of the
// scan on irregular levels: the refinement samples the step before its
// Brent search. Case 400 of the irregular grid (a pitch error of X, 30.1 mm
// with a harmonic) is named by its kind with the 8.94 mm cycle (ΔRSS 1247);
// Brent over the whole step settled on 8.92 mm (ΔRSS 1199), the second and
// third cycles then changed and the pitch error was missed.
TEST(DiagnoseDesigns, AChosenCyclesPeriodIsTheBestMaximumWithinItsStep) {
  const auto [h, seed] = sweep_case(Design::grid_irregular, 400);
  ASSERT_EQ(h.shape, Shape::pitch);
  const Case c = run_case(Design::grid_irregular, h, seed);
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  EXPECT_TRUE(c.by_period) << c.found;
}

// The cycle period test's margin is one column's χ² times the noise of a
// function of the levels (DesignAmbiguityOptions::level_noise_margin): the
// model's own error at each target repeats in every run, so what the
// levels hold beyond the fit scatters more than single readings. Laser
// lines case 4 (a cycle at 11.34 mm beside a pitch error of 18.7 mm) and
// the irregular grid's cases 44 (a cycle of Y of 0.27 µm rms beside an
// off-centre coupling) and 66 (a cycle at 8.94 mm for a pitch error of
// 13.0 mm) are `ambiguous` with another period; with σ̂² alone (and
// without the level-out test, which now also catches 44 and 66) each was a
// wrong name.
TEST(DiagnoseDesigns, TheCyclePeriodMarginIsTheLevelsNoise) {
  DesignAmbiguityOptions readings_only;
  readings_only.level_noise_margin = false;
  readings_only.level_out_test = false;
  // (Case 44's cycle is also kept out by a coupling's linear parts coming
  // first among its partners, SelectionOptions::coupling_parts_first.)
  SelectionOptions by_criterion;
  by_criterion.coupling_parts_first = false;
  for (const auto& [design, i] : std::vector<std::pair<Design, int>>{
           {Design::axis_lines, 4}, {Design::grid_irregular, 44}, {Design::grid_irregular, 66}}) {
    const auto [h, seed] = sweep_case(design, i);
    const Case with = run_case(design, h, seed);
    EXPECT_NE(with.verdict, Verdict::wrong) << i << with.found;
    const Case without = run_case(design, h, seed, 0.0, &by_criterion, false, &readings_only);
    EXPECT_EQ(without.verdict, Verdict::wrong) << i << without.found;
  }
}

// The level-out test (DesignAmbiguityOptions::level_out_test): a pitch
// error with its harmonic, read at 12 irregular levels of X (grid case 22,
// 39.9 mm) or along a laser line's 21 targets (case 45, 39.4 mm of Z),
// selected as a cycle at a period one level alone prefers (10.9 mm;
// 13.2 mm). Leaving that level out, another period fits as well, and the
// cycle is not named; without the test each was a wrong name. (Case 45
// is also kept from the wrong name by the final fit's period refinement
// and the resolution rule for a second cycle, refine_periods and
// resolve_chosen_cycles: the runs without the test leave them out too.)
TEST(DiagnoseDesigns, APeriodThatRestsOnOneLevelIsNotAName) {
  DesignAmbiguityOptions without_test;
  without_test.level_out_test = false;
  SelectionOptions earlier_cycles;
  earlier_cycles.refine_periods = false;
  earlier_cycles.resolve_chosen_cycles = false;
  for (const auto& [design, i] : std::vector<std::pair<Design, int>>{{Design::grid_irregular, 22},
                                                                     {Design::axis_lines, 45}}) {
    const auto [h, seed] = sweep_case(design, i);
    ASSERT_EQ(h.shape, Shape::pitch);
    const Case with = run_case(design, h, seed);
    EXPECT_NE(with.verdict, Verdict::wrong) << i << with.found;
    const Case without = run_case(design, h, seed, 0.0, &earlier_cycles, false, &without_test);
    EXPECT_EQ(without.verdict, Verdict::wrong) << i << without.found;
  }
}

// A period not resolved is not a kind not resolved (DesignAmbiguityOptions
// period_only_*): irregular grid cases 120 and 577, pitch errors of X
// (24.9 and 26.4 mm, with their harmonic) selected as a cycle at their
// period (24.85, 26.39 mm) that rests on one level (without x = −914 or
// −990 mm another period fits as well). The cycle holds over 99 % of what
// any function of the 12 levels holds and no smooth function of x follows
// it: named, its period unresolved (other_periods_mm); with the rule off,
// `ambiguous` — no name.
TEST(DiagnoseDesigns, APitchErrorWhosePeriodIsNotResolvedIsNamedByItsKind) {
  DesignAmbiguityOptions rule_off;  // no design has 1000 levels
  rule_off.period_only_min_levels = 1000;
  for (const int i : {120, 577}) {
    const auto [h, seed] = sweep_case(Design::grid_irregular, i);
    ASSERT_EQ(h.shape, Shape::pitch);
    const Case with = run_case(Design::grid_irregular, h, seed);
    EXPECT_EQ(with.verdict, Verdict::right) << i << with.found;
    EXPECT_TRUE(with.by_period) << i << with.found;
    const Case without = run_case(Design::grid_irregular, h, seed, 0.0, nullptr, false, &rule_off);
    EXPECT_EQ(without.verdict, Verdict::ambiguous) << i << without.found;
  }
}

// The linear parts of an off-centre coupling join its combination at their
// χ² (SelectionOptions::coupling_parts_at_chi2): toolpath cases 202, 738
// and 986 were a smooth `unexplained` function of (x, y) when the small
// squareness the coupling's centre carries had to pass the partner floor
// (e.g. case 202: ΔRSS 188 against a floor of 211); with it they are the
// coupling with its linear parts.
// And they come before any other partner (coupling_parts_first): in grid
// case 908 (1000-seed sweep) an arm offset εY×ΔZ, which carries the
// model's own table error, took the place of the scale of Y that an
// off-centre coupling y·z→Y carries — a wrong name before the harness set
// the machine's own error apart (of_the_machine(): the arm offset is that
// error, so both are graded right now); with its linear parts first the
// coupling is named with its scale of Y.
TEST(DiagnoseDesigns, ACouplingsLinearPartsComeBeforeOtherPartners) {
  const auto [h, seed] = sweep_case(Design::grid, 908);
  ASSERT_EQ(h.shape, Shape::coupling);
  const auto scale_y = [](const Case& c) {
    return std::any_of(c.effects.begin(), c.effects.end(), [](const SelectedTerm& st) {
      return st.term.kind == TermKind::scale && st.term.axis == 1 && st.term.direction == 1;
    });
  };
  const Case with = run_case(Design::grid, h, seed);
  EXPECT_EQ(with.verdict, Verdict::right) << with.found;
  EXPECT_TRUE(scale_y(with)) << with.found;
  SelectionOptions by_criterion;
  by_criterion.coupling_parts_first = false;
  const Case without = run_case(Design::grid, h, seed, 0.0, &by_criterion);
  EXPECT_FALSE(scale_y(without)) << without.found;
  EXPECT_EQ(without.machine_names, 1) << without.found;
}

TEST(DiagnoseDesigns, AnOffCentreCouplingKeepsItsSmallLinearParts) {
  SelectionOptions at_floor;
  at_floor.coupling_parts_at_chi2 = false;
  for (int i : {202, 738, 986}) {
    const auto [h, seed] = sweep_case(Design::toolpath, i);
    ASSERT_EQ(h.shape, Shape::coupling);
    const Case with = run_case(Design::toolpath, h, seed);
    EXPECT_EQ(with.verdict, Verdict::right) << i << with.found;
    const Case without = run_case(Design::toolpath, h, seed, 0.0, &at_floor);
    EXPECT_NE(without.verdict, Verdict::right) << i << without.found;
    EXPECT_NE(without.found.find("unexplained"), std::string::npos) << i << without.found;
  }
}

// A coupling is scored by its linear part only where its product part is
// below what the design resolves (scored()): on the ballbar's circles,
// case 128's y·z→Y adds 1 % beyond its best linear part and is named by its
// scale of Y; on the grid, case 108's adds 29 %, so that a linear part alone
// would be a miss there (the grid names the coupling itself).
TEST(DiagnoseDesigns, ACouplingIsScoredByItsLinearPartOnlyWhereItsProductIsNotResolved) {
  {
    const auto [h, seed] = sweep_case(Design::ballbar, 128);
    ASSERT_EQ(h.shape, Shape::coupling);
    const Case c = run_case(Design::ballbar, h, seed);
    EXPECT_LT(c.product_oracle, kResolvable);
    EXPECT_GE(c.product_oracle, -0.02);
    EXPECT_EQ(c.verdict, Verdict::ambiguous) << c.found;
    EXPECT_TRUE(c.linear_part_named) << c.found;
    bool by_part = false;
    EXPECT_EQ(scored(c, h, &by_part), Verdict::right);
    EXPECT_TRUE(by_part);
    Case flipped = c;  // the same names with the linear part's sign wrong
    flipped.linear_part_named = false;
    EXPECT_EQ(scored(flipped, h), Verdict::ambiguous);
  }
  const auto [h, seed] = sweep_case(Design::grid, 108);
  ASSERT_EQ(h.shape, Shape::coupling);
  Case c = run_case(Design::grid, h, seed);
  EXPECT_GT(c.product_oracle, 0.2);
  EXPECT_EQ(scored(c, h), Verdict::right) << c.found;
  c.verdict = Verdict::ambiguous;  // as if only its linear parts were named
  c.linear_part_named = true;
  EXPECT_EQ(scored(c, h), Verdict::ambiguous);
}

// A coupling is identifiable only as far as it adds beyond its linear parts
// of kinds the design cannot identify (identifiable_parts_unresolved()):
// ballbar case 269 (1000-seed sweep), x-direction ∝ (y − y0)(z − z0), is on
// the XZ circle (y fixed) a squareness dX ∝ z and on the XY circle (z
// fixed) a squareness dX ∝ y; the ballbar identifies neither, and beyond
// them the coupling adds nothing (its oracle gain of 0.05 is all theirs).
// Case 128 (y·z→Y) adds 0.17 beyond its squareness dY ∝ z: its scale of Y
// is resolved and names it. On the grid every linear part is a kind it
// identifies (case 108: no such parts).
TEST(DiagnoseDesigns, ACouplingIsIdentifiableOnlyBeyondItsUnnameableParts) {
  {
    const auto [h, seed] = sweep_case(Design::ballbar, 269);
    ASSERT_EQ(h.shape, Shape::coupling);
    const Case c = run_case(Design::ballbar, h, seed);
    EXPECT_GE(c.oracle, kResolvable);
    EXPECT_LT(c.identifiable_parts_oracle, kResolvable);
    EXPECT_GE(c.identifiable_parts_oracle, -0.02);
    EXPECT_TRUE(identifiable_parts_unresolved(c));
  }
  {
    const auto [h, seed] = sweep_case(Design::ballbar, 128);
    ASSERT_EQ(h.shape, Shape::coupling);
    const Case c = run_case(Design::ballbar, h, seed);
    EXPECT_GT(c.identifiable_parts_oracle, 0.1);
    EXPECT_FALSE(identifiable_parts_unresolved(c));
    EXPECT_EQ(scored(c, h), Verdict::right) << c.found;
  }
  const auto [h, seed] = sweep_case(Design::grid, 108);
  ASSERT_EQ(h.shape, Shape::coupling);
  const Case c = run_case(Design::grid, h, seed);
  EXPECT_EQ(c.identifiable_parts_oracle, -1.0);
  EXPECT_FALSE(identifiable_parts_unresolved(c));
}

// At one Z nothing driven by z is identifiable, but dz is measured in time:
// a drift of Z is (toolpath case 54 of the 1000-seed sweep, −9.98 µm with
// τ = 1725 s, is named thermal_drift t→Z; it was counted "by luck" when
// identifiable() held every effect of Z unidentifiable there).
TEST(DiagnoseDesigns, ADriftOfZIsIdentifiableAtOneZ) {
  Hidden h;
  h.axis = h.dir = 2;
  h.shape = Shape::drift;
  EXPECT_TRUE(identifiable(Design::toolpath, h));
  h.proportional = true;
  EXPECT_TRUE(identifiable(Design::toolpath, h));
  h.shape = Shape::scale;
  EXPECT_FALSE(identifiable(Design::toolpath, h));
  h.shape = Shape::reversal;
  EXPECT_FALSE(identifiable(Design::toolpath, h));

  const auto [drift, seed] = sweep_case(Design::toolpath, 54);
  ASSERT_EQ(drift.shape, Shape::drift);
  ASSERT_EQ(drift.dir, 2);
  const Case c = run_case(Design::toolpath, drift, seed);
  EXPECT_GE(c.oracle, kResolvable);
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
}

// A drift named with alternatives that are all forms of the same drift (a
// thermal drift of its direction, uniform or ∝ a position, at any time
// constant) has its kind and direction named: ballbar case 266 (1000-seed
// sweep), a uniform drift of Y, is named x·t→Y ~ t→Y at three time
// constants (far from the machine's zero x·t→Y is mostly the uniform
// drift). An alternative of another direction or kind keeps it ambiguous.
// Along the four body diagonals every axis's reversal is the same jump,
// but a reversal that grows along its travel (the harness's backlash, 20 %
// more at the end) grows along diagonal k with the sign of the diagonal's
// slope in s_j: a pattern over the four diagonals that tells the axis. Case
// 34 (a reversal of X, −9.5 µm) resolves its growth and is named a
// reversal X→X growing along x, unambiguous; case 54 (+1.95 µm) does not,
// and is counted with the cases the design cannot identify. Without the
// growing reversal in the catalogue case 34 was `ambiguous` among the
// reversals of X, Y and Z (1000 seeds: 3/16 identifiable named right
// before, 52/66 with the reversals whose growth is resolved, 49/50 of them).
TEST(DiagnoseDesigns, AReversalAlongTheDiagonalsIsToldByItsGrowth) {
  const auto [grown, seed] = sweep_case(Design::diagonals, 34);
  ASSERT_EQ(grown.shape, Shape::reversal);
  ASSERT_EQ(grown.axis, 0);
  EXPECT_TRUE(identifiable(Design::diagonals, grown));
  const Case c = run_case(Design::diagonals, grown, seed);
  EXPECT_GE(c.growth_oracle, kResolvable);
  EXPECT_FALSE(growth_unresolved(c));
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  EXPECT_TRUE(c.by_jump) << c.found;  // whose jump it is, the diagonals do not tell
  bool growing_x = false;
  for (const SelectedTerm& st : c.effects)
    growing_x = growing_x ||
                (st.term.kind == TermKind::reversal && st.term.axis == 0 && st.term.degree == 1 &&
                 st.ambiguous_with == std::vector<std::string>{"reversal Y→Y (its jump)",
                                                               "reversal Z→Z (its jump)"});
  EXPECT_TRUE(growing_x) << c.found;

  const auto [small, small_seed] = sweep_case(Design::diagonals, 54);
  ASSERT_EQ(small.shape, Shape::reversal);
  const Case u = run_case(Design::diagonals, small, small_seed);
  EXPECT_TRUE(growth_unresolved(u));
  EXPECT_NE(u.verdict, Verdict::wrong) << u.found;
}

// Along the four body diagonals every axis's reversal jump is the same
// step: a growing reversal's growth tells the axis that grows, its jump
// does not (DesignAmbiguityOptions::reversal_jump). Case 552 hides a
// reversal of Z (−4.2 µm) whose growth is below resolution; the machine's
// own error holds a growth of X's reversal, and the jump with that growth
// was named a reversal of X growing along x — a wrong name. Now the jump's
// other axes are its alternatives ("reversal Z→Z (its jump)") and the case
// is `ambiguous`. Measured once there and back at 0.5 µm (1000 seeds) the
// diagonals' wrong names where not identifiable fell 1 → 0 and the 49
// reversals whose growth is resolved stay named (by their growth).
TEST(DiagnoseDesigns, AGrowingReversalsJumpAlongTheDiagonalsIsNotNamed) {
  const auto [h, seed] = sweep_case(Design::diagonals, 552);
  ASSERT_EQ(h.shape, Shape::reversal);
  ASSERT_EQ(h.axis, 2);
  const Case c = run_case(Design::diagonals, h, seed);
  EXPECT_TRUE(growth_unresolved(c));
  EXPECT_EQ(c.verdict, Verdict::ambiguous) << c.found;
  EXPECT_NE(c.found.find("reversal X→X growing along x"), std::string::npos) << c.found;
  EXPECT_NE(c.found.find("reversal Z→Z (its jump)"), std::string::npos) << c.found;
  DesignAmbiguityOptions jump_named;
  jump_named.reversal_jump = false;
  const Case w = run_case(Design::diagonals, h, seed, 0.0, nullptr, false, &jump_named);
  EXPECT_EQ(w.verdict, Verdict::wrong) << w.found;
}

// A drift ∝ (x − x0)·t of X is a drift ∝ x·t about the machine's zero plus
// a uniform drift, its zero: (x − x0)·f(t) = x·f(t) − x0·f(t). Along the
// body diagonals the proportional part is the same for every direction
// (`ambiguous`, compared with their zero free), but a uniform drift named
// beside it has a direction of its own. Five runs, case 630: y·t→Y is
// `ambiguous` with x·t→X, and the uniform drift beside it was named t→Y —
// a wrong name; swapped as a pair for x·t→X with its zero free and t→X,
// the fit removes as much, and t→X is its alternative
// (RivalOptions::uniform_drift_as_zero). 1000 seeds of every design: only
// the five-run diagonals move (wrong where not identifiable 5/700 → 3/700).
TEST(DiagnoseDesigns, AUniformDriftBesideAnAmbiguousProportionalDriftIsItsZeroAsMuch) {
  const auto [h, seed] = sweep_case(Design::diagonals_runs, 630);
  ASSERT_EQ(h.shape, Shape::drift);
  ASSERT_TRUE(h.proportional);
  const Case c = run_case(Design::diagonals_runs, h, seed);
  EXPECT_EQ(c.verdict, Verdict::ambiguous) << c.found;
  EXPECT_NE(c.found.find("(the zero of thermal_drift x·t→X"), std::string::npos) << c.found;
  bool told = false;
  for (const SelectedTerm& st : c.effects)
    told = told || st.separate_by.find("measure along X on its own") != std::string::npos;
  EXPECT_TRUE(told) << c.found;
  RivalOptions direction_named;
  direction_named.uniform_drift_as_zero = false;
  const Case w =
      run_case(Design::diagonals_runs, h, seed, 0.0, nullptr, false, nullptr, &direction_named);
  EXPECT_EQ(w.verdict, Verdict::wrong) << w.found;
}

// The same where the proportional part's rivals do not hold the truth's
// direction. Five runs, case 144 (a drift ∝ (x − x0)·t of X): z·t→Z is
// named `ambiguous` with y·t→Y by the design's rules, so it is never put
// to the rival test, and x·t→X about the machine's zero fits less than
// either without its zero; the uniform drift beside it was named t→Z — a
// wrong name. Swapped as a pair for every drift in proportion to a
// position of another direction, each with its zero free and the uniform
// drift moved there (RivalOptions::zero_pair_every_direction), x·t→X with
// t→X removes as much: t→X is the uniform drift's alternative and x·t→X
// the proportional drift's.
TEST(DiagnoseDesigns, AUniformDriftIsTheZeroOfEveryProportionalDriftThatFitsAsMuch) {
  const auto [h, seed] = sweep_case(Design::diagonals_runs, 144);
  ASSERT_EQ(h.shape, Shape::drift);
  ASSERT_TRUE(h.proportional);
  ASSERT_EQ(h.dir, 0);
  const Case c = run_case(Design::diagonals_runs, h, seed);
  EXPECT_EQ(c.verdict, Verdict::ambiguous) << c.found;
  EXPECT_NE(c.found.find("(the zero of thermal_drift x·t→X"), std::string::npos) << c.found;
  EXPECT_NE(c.found.find("thermal_drift x·t→X (τ 1800 s) (with its zero, thermal_drift t→X"),
            std::string::npos)
      << c.found;
  RivalOptions rivals_only;
  rivals_only.zero_pair_every_direction = false;
  const Case w =
      run_case(Design::diagonals_runs, h, seed, 0.0, nullptr, false, nullptr, &rivals_only);
  EXPECT_EQ(w.verdict, Verdict::wrong) << w.found;
}

// A case of the diagonals' sweep (five runs; an off-centre coupling with
// direction X) `ambiguous` with `alternative` beside its arm offset, and a
// wrong name with `without`.
void expect_arm_offset_ambiguous_only_with(int i, const std::string& alternative,
                                           const RivalOptions& without) {
  const auto [h, seed] = sweep_case(Design::diagonals_runs, i);
  ASSERT_EQ(h.shape, Shape::coupling);
  ASSERT_EQ(h.dir, 0);
  const Case c = run_case(Design::diagonals_runs, h, seed);
  EXPECT_EQ(c.verdict, Verdict::ambiguous) << c.found;
  EXPECT_NE(c.found.find(alternative), std::string::npos) << c.found;
  bool told = false;
  for (const SelectedTerm& st : c.effects)
    told = told || (st.term.kind == TermKind::arm_offset &&
                    st.separate_by.find("lines parallel to the axes") != std::string::npos);
  EXPECT_TRUE(told) << c.found;
  const Case w = run_case(Design::diagonals_runs, h, seed, 0.0, nullptr, false, nullptr, &without);
  EXPECT_EQ(w.verdict, Verdict::wrong) << w.found;
}

// An arm offset can be the linear part of a coupling off its travel
// centre. Five runs, case 801 (an off-centre coupling x·z→X, +9.5 µm): the
// catalogue's coupling about the travel centre left its linear parts (a
// scale X and a squareness dX ∝ z: along a body diagonal both grow with
// the line's parameter), which an arm offset εZ×ΔY took in step 1; the
// coupling named beside it was `ambiguous` (y·z→Y ~ x·z→X), the arm
// offset a plain wrong name. Swapped with that coupling, each coupling
// with its centre free (RivalOptions::arm_offset_as_coupling_centre),
// x·z→X off its centre removes more than the pair: the arm offset is
// `ambiguous` with it.
TEST(DiagnoseDesigns, AnArmOffsetIsTheLinearPartOfACouplingOffItsCentre) {
  RivalOptions centred;
  centred.arm_offset_as_coupling_centre = false;
  expect_arm_offset_ambiguous_only_with(
      801, "arm_offset εZ×ΔY 0.74 ~ coupling x·z→X off its travel centre", centred);
}

// The same where no coupling is named beside the arm offset. On the generic
// machine of seed 5, five runs, case 870 (an off-centre coupling x·z→X,
// +7.1 µm): an arm offset εZ×ΔY alone, beside a smooth function dZ(x, t).
// Swapped alone for every coupling with its centre free
// (RivalOptions::arm_offset_alone_as_coupling), x·z→X off its centre
// removes more even after the price of its two extra columns: `ambiguous`.
TEST(DiagnoseDesigns, AnArmOffsetAloneIsACouplingOffItsCentreAsMuch) {
  const OnMachine on(generic5_vm(), "generic, seed 5");
  RivalOptions beside_a_coupling_only;
  beside_a_coupling_only.arm_offset_alone_as_coupling = false;
  expect_arm_offset_ambiguous_only_with(
      870, "arm_offset εZ×ΔY 0.70 ~ coupling x·z→X off its travel centre", beside_a_coupling_only);
}

// Along the four body diagonals a uniform drift's axis is told only by the
// sign pattern of its projection over the four lines; a drift of Z
// projects with one sign on all four. Case 58 (a drift of X, +9.7 µm)
// resolves its direction (what it adds beyond the same course in time in
// Y or Z) and is named; case 290 (a drift of Z, −8.3 µm) is resolvable as
// a whole (oracle 0.10) but not in its direction (0.02): counted with the
// cases the design cannot identify, and not named (1000 seeds: 52/66
// identifiable named right before, 52/58 with the 8 such drifts set apart,
// none of them named).
TEST(DiagnoseDesigns, ADriftAlongTheDiagonalsIsCountedByItsDirection) {
  const auto [x_drift, x_seed] = sweep_case(Design::diagonals, 58);
  ASSERT_EQ(x_drift.shape, Shape::drift);
  ASSERT_EQ(x_drift.axis, 0);
  const Case c = run_case(Design::diagonals, x_drift, x_seed);
  EXPECT_GE(c.oracle, kResolvable);
  EXPECT_FALSE(direction_unresolved(c)) << c.direction_oracle;
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;

  const auto [z_drift, z_seed] = sweep_case(Design::diagonals, 290);
  ASSERT_EQ(z_drift.shape, Shape::drift);
  ASSERT_EQ(z_drift.axis, 2);
  const Case u = run_case(Design::diagonals, z_drift, z_seed);
  EXPECT_GE(u.oracle, kResolvable);
  EXPECT_TRUE(direction_unresolved(u)) << u.direction_oracle;
  EXPECT_NE(u.verdict, Verdict::wrong) << u.found;
}

// The truth machine's own error against its model (its tables come from a
// laser campaign with noise) is what the simulation gets wrong as much as
// the hidden effect: a name of it is set apart, neither right nor wrong
// (of_the_machine()). XY ballbar case 969 (a scale of X) names a coupling
// x·y→X beside it that the machine's noise-free error holds (a wrong name
// before); grid case 89 (a pitch error of Z whose samples on the 5 levels
// lie on a line, named a scale Z) stays wrong: the machine's error holds
// none of that scale. At 0.15 µm noise (ABBE_DESIGNS_NOISE) the plate's
// null data named the machine's squareness and cycles in 46/50 cases; set
// apart, 50/50 are clean.
TEST(DiagnoseDesigns, TheMachinesOwnErrorIsNotAWrongName) {
  const auto [scale_x, seed] = sweep_case(Design::ballbar_xy, 969);
  ASSERT_EQ(scale_x.shape, Shape::scale);
  const Case c = run_case(Design::ballbar_xy, scale_x, seed);
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  ASSERT_EQ(c.of_machine.size(), c.effects.size());
  bool coupling_of_machine = false;
  for (std::size_t e = 0; e < c.effects.size(); ++e)
    coupling_of_machine =
        coupling_of_machine || (c.effects[e].term.kind == TermKind::coupling && c.of_machine[e]);
  EXPECT_TRUE(coupling_of_machine) << c.found;
  EXPECT_EQ(c.machine_names, 1);

  const auto [pitch_z, pitch_seed] = sweep_case(Design::grid, 89);
  ASSERT_EQ(pitch_z.shape, Shape::pitch);
  const Case w = run_case(Design::grid, pitch_z, pitch_seed);
  EXPECT_EQ(w.verdict, Verdict::wrong) << w.found;
  EXPECT_EQ(w.machine_names, 0) << w.found;
}

// A cycle's refined period stays within its family's range (the
// short-travel rules); where that holds it at the range's end, the aliases
// the scan found as good are refined too (aliases_at_range_end). Grid case
// 468 (a pitch error of Z, +3.1 µm at 16.6 mm, on 5 regular levels: not
// identifiable): held at 100.00 mm the cycle's path lost the revisit to an
// arm offset εZ×ΔY with a scale of Z, a wrong name (1000 seeds: 4/142 where
// not identifiable, 3/142 before the range was kept); with its aliases it
// is a cycle at 16.2 mm removing what 104.59 mm did before, `ambiguous`
// among the periods the 5 levels alias. Nothing else changed in 1000 seeds
// of any design, 200 of the 50 and 100 mm ballbars, 1000 of a 15×10×6 grid.
TEST(DiagnoseDesigns, ACycleHeldAtItsRangesEndIsRefinedAtItsAliases) {
  const auto [h, seed] = sweep_case(Design::grid, 468);
  ASSERT_EQ(h.shape, Shape::pitch);
  ASSERT_EQ(h.dir, 2);
  const Case with = run_case(Design::grid, h, seed);
  EXPECT_NE(with.verdict, Verdict::wrong) << with.found;
  bool cycle_in_range = false;
  for (const SelectedTerm& st : with.effects)
    cycle_in_range = cycle_in_range || (st.term.kind == TermKind::cyclic && st.term.axis == 2 &&
                                        st.term.period_mm < 100.0 - 1e-6);
  EXPECT_TRUE(cycle_in_range) << with.found;
  SelectionOptions held;
  held.aliases_at_range_end = false;
  const Case without = run_case(Design::grid, h, seed, 0.0, &held);
  EXPECT_EQ(without.verdict, Verdict::wrong) << without.found;
}

TEST(DiagnoseDesigns, ADriftAmbiguousOnlyInItsFormIsNamed) {
  Hidden drift_y;
  drift_y.shape = Shape::drift;
  drift_y.axis = drift_y.dir = 1;
  EXPECT_TRUE(same_drift_form("thermal_drift t→Y (at 3 time constants, 900 s – 1800 s)", drift_y));
  EXPECT_TRUE(same_drift_form("thermal_drift y·t→Y (τ 10800 s)", drift_y));
  EXPECT_TRUE(same_drift_form("thermal_drift x·t→Y", drift_y));
  EXPECT_FALSE(same_drift_form("thermal_drift z·t→Z (τ 600 s)", drift_y));
  EXPECT_FALSE(same_drift_form("scale Y", drift_y));
  EXPECT_FALSE(same_drift_form("reversal Y→Y growing along y", drift_y));
  EXPECT_FALSE(same_drift_form("any function of z on its 3 levels", drift_y));
  Hidden scale_y = drift_y;
  scale_y.shape = Shape::scale;
  EXPECT_FALSE(same_drift_form("thermal_drift t→Y", scale_y));
  // A drift ∝ a position: its mean scale is one of its forms.
  Hidden growing_y = drift_y;
  growing_y.proportional = true;
  EXPECT_TRUE(same_drift_form("scale Y", growing_y));
  EXPECT_FALSE(same_drift_form("scale X", growing_y));
  EXPECT_FALSE(same_drift_form("squareness dY ∝ x", growing_y));

  const auto [h, seed] = sweep_case(Design::ballbar, 266);
  ASSERT_EQ(h.shape, Shape::drift);
  ASSERT_EQ(h.dir, 1);
  const Case c = run_case(Design::ballbar, h, seed);
  EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  EXPECT_TRUE(c.by_form) << c.found;
  ASSERT_EQ(c.effects.size(), 1u) << c.found;
  EXPECT_EQ(c.effects[0].term.kind, TermKind::thermal_drift);
  EXPECT_FALSE(c.effects[0].ambiguous_with.empty()) << c.found;
}

// On the raster toolpath time follows y. A drift (x − x0)·f(t) of X was
// named scale X + a drift of X + a coupling x·y→X (case 37), and an
// off-centre coupling x·y→Y a drift x·t→Y (case 448): each is now
// `ambiguous` with the other (design_ambiguity.hpp, time following an axis
// the design does not level), and case 37 is named right by its scale and
// drift.
TEST(DiagnoseDesigns, WhereTimeFollowsARasterADriftAndACouplingAreNotToldApart) {
  const auto [drift, drift_seed] = sweep_case(Design::toolpath, 37);
  ASSERT_EQ(drift.shape, Shape::drift);
  ASSERT_TRUE(drift.proportional);
  const Case d = run_case(Design::toolpath, drift, drift_seed);
  EXPECT_EQ(d.verdict, Verdict::right) << d.found;
  bool coupling_ambiguous = false;
  for (const SelectedTerm& st : d.effects)
    if (st.term.kind == TermKind::coupling)
      coupling_ambiguous = !st.ambiguous_with.empty() &&
                           st.ambiguous_with[0].find("thermal_drift x·t→X") != std::string::npos;
  EXPECT_TRUE(coupling_ambiguous) << d.found;

  const auto [coupling, coupling_seed] = sweep_case(Design::toolpath, 448);
  ASSERT_EQ(coupling.shape, Shape::coupling);
  const Case c = run_case(Design::toolpath, coupling, coupling_seed);
  EXPECT_NE(c.verdict, Verdict::wrong) << c.found;
}

// Along the four body diagonals a drift ∝ (x − x0)·t in X, its zero
// anywhere, was named a drift y·t→Y in 6 of 734 cases (1000-seed sweep):
// about the machine's zero, y·t→Y fits it better than x·t→X does, beyond
// a one-column χ². Compared each with its zero free (the uniform drift of
// its direction beside it; RivalOptions::zero_free_drifts), x·t→X stands
// in as well and the name is `ambiguous`.
TEST(DiagnoseDesigns, ProportionalDriftsAreComparedWithTheirZeroFree) {
  RivalOptions fixed_zero;
  fixed_zero.zero_free_drifts = false;
  // Without the drift's course floor, which names cases 338 and 362 as a
  // scale X (ADriftWhoseCourseIsNotResolvedIsItsStaticForm).
  SelectionOptions course_free;
  course_free.drift_course_floor = false;
  for (int i : {14, 202, 338, 362, 734, 892}) {
    const auto [h, seed] = sweep_case(Design::diagonals, i);
    ASSERT_EQ(h.shape, Shape::drift);
    ASSERT_TRUE(h.proportional);
    const Case with = run_case(Design::diagonals, h, seed);
    EXPECT_NE(with.verdict, Verdict::wrong) << i << with.found;
    const Case without =
        run_case(Design::diagonals, h, seed, 0.0, &course_free, false, nullptr, &fixed_zero);
    EXPECT_EQ(without.verdict, Verdict::wrong) << i << without.found;
  }
}

// A drift ∝ (z − z0)·t of Z on the grid (cases 216 and 524 of the
// 1000-seed sweep, τ 2426 and 1713 s): its scan against the residual alone
// chose τ 300 s (nearly done: a scale of Z), so it was not a part of the
// structure a smooth function of (x, t) or (y, t) found, and the smooth
// function was left `unexplained`. Judged as a partner at every time
// constant of its grid (drift_parts_at_other_tau) it joins at 2700 s and is
// named, with the right kind and direction.
TEST(DiagnoseDesigns, ADriftJoinsAStructureAtAnotherTimeConstant) {
  SelectionOptions scanned_tau_only;
  scanned_tau_only.drift_parts_at_other_tau = false;
  for (int i : {216, 524}) {
    const auto [h, seed] = sweep_case(Design::grid, i);
    ASSERT_EQ(h.shape, Shape::drift);
    ASSERT_TRUE(h.proportional);
    ASSERT_EQ(h.dir, 2);
    const Case with = run_case(Design::grid, h, seed);
    EXPECT_EQ(with.verdict, Verdict::right) << i << with.found;
    EXPECT_NE(with.found.find("thermal_drift z·t→Z"), std::string::npos) << i << with.found;
    const Case without = run_case(Design::grid, h, seed, 0.0, &scanned_tau_only);
    EXPECT_EQ(without.verdict, Verdict::none) << i << without.found;
    EXPECT_NE(without.found.find("unexplained"), std::string::npos) << i << without.found;
  }
  // With such a drift the combination's lead must add a partner's floor
  // beside it: case 21's drift ∝ z (its oracle 0.05, at the resolution)
  // joined with a reversal of Z growing along z as the lead, which added
  // 28 µm² beside it (its floor 48); named, that reversal was a wrong name.
  const auto [h, seed] = sweep_case(Design::grid, 21);
  ASSERT_EQ(h.shape, Shape::drift);
  const Case c = run_case(Design::grid, h, seed);
  EXPECT_EQ(c.found.find("reversal"), std::string::npos) << c.found;
  EXPECT_NE(c.verdict, Verdict::wrong) << c.found;
}

// On the grid walked once a drift is identifiable only where its course
// within each Z level is resolved (course_unresolved()): case 181's drift
// of X (τ 686 s) adds 9 % beyond its best function of the 3 levels and is
// named; case 290's drift ∝ z of Z adds nothing beyond a value and a slope
// per level, and is `ambiguous` with any function of z on its 3 levels —
// what the data allow.
TEST(DiagnoseDesigns, AOnePassDriftIsIdentifiableOnlyByItsCourseWithinTheLevels) {
  {
    const auto [h, seed] = sweep_case(Design::grid_one_pass, 181);
    ASSERT_EQ(h.shape, Shape::drift);
    const Case c = run_case(Design::grid_one_pass, h, seed);
    EXPECT_GE(c.course_oracle, kResolvable);
    EXPECT_FALSE(course_unresolved(c));
    EXPECT_EQ(c.verdict, Verdict::right) << c.found;
  }
  const auto [h, seed] = sweep_case(Design::grid_one_pass, 290);
  ASSERT_EQ(h.shape, Shape::drift);
  const Case c = run_case(Design::grid_one_pass, h, seed);
  EXPECT_GE(c.oracle, kResolvable);         // the drift itself is resolved…
  EXPECT_LT(c.course_oracle, kResolvable);  // …its course within the levels is not
  EXPECT_TRUE(course_unresolved(c));
  EXPECT_EQ(c.verdict, Verdict::ambiguous) << c.found;
  // Elsewhere no case has a course measured.
  const auto [g, gseed] = sweep_case(Design::grid, 98);
  ASSERT_EQ(g.shape, Shape::drift);
  EXPECT_FALSE(course_unresolved(run_case(Design::grid, g, gseed)));
}

// The virtual machine's tables are read from a temporary directory, which
// is removed once they are (it used to stay in /tmp after every run).
TEST(DiagnoseDesigns, TheVirtualMachineLeavesNoFilesBehind) {
  ASSERT_FALSE(noisy_vm().machine.spec().table_file.empty());
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(::testing::TempDir()) /
                                       ("abbe_designs_vm_" + std::to_string(::getpid()))));
}

// A cycle leads a structure's combination only where it is significant
// beside the smooth function (SelectionOptions::cyclic_lead_beyond_smooth):
// case 108 of the grid, an off-centre coupling y·z→Y, is named as the
// coupling with its linear parts (scale Y, squareness dY ∝ z); when any
// significant cycle could lead, a cycle of Y (4.2 mm, `ambiguous` with its
// aliases) took the place of the scale.
TEST(DiagnoseDesigns, ACycleLeadsOnlyBesideTheSmoothFunction) {
  const auto [h, seed] = sweep_case(Design::grid, 108);
  ASSERT_EQ(h.shape, Shape::coupling);
  auto kinds = [](const Case& c) {
    std::set<TermKind> k;
    for (const SelectedTerm& st : c.effects) k.insert(st.term.kind);
    return k;
  };
  const Case with = run_case(Design::grid, h, seed);
  EXPECT_EQ(with.verdict, Verdict::right) << with.found;
  EXPECT_EQ(kinds(with).count(TermKind::cyclic), 0u) << with.found;
  EXPECT_EQ(kinds(with).count(TermKind::scale), 1u) << with.found;
  SelectionOptions any_lead;
  any_lead.cyclic_lead_beyond_smooth = false;
  const Case without = run_case(Design::grid, h, seed, 0.0, &any_lead);
  EXPECT_EQ(kinds(without).count(TermKind::cyclic), 1u) << without.found;
}

// Gross outliers (issue 16): 2 % of the grid's points 20–50 µm off in one
// component, on top of a hidden effect of 1–2 µm (2–4× the noise) or of
// null data. The outliers are flagged and left out: the effect is still
// named where the design resolves it, no effect is made of the outliers (no
// wrong name; null data stay clean), and the noise estimates stay within a
// factor 1.5 of the true 0.5 µm.
TEST(DiagnoseDesigns, GridWithOutliers) {
  const int n = std::max(8, seeds() / 2);
  const Box b = box();
  const double L = noisy_vm().generated.truth.tool_length;
  Rates r;
  std::size_t injected = 0, flagged = 0, false_flags = 0;
  int noise_ok = 0, independent_ok = 0;
  int right_without = 0, lost = 0, gained = 0;
  for (int i = 0; i < n; ++i) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(9000 + 37 * i));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto seed = static_cast<std::uint64_t>(500 + i);
    Hidden h;
    if (i % 4 != 3) {
      do {
        h = draw(rng, b, L);
      } while (!identifiable(Design::grid, h));
      h.a = h.sign * (2.0 + 2.0 * u(rng)) * noise_level();
      h.text = fmt::format("{} axis {} dir {} {:+.2f} µm", shape_name(h.shape), "XYZ"[h.axis],
                           "XYZ"[h.dir], h.a);
    }
    const Case c = run_case(Design::grid, h, seed, 0.02);
    // The same measurement without the outliers: what they cost.
    const Case clean = run_case(Design::grid, h, seed);
    if (h.shape != Shape::none && c.oracle >= kResolvable) {
      const bool with_right = c.verdict == Verdict::right;
      const bool without_right = clean.verdict == Verdict::right;
      right_without += without_right ? 1 : 0;
      lost += without_right && !with_right ? 1 : 0;
      gained += with_right && !without_right ? 1 : 0;
    }
    injected += c.injected;
    flagged += c.flagged;
    false_flags += c.false_flags;
    const bool nok = c.noise_um < 1.5 * noise_level() && c.noise_um > noise_level() / 1.5;
    const bool iok = c.noise_independent_um < 1.5 * noise_level() &&
                     c.noise_independent_um > noise_level() / 1.5;
    noise_ok += nok ? 1 : 0;
    independent_ok += iok ? 1 : 0;
    std::string tag;
    if (h.shape == Shape::none) {
      tag = r.add_null(c.verdict);
    } else if (c.oracle >= kResolvable) {
      tag = r.add_identifiable(c.verdict);
    } else {
      ++r.n_un;
      r.un_wrong += c.verdict == Verdict::wrong ? 1 : 0;
      tag = c.verdict == Verdict::wrong ? "below resolution, WRONG NAME" : "below resolution";
    }
    std::cerr << fmt::format(
        "outliers | seed {:3d} | {:<45} | {:<12} | flagged {}/{} +{} false | noise {:.3f} "
        "(data alone {:.3f}) |{}\n",
        i, h.text, tag, c.flagged, c.injected, c.false_flags, c.noise_um, c.noise_independent_um,
        c.found);
  }
  std::cerr << fmt::format(
      "RATES | grid with 2 % outliers, hidden 1-2 µm | named right {}/{} , wrong {} (+{} below "
      "resolution) | null clean {}/{} | outliers flagged {}/{} , false flags {} | noise within "
      "x1.5: fit {}/{} , data alone {}/{} | without the outliers named right {}/{} (lost to "
      "them {}, gained {})\n",
      r.id_right, r.n_id, r.id_wrong, r.un_wrong, r.null_clean, r.n_null, flagged, injected,
      false_flags, noise_ok, n, independent_ok, n, right_without, r.n_id, lost, gained);
  EXPECT_EQ(r.id_wrong + r.un_wrong, 0);  // no effect made of outliers
  EXPECT_EQ(r.null_clean, r.n_null);
  // 12/13 with 20 seeds (11/13 before design_ambiguity), 41/49 with 100
  // (with the combinations entering whole and the swap test). The same
  // measurements without the outliers name the same 41/49 (lost 0, gained
  // 0): the misses are effects of 2–4× the noise at the edge of this design,
  // not the outliers' doing, and the outliers may cost at most 1 in 20.
  EXPECT_GE(r.n_id ? static_cast<double>(r.id_right) / r.n_id : 1.0, 0.8);
  EXPECT_LE(lost, r.n_id / 20) << "named right without the outliers, missed with them";
  EXPECT_GE(static_cast<double>(flagged), 0.95 * static_cast<double>(injected));
  EXPECT_LE(static_cast<double>(false_flags), 0.002 * 960.0 * n);
  // The noise after the fit (the significance floor's σ̂) is within the
  // factor in every case. The estimate from the data alone scatters
  // 0.32–1.0 µm on this grid with or without the outliers (measured: the
  // same 20 cases without outliers give the same values and the same
  // names), so it is held to most cases only.
  EXPECT_EQ(noise_ok, n);
  EXPECT_GE(independent_ok, (3 * n) / 4);
}

}  // namespace
}  // namespace abbe::diagnose
