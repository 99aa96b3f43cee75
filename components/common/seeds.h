#pragma once

// Seeded random streams. Every seeded stream of the project (a study's runs, the frames of
// an error measurement) is derived from its seed through SplitMix64, so that a run or a
// frame has its own generator whatever thread computes it, and neighbouring indices give
// unrelated streams.

#include <cstdint>

namespace stickrep {

// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators",
// 2014): the output of the generator from state `x`, which then moves on by the gamma.
inline constexpr std::uint64_t kSplitMixGamma = 0x9e3779b97f4a7c15ull;

constexpr std::uint64_t SplitMix64(std::uint64_t x) {
  x += kSplitMixGamma;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The seed of stream `index` of a source seeded with `seed`: SplitMix64's output number
// `index` from state `seed`.
constexpr std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t index) {
  return SplitMix64(seed + kSplitMixGamma * index);
}

}  // namespace stickrep
