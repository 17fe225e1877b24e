#pragma once
// The study's random numbers, the same on every platform: std::mt19937_64's raw output (its
// sequence is fixed by the standard) turned into uniforms, normals and counts here, not by the
// standard library's distributions, whose algorithms differ between implementations.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace rtmot::study {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  /// In [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double normal() {
    // Box-Muller; 1 - u keeps the logarithm finite.
    constexpr double kPi = 3.14159265358979323846;
    const double u = 1.0 - uniform();
    const double v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * v);
  }
  bool chance(double p) { return uniform() < p; }
  int poisson(double mean) {
    // Knuth's product of uniforms: exact, and fast for the small means used here.
    const double limit = std::exp(-mean);
    int count = 0;
    for (double product = uniform(); product > limit; product *= uniform()) ++count;
    return count;
  }
  int index(std::size_t size) {
    return static_cast<int>(std::min(static_cast<double>(size) - 1.0,
                                     std::floor(uniform() * static_cast<double>(size))));
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace rtmot::study
