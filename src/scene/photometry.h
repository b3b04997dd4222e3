// A luminaire's measured distribution of light (an IES LM-63 file's candela table, type C): what a
// point or spot light carrying an `.ies` file sends each way.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rad {

/// How the file's horizontal (C) angles cover the circle; the rest follows by symmetry.
enum class CSymmetry : uint8_t {
  Rotational,   // one C angle: the same in every C plane
  Quadrant,     // C 0..90: symmetric about the C0-C180 and C90-C270 planes
  Bilateral,    // C 0..180: symmetric about the C0-C180 plane
  Bilateral90,  // C 90..270: symmetric about the C90-C270 plane
  Full,         // C 0..360
};

const char* to_string(CSymmetry s);

/// Type C photometry: vertical angles gamma from the nadir (0, straight down the luminaire's
/// axis) to the zenith (180); horizontal angles C counterclockwise, seen from above, from the
/// C0 half-plane (the luminaire's reference direction).
struct Photometry {
  std::string path;               // the file it was read from (for messages)
  std::vector<float> vertical;    // gamma, degrees, strictly increasing, within [0, 180]
  std::vector<float> horizontal;  // C, degrees, strictly increasing, as `symmetry` says
  /// candela[h * vertical.size() + v], the file's candela multiplier, ballast factor and
  /// ballast-lamp (future use) factor applied.
  std::vector<float> candela;
  CSymmetry symmetry = CSymmetry::Rotational;
  int lamps = 1;
  float lumens_per_lamp = -1.0f;  // -1: absolute photometry (no rated lamp lumens)
  float multiplier = 1.0f;        // as in the file (already in `candela`)
  float ballast_factor = 1.0f, ballast_lamp_factor = 1.0f;  // as in the file (already in it)
  float input_watts = 0.0f;
  float max_candela = 0.0f;

  /// The rated lumens of the luminaire's lamps (lamps x lumens per lamp), or a negative value
  /// for absolute photometry.
  float lumens() const { return lumens_per_lamp < 0.0f ? -1.0f : float(lamps) * lumens_per_lamp; }

  /// Candela toward vertical angle `gamma` and horizontal angle `c` (degrees; c any value, taken
  /// modulo 360 and folded by the symmetry), bilinear between the table's angles, 0 outside its
  /// vertical range.
  float candela_at(float gamma, float c) const;

  /// The luminous flux of the table (lumens): its candela integrated over the sphere.
  double flux() const;
};

}  // namespace rad
