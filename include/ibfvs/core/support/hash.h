#pragma once
// Deterministic random numbers: the noise's phases and the generated
// shapes' bumps, the same on every platform.

#include <cstdint>

namespace ibfvs {

/// Uniform numbers in [0, 1) from (seed, index): the same on every
/// platform, unlike std::uniform_real_distribution.
inline float hash_uniform(std::uint32_t seed, std::uint64_t index) {
  // splitmix64 of (seed, index): well mixed, cheap, portable.
  std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32) ^ (index + 0x9E3779B97F4A7C15ull);
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<float>(z >> 40) / static_cast<float>(1ull << 24);
}

}  // namespace ibfvs
