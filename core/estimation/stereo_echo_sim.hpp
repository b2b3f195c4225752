#pragma once
// Simulated echoes of the stereo ultrasonic sensor (paper 000) in a WorldMap: the first echo
// (shortest acoustic path) among
//   * specular wall reflections (mirror image; both reflection points, for R1 and R2, must lie on
//     the wall segment and the sensor must be in front of the face),
//   * concave corners (retro-reflection, image 2C - T; the sensor must lie inside the corner's
//     opening between its two walls),
//   * convex edges (diffraction, |E - T| + |E - R_i|),
// each only inside the transducer's beam and with an unobstructed path, then seeded noise,
// random dropouts, the minimum range and the max-TOF gate. Deterministic for a given SimRandom.

#include <cstddef>
#include <string>
#include <vector>

#include "core/estimation/stereo_sonar.hpp"
#include "core/sim/random.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct StereoEchoNoise {
  double path_stddev_m = 0.002;      // per receiver path, constant part
  double path_stddev_per_m = 0.001;  // extra stddev per metre of path
  double dropout_probability = 0.0;  // echo missing at random
  // Transducer beam: reflectors (wall normals, corner/edge directions) farther off the boresight
  // give no echo. [A] not in paper 000; Murata 40 kHz parts have a beam of roughly +/-30 deg.
  double beam_half_angle_rad = degToRad(30.0);
  double min_range_m = 0.2;  // [000] detection range 0.2 - 5 m (distance d from T)
};

enum class ReflectorKind { kWall, kCorner, kEdge };

enum class EchoStatus {
  kEcho,          // r1, r2 hold a measurement
  kNoReflector,   // nothing in the beam and in range
  kDropout,       // a reflector was there but the echo was lost (random)
  kBeyondMaxTof,  // the echo arrived after the max-TOF window
};

struct SimulatedEcho {
  EchoStatus status = EchoStatus::kNoReflector;
  EchoPaths paths;       // measured (noisy) path lengths; valid when status == kEcho
  EchoPaths true_paths;  // noise-free path lengths of the chosen reflector (not for kNoReflector)
  ReflectorKind kind = ReflectorKind::kWall;
  // Index into StereoEchoSimulator::segments() for walls, into WorldMap::features otherwise.
  std::size_t reflector_index = 0;
  std::string reflector_id;  // wall or feature id, for diagnostics and display
};

// Precomputes the reflectors of a map; then echo() is cheap (linear in the map size).
class StereoEchoSimulator {
 public:
  // Throws std::invalid_argument for invalid params or noise (negative stddevs, probability
  // outside [0, 1], non-positive beam).
  StereoEchoSimulator(const WorldMap& map, StereoSonarParams params, StereoEchoNoise noise);

  // Noise-free first echo (status kEcho, kNoReflector or kBeyondMaxTof; never kDropout).
  SimulatedEcho idealEcho(const Pose2& sensor) const;
  // idealEcho plus dropouts and Gaussian path noise drawn from `rng`. Throws
  // std::invalid_argument for a non-finite sensor pose.
  SimulatedEcho echo(const Pose2& sensor, SimRandom& rng) const;

  struct ReflectingSegment {
    Segment segment;
    std::string wall_id;
  };
  const std::vector<ReflectingSegment>& segments() const { return segments_; }
  const StereoSonarParams& params() const { return params_; }
  const StereoEchoNoise& noise() const { return noise_; }

 private:
  struct Feature {
    PointFeatureKind kind;
    Vec2 position;
    std::string id;
    // Corner opening: unit directions of the walls leaving the corner (concave corners only).
    std::vector<Vec2> arms;
  };

  bool pathClear(const Vec2& from, const Vec2& to, std::size_t skip_segment,
                 const Vec2* skip_point) const;

  std::vector<ReflectingSegment> segments_;
  std::vector<Feature> features_;
  StereoSonarParams params_;
  StereoEchoNoise noise_;
};

}  // namespace irgs
