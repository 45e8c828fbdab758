// Seeded random numbers for test noise that are the same with every standard library.
//
// std::mt19937's outputs are specified bit for bit ([rand.predef]: the 10000th output of a
// default-constructed one is 4123659995), but std::uniform_real_distribution,
// std::normal_distribution and std::generate_canonical are not: libstdc++, libc++ and MSVC give
// different numbers for the same seed, so a test calibrated on one library's noise could pass
// or fail on another. PortableRandom maps the engine's outputs itself:
//   unit():    two outputs a, b -> (a + b 2^32) / 2^64 in double arithmetic, in [0, 1)
//              (the largest double below 1 where the sum rounds up to 2^64);
//   uniform(lo, hi) = lo + (hi - lo) unit() as (hi - lo) unit() + lo;
//   normal():  Marsaglia's polar method: x = 2 unit() - 1, y = 2 unit() - 1 until
//              0 < r2 = x^2 + y^2 <= 1, then y m and (on the next call) x m with
//              m = sqrt(-2 ln r2 / r2), a pair of independent N(0, 1) numbers.
// These are the formulas libstdc++ uses, so the tests' noise is what it was when they were
// calibrated with std::normal_distribution under GCC; only std::log and std::sqrt come from the
// platform (sqrt is correctly rounded; a libm's log may differ in the last bit).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace rheo::test {

class PortableRandom {
 public:
  explicit PortableRandom(std::uint32_t seed) : bits_(seed) {}

  double unit() {
    const double low = static_cast<double>(bits_());
    const double high = static_cast<double>(bits_());
    const double u = (low + high * 4294967296.0) / 18446744073709551616.0;
    return u < 1.0 ? u : std::nextafter(1.0, 0.0);
  }

  double uniform(double lo, double hi) { return unit() * (hi - lo) + lo; }

  double normal() {
    if (saved_available_) {
      saved_available_ = false;
      return saved_;
    }
    double x = 0.0, y = 0.0, r2 = 0.0;
    do {
      x = 2.0 * unit() - 1.0;
      y = 2.0 * unit() - 1.0;
      r2 = x * x + y * y;
    } while (r2 > 1.0 || r2 == 0.0);
    const double m = std::sqrt(-2.0 * std::log(r2) / r2);
    saved_ = x * m;
    saved_available_ = true;
    return y * m;
  }

 private:
  std::mt19937 bits_;
  double saved_ = 0.0;
  bool saved_available_ = false;
};

}  // namespace rheo::test
