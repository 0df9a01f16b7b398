#pragma once
// Recursive zonal equal-area (EQ) partition (Leopardi 2006), applied to the upper hemisphere
// (pole +y) so that together with its mirror image it partitions the whole sphere into 2N
// regions that come in antipodal pairs. Each pair is one LDM: the view along a region's
// centre direction answers queries in both directions +-d (thesis §3.3.1, §4.3.2), so the
// thesis's "partition the sphere, keep one hemisphere, cull parallel directions" is exact
// here and every LDM stands for the same solid angle 2*pi/N of the hemisphere around any
// surface normal.
//
// Construction, as in Leopardi's EQ algorithm for S^2:
//   region area A = 2*pi / N; a polar cap of area A (cos theta_c = 1 - 1/N);
//   the band theta_c..pi/2 split into round((pi/2 - theta_c) / sqrt(A)) collars of equal
//   height, the ideal region count of each collar rounded with the discrepancy carried to the
//   next so that the counts sum to N - 1; collar boundaries then moved so that each collar's
//   area is exactly its count times A; centres at mid-colatitude, longitudes
//   (j - 1/2) * 2*pi / m + offset, with Leopardi's rotation offset between collars.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ldm {

struct SphereZone {
  double cos_top = 1.0;     // cos of the zone's upper (smaller) colatitude
  double cos_bottom = 0.0;  // cos of its lower colatitude
  uint32_t regions = 1;     // regions in the zone (1 for the polar cap)
  double offset_turns = 0;  // longitude of the first region's start, in turns
  uint32_t first_region = 0;
};

class HemispherePartition {
 public:
  explicit HemispherePartition(uint32_t regions);

  uint32_t size() const { return count_; }
  const std::vector<SphereZone>& zones() const { return zones_; }
  // Centre direction of each region: unit vectors with y > 0.
  const std::vector<glm::dvec3>& centres() const { return centres_; }
  // Solid angle of region i (steradians), from its zone's bounds.
  double region_area(uint32_t region) const;
  // The region containing direction d (any unit vector; d and -d map to the same region).
  uint32_t region_of(glm::dvec3 d) const;

 private:
  uint32_t count_;
  std::vector<SphereZone> zones_;
  std::vector<glm::dvec3> centres_;
};

}  // namespace ldm
