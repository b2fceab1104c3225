// random_programs: writes N random but valid NC programs (fixed seeds, so the
// set is the same on every run) for the differential test against rs274:
// lines and arcs (IJK, R of both signs, turns, helices) in the three planes,
// G90/G91, G20/G21, work offsets, the G92 family, G43/G49, dwells and every
// supported canned cycle with G98/G99 and L repeats.
//
// usage: random_programs COUNT OUTPUT_DIR
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

class Generator {
 public:
  explicit Generator(unsigned seed) : rng_(seed) {}

  std::string program() {
    inch_ = chance(0.3);
    scale_ = inch_ ? 0.04 : 1.0;
    line(inch_ ? "G20" : "G21");
    line("G90 G17 G94 F" + num(uniform(50, 500) * scale_));
    reset_position();
    const int blocks = static_cast<int>(uniform(20, 60));
    for (int b = 0; b < blocks; ++b) {
      const double k = uniform(0, 1);
      if (k < 0.22)
        straight();
      else if (k < 0.47)
        arc();
      else if (k < 0.52)
        plane();
      else if (k < 0.57)
        distance_mode();
      else if (k < 0.61)
        line("G4 P" + num(uniform(0, 2)));
      else if (k < 0.66)
        frame();
      else if (k < 0.71)
        tool_length();
      else if (k < 0.88)
        cycle();
      else
        units();
    }
    line("M2");
    return text_;
  }

 private:
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  bool chance(double p) { return uniform(0, 1) < p; }
  void line(const std::string& s) { text_ += s + "\n"; }
  double round3(double v) { return std::round(v * 1000.0) / 1000.0; }

  // After anything that moves the program frame: absolute move to zero.
  void reset_position() {
    line("G90 G0 X0 Y0 Z0");
    pos_[0] = pos_[1] = pos_[2] = 0.0;
    incremental_ = false;
  }

  std::string axis_word(int a, double target) {
    const std::string w = std::string(1, "XYZ"[a]) + num(incremental_ ? target - pos_[a] : target);
    pos_[a] = target;
    return w;
  }

  void straight() {
    std::string block = pick(2) ? "G1" : "G0";
    for (int a = 0; a < 3; ++a)
      if (chance(0.7)) block += " " + axis_word(a, round3(uniform(-50, 50) * scale_));
    line(block);
  }

  void arc() {
    static const int kAxes[3][3] = {{0, 1, 2}, {2, 0, 1}, {1, 2, 0}};
    const int* ax = kAxes[plane_];
    const double radius = uniform(1, 30) * scale_;
    const double a0 = uniform(0, 2 * M_PI), a1 = uniform(0, 2 * M_PI);
    const double c0 = pos_[ax[0]] - radius * std::cos(a0);
    const double c1 = pos_[ax[1]] - radius * std::sin(a0);
    double target[3] = {pos_[0], pos_[1], pos_[2]};
    target[ax[0]] = std::round((c0 + radius * std::cos(a1)) * 1e4) / 1e4;
    target[ax[1]] = std::round((c1 + radius * std::sin(a1)) * 1e4) / 1e4;
    if (chance(0.3)) target[ax[2]] = round3(pos_[ax[2]] + uniform(-5, 5) * scale_);
    const double start0 = pos_[ax[0]], start1 = pos_[ax[1]];
    std::string block = pick(2) ? "G2" : "G3";
    for (int a = 0; a < 3; ++a)
      if (target[a] != pos_[a] || chance(0.3)) block += " " + axis_word(a, target[a]);
    if (chance(0.5)) {
      block += std::string(" ") + "IJK"[ax[0]] + num(c0 - start0);
      block += std::string(" ") + "IJK"[ax[1]] + num(c1 - start1);
      if (chance(0.2)) block += " P" + std::to_string(1 + pick(3));
    } else {
      const double chord = std::hypot(target[ax[0]] - start0, target[ax[1]] - start1);
      if (chord < 1e-3) return;
      const double r = std::max(radius, chord / 2 + 0.01 * scale_);
      block += " R" + num(chance(0.5) ? r : -r);
    }
    line(block);
  }

  void plane() {
    plane_ = pick(3);
    line(plane_ == 0 ? "G17" : plane_ == 1 ? "G18" : "G19");
  }

  void distance_mode() {
    incremental_ = !incremental_;
    line(incremental_ ? "G91" : "G90");
  }

  void frame() {
    static const char* kCodes[] = {"G54", "G55",   "G56",   "G57",  "G58",
                                   "G59", "G92.1", "G92.2", "G92.3"};
    if (chance(0.4))
      line("G92 X" + num(uniform(-10, 10) * scale_) + " Z" + num(uniform(-10, 10) * scale_));
    else
      line(kCodes[pick(9)]);
    reset_position();
  }

  void tool_length() {
    line(chance(0.3) ? "G49" : "G43 H" + std::to_string(1 + pick(9)));
    reset_position();
  }

  void cycle() {
    static const int kAxes[3][3] = {{0, 1, 2}, {2, 0, 1}, {1, 2, 0}};
    static const char* kCodes[] = {"G81", "G82", "G83", "G73", "G85", "G89"};
    const int* ax = kAxes[plane_];
    const std::string code = kCodes[pick(6)];
    std::string block = std::string(pick(2) ? "G98 " : "G99 ") + code;
    auto word = [](int a, double v) { return std::string(" ") + "XYZ"[a] + num(v); };
    if (incremental_) {
      block += word(ax[0], uniform(-10, 10) * scale_) + word(ax[1], uniform(-10, 10) * scale_);
      block += " R" + num(uniform(-5, 5) * scale_) + word(ax[2], -uniform(0.5, 10) * scale_);
    } else {
      const double r = uniform(-10, 10) * scale_;
      block += word(ax[0], uniform(-50, 50) * scale_) + word(ax[1], uniform(-50, 50) * scale_);
      block += " R" + num(r) + word(ax[2], r - uniform(0.5, 10) * scale_);
    }
    if (code == "G82" || code == "G89") block += " P" + num(uniform(0, 1));
    if (code == "G83" || code == "G73") block += " Q" + num(uniform(0.3, 3) * scale_);
    if (chance(0.3)) block += " L" + std::to_string(1 + pick(3));
    line(block);
    if (chance(0.5)) {  // a second hole in the same series
      line(word(ax[0], (incremental_ ? 1 : 10) * scale_).substr(1));
    }
    line("G80");
    reset_position();
  }

  void units() {
    // rs274 does not convert an active tool length offset when the units
    // change (docs/interop.md), so cancel it first.
    line("G49");
    inch_ = !inch_;
    scale_ = inch_ ? 0.04 : 1.0;
    line(inch_ ? "G20" : "G21");
    reset_position();
  }

  std::mt19937 rng_;
  std::string text_;
  bool inch_ = false;
  bool incremental_ = false;
  double scale_ = 1.0;
  int plane_ = 0;
  double pos_[3] = {0, 0, 0};
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: random_programs COUNT OUTPUT_DIR\n");
    return 2;
  }
  const int count = std::atoi(argv[1]);
  for (int i = 0; i < count; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/random-%04d.ngc", i);
    std::ofstream out(std::string(argv[2]) + name);
    out << Generator(1000u + static_cast<unsigned>(i)).program();
    if (!out) {
      std::fprintf(stderr, "random_programs: cannot write %s%s\n", argv[2], name);
      return 1;
    }
  }
  return 0;
}
