#pragma once
// Seeded random numbers. Every random component takes an Rng& so that runs are reproducible from a
// seed.
#include <cstdint>
#include <random>

namespace adaptive_perception::math {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) : engine_(seed) {}

  /// Uniform on [lo, hi).
  double uniform(double lo = 0.0, double hi = 1.0) {
    return std::uniform_real_distribution<double>(lo, hi)(engine_);
  }
  /// Normal with the given mean and standard deviation.
  double gaussian(double mean = 0.0, double stddev = 1.0) {
    return mean + stddev * normal_(engine_);
  }
  /// Uniform integer in [lo, hi].
  int uniformInt(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }
  /// True with probability p.
  bool bernoulli(double p) { return uniform() < p; }
  /// A new seed drawn from this stream: for giving sub-components independent reproducible streams.
  std::uint64_t split() { return engine_(); }

  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

/// A seed for item b of stream a (a frame's seed and a particle's index, say): a 64-bit mix of
/// both, so that every item draws from its own stream whatever order the items run in.
inline std::uint64_t mixSeeds(std::uint64_t a, std::uint64_t b) {
  std::uint64_t x = a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull + (a << 6) + (a >> 2));
  x ^= x >> 31;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 29;
  return x;
}

}  // namespace adaptive_perception::math
