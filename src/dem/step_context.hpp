// dem/step_context: what every stage of one step reads about that step: its length, the top plate's
// motion at its end, and the plates' displacement, velocity and acceleration by Plate index.
// Owns: nothing but this value type.
#pragma once

#include <array>

#include "dem/params.hpp"

namespace rupture::dem {

struct StepContext {
  double dt = 0.0;       // s
  double half_dt = 0.0;  // s: the kicks' length; 0 for a force pass outside a step (no kick)
  PlateMotion top;
  std::array<double, 3> plate_u{}, plate_v{}, plate_a{};  // mm, mm/s, mm/s^2 per Plate

  static StepContext at(double dt, double half_dt, const PlateMotion& top) {
    return {dt,
            half_dt,
            top,
            {0.0, 0.0, top.displacement},
            {0.0, 0.0, top.velocity},
            {0.0, 0.0, top.acceleration}};
  }
};

}  // namespace rupture::dem
