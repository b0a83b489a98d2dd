// Crack paths read off a damage field: the direction a crack runs from a tip, how far a crack
// front has gone, and how many branches cross a line.
#pragma once
#include <vector>

namespace rift::fracture {

struct DamagePoint {
  double x, y, damage;
};

/// Direction (degrees, atan2 of the mean principal axis) of the damaged points (damage >=
/// threshold) at distance in [r_min, r_max] from the tip, on the side given by `side_sign`
/// (+1: y > tip y, -1: y < tip y); NaN when fewer than 3 points qualify.
double crack_direction_degrees(const std::vector<DamagePoint>& field, double tip_x, double tip_y, double r_min,
                               double r_max, double threshold, int side_sign);

/// Largest x of a damaged point (damage >= threshold) with y in [y_lo, y_hi]; -inf when none.
double damage_front_x(const std::vector<DamagePoint>& field, double y_lo, double y_hi, double threshold);

/// Number of separate damaged stretches (damage >= threshold) along the vertical line x = line_x,
/// sampling points within half a spacing of the line; gaps longer than `gap` separate branches.
int branches_crossing(const std::vector<DamagePoint>& field, double line_x, double spacing, double threshold, double gap);

}  // namespace rift::fracture
