// compensated_compare: checks LinuxCNC rs274's reading of a program
// compensated by `abbe compensate` against abbe's compensation vectors.
//
// usage: compensated_compare MACHINE ORIGINAL RS274_ORIGINAL RS274_COMPENSATED
// prints one line "<class>\t<motions>\t<detail>" and exits 0 (matched) or 1
// (mismatch).
//
// The compensation vector of a motion is computed here, independently of
// the program rewriting: the original program is interpreted with the
// machine's configuration and fragmented as `abbe compensate` does (5 mm),
// and PointSolver (the ae-arm model of MACHINE) gives c − n at the motion's
// end point with the direction signs of the motion (a zero-length motion
// keeps the previous vector: the commanded point does not move). Then, in
// rs274's canonical output, every end point of the compensated program must
// equal the original's end point plus that vector:
//  - straight and arc motions: all three coordinates; the compensated
//    program may have extra feed motions before it (the pieces a split move
//    was cut into), matched in order;
//  - canned cycles (several motions from one line): per hole (the motions
//    ending at one in-plane position) the bottom (the feed end farthest from
//    where the block leaves the tool) all three coordinates, the other
//    motions in the plane only (R plane, clearance level and peck depths are
//    not compensated); a G91 cycle with L repeats shares one increment among
//    its holes (a least-squares fit, docs/compensation.md): 4 µm allowed.
// The slack is rs274's printed resolution (0.5e-4 program units) of both
// numbers, the compensated program's own rounding (the same) and the
// solver's 0.01 µm.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/compensate/point_solver.hpp"
#include "abbe/gcode/motion.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "canon_reader.hpp"

namespace {

using interop::Canon;
using interop::Kind;

struct Expected {
  Kind kind = Kind::other;
  std::size_t line = 0;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();  // c − n at the end, mm
  // Accepted vectors: d, and at an arc end with an axis at its reversal the
  // vectors with that axis's sign −1, 0 or +1.
  std::vector<Eigen::Vector3d> alt;
  bool cycle = false;      // one of several motions of a line
  bool bottom = false;     // a hole bottom of a cycle
  int normal = 2;          // drill axis of a cycle
  double allowance = 0.0;  // mm (G91 L repeats)
};

Kind kind_of(abbe::gcode::MotionKind k) {
  switch (k) {
    case abbe::gcode::MotionKind::rapid:
      return Kind::traverse;
    case abbe::gcode::MotionKind::linear:
      return Kind::feed;
    case abbe::gcode::MotionKind::arc:
      return Kind::arc;
    default:
      return Kind::other;
  }
}

// Compensation vectors at every motion end of the original (dwells left out).
std::vector<Expected> compensation_vectors(const std::string& machine_file,
                                           const std::string& program) {
  const abbe::machine::Machine m = abbe::machine::Machine::load(machine_file);
  const abbe::model::ErrorModel em(m, abbe::model::ModelKind::ae_arm);
  const abbe::compensate::PointSolver solver(em);
  abbe::model::ModelData data;
  abbe::path::Fragmenter fragmenter(abbe::path::FragmentOptions{5.0, 10000.0});
  std::vector<abbe::gcode::Motion> motions;
  std::vector<Expected> out;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  std::ifstream in(program, std::ios::binary);
  abbe::gcode::run_program(
      in, program, abbe::pipeline::interpreter_config(m), [&](const abbe::gcode::Motion& mo) {
        if (mo.kind == abbe::gcode::MotionKind::dwell) return;
        bool have = false;
        abbe::path::PathPoint last;
        // The start point the fragmenter repeats is not a target.
        fragmenter.add(mo, [&](const abbe::path::PathPoint& pp) {
          if (!have && pp.p == mo.start && (pp.p - mo.end).norm() > 0.0) return;
          last = pp;
          have = true;
        });
        if (have) d = solver.solve(abbe::pipeline::eval_point(last), data).c - last.p;
        Expected e;
        e.kind = kind_of(mo.kind);
        e.alt.push_back(d);
        // At an arc end where an in-plane axis is at (or
        // within 1° of) its reversal the direction sign of
        // that axis is ambiguous: either side's tables
        // (or none) may be taken.
        if (have && mo.kind == abbe::gcode::MotionKind::arc) {
          const abbe::compensate::MotionPath path(mo);
          const Eigen::Vector3d v = path.at(1.0) - path.at(1.0 - 1e-6);
          std::vector<int> open;
          for (int a = 0; a < 3; ++a)
            if (std::abs(v[a]) <= 0.02 * v.norm()) open.push_back(a);
          const int combos = open.size() == 1 ? 3 : open.size() == 2 ? 9 : 1;
          for (int c = 0; c < combos && !open.empty(); ++c) {
            abbe::model::EvalPoint ep = abbe::pipeline::eval_point(last);
            ep.dir[static_cast<std::size_t>(open[0])] = static_cast<std::int8_t>(c % 3 - 1);
            if (open.size() > 1)
              ep.dir[static_cast<std::size_t>(open[1])] = static_cast<std::int8_t>(c / 3 - 1);
            e.alt.push_back(solver.solve(ep, data).c - last.p);
          }
        }
        e.line = mo.line;
        e.d = d;
        e.normal = abbe::gcode::plane_axes(mo.plane)[2];
        out.push_back(e);
        motions.push_back(mo);
      });
  // Canned cycles: the motions of one line. A hole is the set of motions
  // ending at one in-plane position; its bottom is the feed end farthest
  // from where the block leaves the tool (pecks end short of it).
  for (std::size_t a = 0; a < out.size();) {
    std::size_t b = a + 1;
    while (b < out.size() && out[b].line == out[a].line) ++b;
    if (b - a > 1) {
      const int n = out[a].normal;
      const Eigen::Vector3d leave = motions[b - 1].end;
      auto in_plane = [&](std::size_t i) {
        Eigen::Vector3d q = motions[i].end;
        q[n] = 0.0;
        return q;
      };
      std::vector<std::size_t> bottom_of(b - a, b);  // per motion: its hole's bottom
      std::size_t holes = 0;
      for (std::size_t i = a; i < b; ++i) {
        if (bottom_of[i - a] != b) continue;
        ++holes;
        std::size_t best = b;
        for (std::size_t k = i; k < b; ++k)
          if ((in_plane(k) - in_plane(i)).norm() < 1e-9 &&
              motions[k].kind == abbe::gcode::MotionKind::linear &&
              (best == b || (motions[k].end - leave).norm() > (motions[best].end - leave).norm()))
            best = k;
        for (std::size_t k = i; k < b; ++k)
          if ((in_plane(k) - in_plane(i)).norm() < 1e-9) bottom_of[k - a] = best;
      }
      for (std::size_t i = a; i < b; ++i) {
        out[i].cycle = true;
        const std::size_t bot = bottom_of[i - a];
        if (bot == b) continue;  // no feed at this position (a rapid between holes)
        out[i].d = out[bot].d;
        out[i].alt = {out[bot].d};
        out[i].bottom = i == bot;
        if (holes > 1) out[i].allowance = 4e-3;
      }
    }
    a = b;
  }
  return out;
}

std::vector<Canon> motions_of(const std::vector<Canon>& all) {
  std::vector<Canon> out;
  for (const Canon& c : all)
    if (c.kind == Kind::traverse || c.kind == Kind::feed || c.kind == Kind::arc) out.push_back(c);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: compensated_compare MACHINE ORIGINAL RS274_ORIGINAL RS274_COMPENSATED\n";
    return 2;
  }
  std::vector<Expected> want;
  try {
    want = compensation_vectors(argv[1], argv[2]);
  } catch (const abbe::InputError& e) {
    std::cout << "mismatch\t0\tabbe cannot interpret the original: " << e.what() << "\n";
    return 1;
  }
  std::string err_o, err_c;
  const std::vector<Canon> o = motions_of(interop::read_rs274(argv[3], err_o));
  const std::vector<Canon> c = motions_of(interop::read_rs274(argv[4], err_c));
  if (!err_c.empty() && err_o.empty()) {
    std::cout << "mismatch\t0\trs274 refuses the compensated program: " << err_c << "\n";
    return 1;
  }
  if (o.size() != want.size()) {
    std::cout << "mismatch\t0\trs274 made " << o.size() << " motions of the original, abbe "
              << want.size() << "\n";
    return 1;
  }
  constexpr double kSolver = 1e-5;  // mm
  std::size_t j = 0, pieces = 0;
  double max_d = 0.0, max_res = 0.0;
  char buf[512];
  // compensate writes no word for an axis the program has not commanded yet
  // (its position is only assumed): until the original's ends leave rs274's
  // start value 0 on an axis, that axis may also keep its nominal value.
  std::array<bool, 3> commanded{};
  for (std::size_t i = 0; i < o.size(); ++i) {
    const Expected& e = want[i];
    const Eigen::Vector3d original(o[i].end[0], o[i].end[1], o[i].end[2]);
    for (int a = 0; a < 3; ++a)
      if (original[a] != 0.0) commanded[static_cast<std::size_t>(a)] = true;
    std::vector<Eigen::Vector3d> alts = e.alt;
    if (!(commanded[0] && commanded[1] && commanded[2]))
      for (const Eigen::Vector3d& d : e.alt) {
        Eigen::Vector3d kept = d;
        for (int a = 0; a < 3; ++a)
          if (!commanded[static_cast<std::size_t>(a)]) kept[a] = 0.0;
        alts.push_back(kept);
      }
    const Eigen::Vector3d target = original + e.d;
    auto residual_to = [&](const Canon& x, const Eigen::Vector3d& t, double& worst) {
      worst = 0.0;
      bool ok = true;
      for (int a = 0; a < 3; ++a) {
        if (e.cycle && !e.bottom && a == e.normal) continue;
        const double r = std::abs(x.end[a] - t[a]);
        const double slack = o[i].slack[a] + 2.0 * x.slack[a] + kSolver + e.allowance + 1e-9;
        worst = std::max(worst, r);
        ok = ok && r <= slack;
      }
      return ok;
    };
    // Whether x ends at the original plus one of the accepted vectors; worst:
    // the least residual among the vectors it matches (among all if none).
    auto residual = [&](const Canon& x, double& worst) {
      bool ok = false;
      worst = 1e300;
      for (const Eigen::Vector3d& d : alts) {
        double w = 0.0;
        const bool hit = residual_to(x, original + d, w);
        if (hit && !ok)
          worst = w;  // the first match: misses no longer count
        else if (hit || !ok)
          worst = std::min(worst, w);
        ok = ok || hit;
      }
      return ok;
    };
    bool found = false;
    double worst = 0.0;
    while (j < c.size()) {
      if (c[j].kind == e.kind && residual(c[j], worst)) {
        found = true;
        break;
      }
      // A piece of a split feed: a feed or arc before the motion's own end.
      const bool piece = !e.cycle && (e.kind == Kind::feed || e.kind == Kind::arc) &&
                         (c[j].kind == Kind::feed || c[j].kind == Kind::arc);
      if (!piece) break;
      ++pieces;
      ++j;
    }
    if (!found) {
      const Canon* x = j < c.size() ? &c[j] : nullptr;
      if (x) residual(*x, worst);
      std::snprintf(buf, sizeof buf,
                    "motion %zu (line %zu): expected end (%.4f, %.4f, %.4f) = original + "
                    "(%.2f, %.2f, %.2f) µm, rs274 has %s (%.1f µm off)",
                    i + 1, e.line, target[0], target[1], target[2], 1e3 * e.d[0], 1e3 * e.d[1],
                    1e3 * e.d[2], x ? x->text.c_str() : "no more motions", 1e3 * worst);
      std::cout << "mismatch\t" << i << "\t" << buf << "\n";
      return 1;
    }
    max_d = std::max(max_d, e.d.norm());
    max_res = std::max(max_res, worst);
    ++j;
  }
  if (j != c.size()) {
    std::cout << "mismatch\t" << o.size() << "\t" << c.size() - j
              << " extra motions at the end of the compensated program\n";
    return 1;
  }
  std::snprintf(buf, sizeof buf,
                "%zu pieces inserted, max |c − n| %.2f µm, max |end − (orig + (c − n))| %.2f µm",
                pieces, 1e3 * max_d, 1e3 * max_res);
  std::cout << "matched\t" << o.size() << "\t" << buf << "\n";
  return 0;
}
