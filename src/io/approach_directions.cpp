#include "abbe/io/approach_directions.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>

namespace abbe::io {

std::vector<int> infer_approach_directions(MeasuredData& data, double min_move_mm) {
  std::vector<int> filled;
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const bool given = std::any_of(data.rows.begin(), data.rows.end(),
                                   [&](const MeasuredRow& r) { return r.v[jj] != 0; });
    if (!given && !data.rows.empty()) filled.push_back(j);
  }
  if (filled.empty()) return filled;
  // The rows of each set, in file order, then stably by time.
  std::map<std::string, std::vector<std::size_t>> sets;
  for (std::size_t i = 0; i < data.rows.size(); ++i) sets[data.rows[i].set].push_back(i);
  for (auto& [name, rows] : sets) {
    std::stable_sort(rows.begin(), rows.end(),
                     [&](std::size_t a, std::size_t b) { return data.rows[a].t < data.rows[b].t; });
    for (int j : filled) {
      const auto jj = static_cast<std::size_t>(j);
      std::int8_t last = 0;
      for (std::size_t k = 0; k < rows.size(); ++k) {
        MeasuredRow& r = data.rows[rows[k]];
        if (k > 0) {
          const double move = r.p[j] - data.rows[rows[k - 1]].p[j];
          if (move > min_move_mm) last = 1;
          if (move < -min_move_mm) last = -1;
        }
        r.v[jj] = last;
      }
    }
  }
  // An axis that never moved stays 0: nothing was inferred for it.
  filled.erase(std::remove_if(filled.begin(), filled.end(),
                              [&](int j) {
                                return std::none_of(data.rows.begin(), data.rows.end(),
                                                    [&](const MeasuredRow& r) {
                                                      return r.v[static_cast<std::size_t>(j)] != 0;
                                                    });
                              }),
               filled.end());
  return filled;
}

}  // namespace abbe::io
