#pragma once
// Ready-made simulator configurations shared by irgs-sim and the GUI.

#include "core/sim/simulator.hpp"

namespace irgs {

// `base` with the odometry errors of a typical small hand-built robot: wheels differing by
// +-0.05 %, effective wheelbase 0.5 % wider than nominal (tyre contact), 0.1 % random slip per
// step. irgs-sim and the GUI simulate with these unless told to run ideal; sensor noise keeps
// the simulator's defaults.
SimConfig typicalSimConfig(SimConfig base = {});

// `base` with every error source switched off: exact odometry, noise-free sonar without dropouts.
// The paper-003 simulator ran this way ("the simulation excludes sensor and actuator errors").
SimConfig idealSimConfig(SimConfig base = {});

}  // namespace irgs
