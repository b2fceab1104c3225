#pragma once
// The virtual laser campaign (ISO 230-2 style): per axis, targets every
// `spacing_mm` over the travel, `runs` bidirectional runs; the other axes
// stand at their measured_at positions with their error motions absent
// (v1 simplification); linear components are read at the reflector point M
// (reading = [E_j(M) − M]_k, exact), angular ones directly; Gaussian noise.
#include <string>
#include <vector>

#include "abbe/sim/truth_generator.hpp"

namespace abbe::sim {

struct RunReading {
  int axis = 0;
  int component = 0;
  double target_mm = 0.0;
  int run = 1;
  int dir = +1;  // +1 up (fwd), −1 down (rev)
  double deviation = 0.0;
};

struct TableEntry {
  int axis = 0;
  int component = 0;
  double position_mm = 0.0;
  double fwd = 0.0;  // mean over the up runs
  double rev = 0.0;  // mean over the down runs
};

struct CampaignResult {
  std::vector<RunReading> runs;
  std::vector<TableEntry> table;
  Squareness squareness;  // as measured (with noise)
};

// Target positions of axis j: travel_min + k·spacing, plus travel_max.
std::vector<double> campaign_targets(const AxisTruth& axis, double spacing_mm);

CampaignResult run_campaign(const GeneratedMachine& machine);

std::string runs_to_csv(const CampaignResult& result);
std::string table_to_csv(const CampaignResult& result);
// The machine file (docs/formats.md schema); `table_file` is written as `table:`.
std::string machine_to_yaml(const GeneratedMachine& machine, const CampaignResult& result,
                            const std::string& table_file);

}  // namespace abbe::sim
