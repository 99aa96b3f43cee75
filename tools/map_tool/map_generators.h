#pragma once

// Seeded generators for the five domains of §6.8. The real floor plans are not published, so
// each generator builds a plausible floor from what the text reports (census tables, scale,
// regularity, reference landmarks); maps/README.md says what each one takes from the text.
// The output is committed under maps/; regenerating with the seed in the file reproduces it
// byte for byte (the generators use their own integer sampling, not std:: distributions,
// whose results differ between standard libraries).

#include <cstdint>
#include <string>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::map {

// The domains and the seed their committed map was generated with.
struct DomainInfo {
  std::string name;
  std::uint64_t seed;
  std::string summary;
};
const std::vector<DomainInfo>& Domains();

// Generates domain `name` with `seed`; throws std::invalid_argument for an unknown name.
Map GenerateDomain(const std::string& name, std::uint64_t seed);

// The Engineering Building's third floor (§6.2, §6.8): 10 rings (3 wings, each an outer
// corridor wall around 2-3 blocks of rooms), built so that Tables 6.1-6.3, 6.5, 6.8 and 6.9
// hold exactly and the mean edge metric is 67.64 in.
Map GenerateEngineeringBuilding(std::uint64_t seed);
// Wells Hall, 7th floor: a corridor loop around a core, about 15 % of the Engineering
// Building, highly regular office modules, one reference landmark in the major ring.
// `modified` adds one artificial ribbon at the edge farthest from that landmark (§6.8).
Map GenerateWellsHall(std::uint64_t seed, bool modified);
// A regular polygon of 46 sides of 100 in with one unique feature (§6.8).
Map GenerateRegularPolygon(std::uint64_t seed);
// 1/10 mile of street frontage around a city block (§6.8).
Map GenerateStorefront(std::uint64_t seed);

}  // namespace stickrep::map
