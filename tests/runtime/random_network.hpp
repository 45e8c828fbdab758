// A seeded generator of valid .rheo models for differential tests of the two integrators
// (differential_test.cpp): every element kind, series and parallel blocks nested up to a given
// depth below the model's body, parameters log-uniform over ranges from realistic to adversarial.
//
// Portable: the numbers come from std::mt19937_64's bits, mapped to [0, 1) by this file (53
// bits / 2^53) and to ranges by std::pow, never through std::uniform_*_distribution, whose
// outputs differ between standard libraries; values are written with 6 significant digits, so
// a seed gives the same model text everywhere (up to the last bit of std::pow). Every number is
// drawn into a named variable first: the order in which a call's arguments are evaluated is
// unspecified, and differs between compilers.
//
// Valid for both integrators by construction, following the rules of docs/errors.md: a gap
// only in a series chain with a compliant member, never two sliders or gaps next to each other
// in a chain, no slider in the model's body (IDA refuses it), an inerter only as a damped
// internal mass (series { spring; parallel { inerter; dashpot } }, so that the network has a
// periodic state from rest), yeoh and poly_spring laws monotone (no snap-through in series), a
// bouc_wen inside a block only in a model without sliders, gaps or friction elements (IDA
// refuses it there).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

namespace rheo::test {

class RandomNetwork {
 public:
  // Blocks nest at most max_depth below the model's body.
  RandomNetwork(std::uint64_t seed, int max_depth) : bits_(seed), max_depth_(max_depth) {}

  // The largest natural frequency sqrt(k/b) [rad/s] of the damped internal masses of the last
  // model (0 without one): what a fixed step must resolve (differential_test.cpp).
  double fastest_mass() const { return fastest_mass_; }

  // The text of one model named `name` (no simulate block).
  std::string model(const std::string& name) {
    switches_ = unit() < 0.5;  // sliders, gaps, friction; else bouc_wen may nest
    springpot_ = false;
    fastest_mass_ = 0.0;
    budget_ = 4 + below(9);  // leaves beyond the mandatory ones of each block
    std::string body;
    const int n = 1 + below(3);
    for (int i = 0; i < n; ++i) body += (i == 0 || (unit() < 0.5 && spend()) ? series(1) : leaf(false)) + "\n";
    return fmt::format("model {} {{\n{}}}\n", name, body);
  }

 private:
  double unit() { return static_cast<double>(bits_() >> 11) * 0x1.0p-53; }  // [0, 1)
  int below(int n) { return static_cast<int>(unit() * n); }                 // 0 .. n-1
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
  double between(double lo, double hi) { return lo + (hi - lo) * unit(); }
  static std::string num(double v) { return fmt::format("{:.6g}", v); }
  // Takes one leaf from the model's budget: whether there was one (keeps models small enough
  // that both integrators finish each in well under a second).
  bool spend() { return budget_-- > 0; }

  // A chain of 2-3 members: a compliant leaf, then a nested parallel block, a compliant leaf,
  // a slider or gap (never two in a row), or a damped internal mass (two blocks deeper).
  std::string series(int depth) {
    std::string s = "series {\n" + leaf(true) + "\n";
    const int more = unit() < 0.3 && spend() ? 2 : 1;
    bool after_switch = false;
    for (int i = 0; i < more; ++i) {
      const double r = unit();
      if (depth < max_depth_ && r < 0.5 && spend()) {
        s += parallel(depth + 1);
        after_switch = false;
      } else if (switches_ && !after_switch && r < 0.7) {
        s += unit() < 0.5 ? slider() : gap();
        after_switch = true;
      } else if (depth + 2 <= max_depth_ && r < 0.8) {
        s += damped_mass();
        after_switch = false;
      } else {
        s += leaf(true);
        after_switch = false;
      }
      s += "\n";
    }
    if (after_switch) s += leaf(true) + "\n";  // a switch ends no chain next to a parent's switch
    return s + "}";
  }

  // 2-3 branches: leaves (a slider among them) or nested chains; the first a compliant leaf.
  std::string parallel(int depth) {
    std::string s = "parallel {\n" + leaf(true) + "\n";
    const int more = unit() < 0.3 && spend() ? 2 : 1;
    for (int i = 0; i < more; ++i) {
      if (depth < max_depth_ && unit() < 0.6 && spend()) s += series(depth + 1);
      else if (switches_ && unit() < 0.25) s += slider();
      else s += leaf(true);
      s += "\n";
    }
    return s + "}";
  }

  std::string damped_mass() {
    const double k = log_uniform(10, 1e4), b = log_uniform(0.01, 5), c = log_uniform(0.05, 5);
    fastest_mass_ = std::max(fastest_mass_, std::sqrt(k * 1e3 / b));  // N/mm -> N/m
    return fmt::format("series {{ spring (k = {} N/mm) parallel {{ inerter (b = {} kg) dashpot (c = {} N*s/mm) }} }}", num(k), num(b), num(c));
  }

  std::string slider() {
    if (unit() < 0.3) {
      const double pos = log_uniform(0.5, 50), neg = log_uniform(0.5, 50);
      return fmt::format("slider (fy_pos = {} N, fy_neg = {} N)", num(pos), num(neg));
    }
    return fmt::format("slider (fy = {} N)", num(log_uniform(0.5, 50)));
  }

  std::string gap() {
    const double width = log_uniform(0.005, 0.3);
    return fmt::format("gap (width = {} mm, center = {} mm)", num(width), num(between(-0.4, 0.4) * width));
  }

  // A leaf with a law of its own, never a slider, gap or inerter (nested: inside a block).
  std::string leaf(bool nested) {
    for (;;) {
      switch (below(10)) {
        case 0: return fmt::format("spring (k = {} N/mm)", num(log_uniform(1, 1e5)));
        case 1: {
          const double d10 = log_uniform(1, 1e3), d30 = unit() < 0.3 ? 0.0 : log_uniform(0.01, 100);
          const double d20 = between(-0.9, 0.9) * std::sqrt(5.0 / 3.0 * d10 * d30);
          return fmt::format("yeoh (D10 = {} N/mm, D20 = {} N/mm^3, D30 = {} N/mm^5)", num(d10), num(d20), num(d30));
        }
        case 2: {
          const double k1 = log_uniform(1, 1e4), k3 = unit() < 0.3 ? 0.0 : log_uniform(0.1, 1e4);
          const double k2 = between(-0.9, 0.9) * std::sqrt(3.0 * k1 * k3);
          return fmt::format("poly_spring (k1 = {} N/mm, k2 = {} N/mm^2, k3 = {} N/mm^3)", num(k1), num(k2), num(k3));
        }
        case 3: return fmt::format("dashpot (c = {} N*s/mm)", num(log_uniform(0.01, 10)));
        case 4: return fmt::format("quadratic_dashpot (cq = {} N*s^2/mm^2)", num(log_uniform(1e-4, 0.1)));
        case 5: {
          const double k = log_uniform(1, 1e4), tau = log_uniform(0.5e-3, 0.3);  // s: slower modes need hundreds of cycles
          if (unit() < 0.5) return fmt::format("maxwell (k = {} N/mm, tau = {} ms)", num(k), num(1e3 * tau));
          return fmt::format("maxwell (k = {} N/mm, c = {} N*s/mm)", num(k), num(k * tau));
        }
        case 6: {
          if (!switches_) continue;
          const bool force = unit() < 0.5;
          const double k = log_uniform(10, 1e4), cap = force ? log_uniform(0.5, 50) : log_uniform(1, 100);
          return force ? fmt::format("friction (k = {} N/mm, fy = {} N)", num(k), num(cap))
                       : fmt::format("friction (k = {} N/mm, uy = {} um)", num(k), num(cap));
        }
        case 7:
          if (springpot_) continue;
          springpot_ = true;
          {
            const double k = log_uniform(1, 1e3), alpha = between(0.1, 0.9), tau = log_uniform(1, 100);
            return fmt::format("springpot (k = {} N/mm, alpha = {}, tau = {} ms, f_low = 1 Hz, f_high = 100 Hz)", num(k), num(alpha), num(tau));
          }
        default:  // 8 and 9: bouc_wen (twice as often: its laws and placements vary most)
          if (nested && switches_) continue;
          {
            const bool force = unit() < 0.5;
            const double k = log_uniform(10, 1e3), n = between(1, 4), cap = force ? log_uniform(0.5, 20) : log_uniform(10, 200);
            return force ? fmt::format("bouc_wen (k = {} N/mm, n = {}, fy = {} N)", num(k), num(n), num(cap))
                         : fmt::format("bouc_wen (k = {} N/mm, n = {}, uy = {} um)", num(k), num(n), num(cap));
          }
      }
    }
  }

  std::mt19937_64 bits_;
  int max_depth_;
  bool switches_ = false;
  double fastest_mass_ = 0.0;
  bool springpot_ = false;  // one springpot per model: each is a chain of 22 Maxwell modes (44 unknowns of IDA's dense Newton matrix)
  int budget_ = 0;
};

}  // namespace rheo::test
