// Candidates as models (candidate_model.hpp): whether a refitted candidate can be written.
#include "runtime/diagnosis/candidate_model.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

using namespace rheo;

TEST_CASE("a refitted gap whose centre left its play cannot be written, so its candidate cannot earn") {
  const runtime::Network network = test::network_from(
      "model g { spring s (k = 10 N/mm)  series b { gap p (width = 2 mm in [0.1, 10], center = 0.5 mm in [-5, 5])  spring k (k = 300 N/mm) } }", "g");
  CHECK(runtime::diagnosis::gap_outside_play(network).empty());
  std::vector<double> values = network.parameters();
  values[static_cast<std::size_t>(test::parameter_index(network, "b.p.center"))] = 1.5;  // a fit may go there: the gap then acts as a stop
  const std::string why = runtime::diagnosis::gap_outside_play(network.with_parameters(values));
  CHECK(why.find("beyond half its width") != std::string::npos);
  values[static_cast<std::size_t>(test::parameter_index(network, "b.p.center"))] = -1.0;  // on the edge: still in the play
  CHECK(runtime::diagnosis::gap_outside_play(network.with_parameters(values)).empty());
}
