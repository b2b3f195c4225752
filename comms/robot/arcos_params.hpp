#pragma once
// The ARCOS conversion factors of a Pioneer-class robot, read from the `arcos` object of its
// robot profile (resources/robots/pioneer_*.json; the profile loader keeps unknown keys in
// RobotProfile::extra). Names and meanings are ARIA's (params/*.p, "Conversion factors"):
//
//   "arcos": { "subclass": "p3dx-sh",          SYNC2 subclass the virtual Pioneer reports
//              "angle_conv_factor": 0.001534,  rad per heading unit (2 pi / 4096)
//              "dist_conv_factor": 1.0,        mm per position unit
//              "vel_conv_factor": 1.0,         mm/s per wheel velocity unit
//              "range_conv_factor": 1.0,       mm per sonar range unit
//              "diff_conv_factor": 0.0056,     omega [rad/s] = (vR - vL) / 2 * this (v in mm/s)
//              "vel2_divisor": 20,             mm/s per VEL2 wheel unit
//              "sip_cycle_ms": 100,            SIP period of the virtual Pioneer
//              "watchdog_s": 2.0 }             virtual Pioneer's PULSE watchdog
//
// Every key is optional (the P3-DX values are the defaults); a present key with a bad value is
// reported and the default kept.

#include <string>
#include <vector>

#include "core/robot/robot_profile.hpp"

namespace irgs::comms {

struct ArcosParams {
  std::string subclass = "p3dx-sh";
  double angle_conv_rad = 0.001534;
  double dist_conv_mm = 1.0;
  double vel_conv_mmps = 1.0;
  double range_conv_mm = 1.0;
  double diff_conv = 0.0056;
  int vel2_divisor = 20;
  double sip_cycle_s = 0.1;
  double watchdog_s = 2.0;
};

struct ArcosParamsResult {
  ArcosParams params;
  std::vector<std::string> warnings;  // one line per ignored key value
  bool found = false;                 // the profile has an `arcos` object
};

ArcosParamsResult arcosParamsFromProfile(const RobotProfile& profile);

}  // namespace irgs::comms
