#pragma once
// Approach directions from the order of the points (docs/formats.md,
// "Measured data"). Measured files often carry no vx vy vz; without them the
// model takes the mean of its up and down tables and a reversal cannot be
// tested. Where every row of a file has v_j = 0 for an axis j, this fills
// v_j from the points themselves, walked per `set` in time order (file
// order where t does not vary within the set): v_j = sign(p_j − p_j of the
// previous point) when the axis moved more than `min_move_mm`, else the
// previous point's v_j; 0 until the axis first moves. It assumes each point
// was reached from the one before along a path whose last motion of each
// axis has that sign (a grid or a line walked point to point); a probing
// cycle or an approach strategy (ISO 230-2 overrun) breaks it — then the
// file's own v columns are the only truth. Axes with any nonzero v in the
// file keep the file's values.
#include <vector>

#include "abbe/io/measured_data.hpp"

namespace abbe::io {

// Returns the axes it filled (0 = X, 1 = Y, 2 = Z; an axis that never moves
// stays 0 and is not among them).
std::vector<int> infer_approach_directions(MeasuredData& data, double min_move_mm = 1e-3);

}  // namespace abbe::io
