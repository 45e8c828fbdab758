// force_scales: the free parameters the force is affine in, found from the compiled network
// whatever the parameters' expressions (the laws in force_scales.hpp).
#include "runtime/fit/force_scales.hpp"

#include "runtime/fit/fit.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

namespace force_scales_test {

using namespace rheo;

namespace {

// The paths of the free parameters force_scales names.
std::vector<std::string> scale_paths(const std::string& source) {
  const auto network = test::network_from(source, "m");
  const std::vector<int> free = runtime::bounded_parameters(network);
  std::vector<std::string> paths;
  for (int j : runtime::force_scales(network, free))
    paths.push_back(network.model().parameters[static_cast<std::size_t>(free[static_cast<std::size_t>(j)])].path);
  return paths;
}

}  // namespace

TEST_CASE("root springs, dashpots, sliders, yeoh constants and Maxwell / friction stiffnesses at fixed tau / uy are scales") {
  CHECK(scale_paths("model m { spring s (k = 10 in [1, 100]) dashpot d (c = 1 in [0.1, 10]) slider l (fy = 2 in [1, 5]) "
                    "yeoh y (D10 = 5 in [1, 50], D20 = 0 in [-1, 1], D30 = 0 in [-1, 1]) "
                    "maxwell x (k = 5 in [1, 50], tau = 2 ms in [0.1 ms, 100 ms]) friction f (k = 20 in [1, 100], uy = 0.1 mm in [0.01 mm, 1 mm]) }") ==
        std::vector<std::string>{"s.k", "d.c", "l.fy", "y.D10", "y.D20", "y.D30", "x.k", "f.k"});
}

TEST_CASE("a shape parameter, or a stiffness that moves a shape, is not a scale") {
  // Maxwell written with c: changing k at fixed c changes tau; friction written with fy: k changes uy.
  CHECK(scale_paths("model m { maxwell x (k = 5 in [1, 50], c = 0.01 in [0.001, 1]) friction f (k = 20 in [1, 100], fy = 2 in [1, 5]) }").empty());
  // One parameter shared by two root springs is still a scale (the sum is affine); one that also
  // sets a nested element is not.
  CHECK(scale_paths("model m { param k0 = 10 N/mm in [1, 100]\n spring a (k = k0) spring b (k = 2 * k0) }") == std::vector<std::string>{"k0"});
  CHECK(scale_paths("model m { param k0 = 10 N/mm in [1, 100]\n spring a (k = k0) series { spring b (k = k0) dashpot d (c = 1) } }").empty());
  // Elements inside a series chain are never root scales.
  CHECK(scale_paths("model m { spring a (k = 1) series { spring b (k = 10 in [1, 100]) slider f (fy = 1 in [0.5, 2]) } }").empty());
}

TEST_CASE("a springpot's k scales its Maxwell modes, its alpha does not") {
  CHECK(scale_paths("model m { spring s (k = 1) springpot p (k = 10 in [1, 100], alpha = 0.3 in [0.1, 0.9], tau = 1 s, f_low = 0.1 Hz, "
                    "f_high = 100 Hz) }") == std::vector<std::string>{"p.k"});
}

}  // namespace force_scales_test
