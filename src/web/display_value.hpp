// Values as the API shows them: deg or mm (core/quantity.hpp's to_display), rounded to a
// millionth — far below any joint's resolution — so that 48 deg reads 48.0, not
// 47.99999999999999 after a round trip through radians.
#pragma once

#include <cmath>

#include "core/quantity.hpp"

namespace armctl::web {

inline double tidy(double v) { return std::round(v * 1e6) / 1e6 + 0.0; }  // + 0.0: no "-0"
inline double display_value(Dimension d, double si) { return tidy(to_display(d, si)); }

}  // namespace armctl::web
