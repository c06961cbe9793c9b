// loading/ramp: the top plate's prescribed motion: speed rising smoothly from 0 to v over a ramp
// time T, then constant. Owns the schedule only. Not: plates' forces (dem/) or the run loop.
#pragma once

#include <cmath>

#include "core/units.hpp"
#include "dem/system.hpp"

namespace rupture::loading {

// v(t) = v/2 (1 - cos(pi t / T)) for t < T, then v: velocity and acceleration are continuous, so
// the start sends no shock through the sample. Displacement is the exact integral of v(t).
struct SpeedRamp {
  double speed = 50.0;     // mm/s
  double ramp_time = 0.0;  // s (0: the plate starts at full speed)

  dem::PlateMotion at(double t) const {
    if (t >= ramp_time) {
      return {speed * (t - 0.5 * ramp_time), speed, 0.0};
    }
    const double w = units::pi / ramp_time;
    return {0.5 * speed * (t - std::sin(w * t) / w), 0.5 * speed * (1.0 - std::cos(w * t)),
            0.5 * speed * w * std::sin(w * t)};
  }
};

}  // namespace rupture::loading
