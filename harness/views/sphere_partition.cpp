#include "harness/views/sphere_partition.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "harness/util/error.h"

namespace ldm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Leopardi's circle_offset for dim 2: the rotation between a collar of n_top regions and the
// next of n_bottom regions that keeps region centres apart, in turns.
double circle_offset(uint32_t n_top, uint32_t n_bottom) {
  const double g = double(std::gcd(n_top, n_bottom));
  return (1.0 / n_bottom - 1.0 / n_top) / 2.0 + g / (2.0 * double(n_top) * double(n_bottom));
}

glm::dvec3 direction(double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return {sin_theta * std::cos(phi), cos_theta, sin_theta * std::sin(phi)};
}

}  // namespace

HemispherePartition::HemispherePartition(uint32_t regions) : count_(regions) {
  if (regions == 0) throw UserError("the number of LDM directions N must be at least 1");
  const double n = double(regions);
  const double area = 2.0 * kPi / n;

  SphereZone cap;
  cap.cos_top = 1.0;
  cap.cos_bottom = regions == 1 ? 0.0 : 1.0 - 1.0 / n;
  cap.regions = 1;
  zones_.push_back(cap);

  if (regions > 1) {
    const double theta_cap = std::acos(cap.cos_bottom);
    const double band = kPi / 2.0 - theta_cap;
    const uint32_t collars =
        std::max<uint32_t>(1, uint32_t(std::lround(band / std::sqrt(area))));
    const double fit = band / double(collars);
    // Ideal (fractional) region counts, rounded with the discrepancy carried forward.
    std::vector<uint32_t> counts(collars);
    double discrepancy = 0.0;
    uint32_t assigned = 0;
    for (uint32_t i = 0; i < collars; ++i) {
      const double top = theta_cap + fit * double(i);
      const double bottom = theta_cap + fit * double(i + 1);
      const double ideal = n * (std::cos(top) - std::cos(bottom));  // area / A
      long rounded = std::lround(ideal + discrepancy);
      if (i + 1 == collars) rounded = long(regions - 1 - assigned);  // exact total
      rounded = std::max<long>(1, rounded);
      counts[i] = uint32_t(rounded);
      discrepancy += ideal - double(rounded);
      assigned += counts[i];
    }
    // Collar boundaries chosen so that every collar's area is exactly count * A.
    uint32_t cumulative = 1;
    double offset = 0.0;
    uint32_t previous_count = 1;
    for (uint32_t i = 0; i < collars; ++i) {
      SphereZone zone;
      zone.cos_top = 1.0 - double(cumulative) / n;
      cumulative += counts[i];
      zone.cos_bottom = i + 1 == collars ? 0.0 : 1.0 - double(cumulative) / n;
      zone.regions = counts[i];
      if (i > 0) offset += circle_offset(previous_count, counts[i]);
      zone.offset_turns = offset - std::floor(offset);
      previous_count = counts[i];
      zones_.push_back(zone);
    }
  }

  uint32_t next = 0;
  for (auto& zone : zones_) {
    zone.first_region = next;
    next += zone.regions;
    if (zone.cos_top == 1.0) {  // the polar cap: centred on the pole
      centres_.push_back({0.0, 1.0, 0.0});
      continue;
    }
    const double mid = 0.5 * (std::acos(zone.cos_top) + std::acos(zone.cos_bottom));
    for (uint32_t j = 0; j < zone.regions; ++j) {
      const double phi = 2.0 * kPi * ((double(j) + 0.5) / double(zone.regions) + zone.offset_turns);
      centres_.push_back(direction(std::cos(mid), phi));
    }
  }
}

double HemispherePartition::region_area(uint32_t region) const {
  for (const auto& zone : zones_)
    if (region >= zone.first_region && region < zone.first_region + zone.regions)
      return 2.0 * kPi * (zone.cos_top - zone.cos_bottom) / double(zone.regions);
  throw UserError("region index " + std::to_string(region) + " out of range");
}

uint32_t HemispherePartition::region_of(glm::dvec3 d) const {
  d = glm::normalize(d);
  if (d.y < 0.0) d = -d;
  const double cos_theta = std::min(1.0, d.y);
  for (const auto& zone : zones_) {
    const bool last = &zone == &zones_.back();
    if (cos_theta > zone.cos_bottom || last) {
      if (zone.regions == 1 && zone.cos_top == 1.0) return zone.first_region;
      double turns = std::atan2(d.z, d.x) / (2.0 * kPi) - zone.offset_turns;
      turns -= std::floor(turns);
      uint32_t j = uint32_t(turns * double(zone.regions));
      return zone.first_region + std::min(j, zone.regions - 1);
    }
  }
  return zones_.back().first_region;
}

}  // namespace ldm
