#pragma once
// The machines and points of the Monte Carlo uncertainty tests
// (prediction_uncertainty_test.cpp, aligned_uncertainty_test.cpp).
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/machine.hpp"
#include "model_test_machines.hpp"

namespace abbe::test {

// A table with every component of every axis (values of a few µm/µrad) and
// per-target uncertainties; reflectors away from the points.
inline std::string full_table(bool with_u, double u_target) {
  std::string csv =
      with_u ? "axis,component,position_mm,direction,value,uncertainty\n" : std::string(kHeader);
  int k = 0;
  for (char a : {'X', 'Y', 'Z'})
    for (char d : {'X', 'Y', 'Z', 'A', 'B', 'C'})
      for (int i = 0; i <= 6; ++i, ++k) {
        const double v = 3.0 * std::sin(0.7 * k);
        csv += fmt::format("{},E{}{},{},mean,{:.6f}", a, d, a, -1200.0 + 400.0 * i, v);
        if (with_u) csv += fmt::format(",{}", u_target);
        csv += "\n";
      }
  return csv;
}

inline machine::MachineSpec full_spec(bool with_u, double u_target) {
  machine::MachineSpec spec =
      spec_with("w X' b Y Z t", full_table(with_u, u_target), Eigen::Vector3d(-500, -250, -280),
                130.0, Eigen::Vector3d(-800, -256, -478));
  spec.squareness = {14.0, -24.0, 13.0};
  return spec;
}

inline const char* kPoints =
    "x,y,z\n-100,-50,-30\n-300,-200,-250\n-650,-420,-120\n-900,-10,-400\n-480,-333,-333\n"
    "-20,-590,-10\n-777,-111,-222\n-250,-250,-250\n";

inline void set_all_sources(machine::CampaignUncertainty& u) {
  u.given = true;
  u.laser_constant_um = 0.2;
  u.laser_ppm = 1.0;
  u.component.fill(0.3);
  u.reflector_mm = 2.0;
  u.squareness_urad = {1.0, 1.5, 0.5};
}

}  // namespace abbe::test
