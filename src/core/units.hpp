// The one table of units armctl reads (core/quantity.cpp holds it): deg and rad (angles), mm
// and m (lengths). Every reader of values with units goes through it: the command line and
// arm files through parse_quantity (core/quantity.hpp), the recording files' "joint:unit"
// headers through find_unit.
#pragma once

#include <string_view>

#include "core/quantity.hpp"

namespace armctl {

struct QuantityUnit {
  const char* name;  // "deg"
  Dimension dimension;
  double to_si;  // the SI value of 1 of this unit
};

// The unit called `name` ("deg", "rad", "mm", "m"; no rate suffix), or nullptr.
const QuantityUnit* find_unit(std::string_view name);
// The unit a value of this dimension is written in for people: deg or mm.
const QuantityUnit& display_unit_of(Dimension d);

}  // namespace armctl
