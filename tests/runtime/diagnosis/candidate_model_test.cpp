// Candidates as models (candidate_model.hpp): a refitted gap written as a file can state it.
#include "runtime/diagnosis/candidate_model.hpp"

#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

using namespace rheo;

TEST_CASE("a refitted gap centre beyond half the width is written at the edge of the play, with the same predictions") {
  const runtime::Network network = test::network_from(
      "model g { spring s (k = 10 N/mm)  series b { gap p (width = 2 mm in [0.1, 10], center = 0.5 mm in [-5, 5])  friction f (k = 300 N/mm, fy = 200 N) } }",
      "g");
  const int center = test::parameter_index(network, "b.p.center");
  std::vector<double> values = network.parameters();
  values[static_cast<std::size_t>(center)] = 1.7;  // where a fit may go: every solver then acts as if it were at +1 mm
  const runtime::Network beyond = network.with_parameters(values);
  const runtime::Network written = runtime::diagnosis::with_gaps_in_play(beyond);
  CHECK(written.parameter(center) == 1.0);
  CHECK(runtime::diagnosis::with_gaps_in_play(network).parameter(center) == 0.5);  // within the play: kept
  const runtime::Drive drive = runtime::quasistatic_sine({3.0, 1.5}, 1.0, 2, 200);
  const auto a = runtime::run_history(beyond, drive, false, runtime::SolverChoice::fixed).force;
  const auto b = runtime::run_history(written, drive, false, runtime::SolverChoice::fixed).force;
  REQUIRE(a.size() == b.size());
  double largest = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) largest = std::max(largest, std::abs(a[k])), difference = std::max(difference, std::abs(a[k] - b[k]));
  CHECK(largest > 100.0);
  CHECK(difference <= 1e-9 * largest);
  // An edge outside the bounds the centre was fitted in: it stays where it is.
  const runtime::Network bounded = test::network_from(
      "model g { series b { gap p (width = 2 mm in [0.1, 10], center = 0.5 mm in [0.2, 5])  spring k (k = 300 N/mm) } }", "g");
  std::vector<double> negative = bounded.parameters();
  negative[static_cast<std::size_t>(test::parameter_index(bounded, "b.p.width"))] = 0.2;
  CHECK(runtime::diagnosis::with_gaps_in_play(bounded.with_parameters(negative)).parameter(test::parameter_index(bounded, "b.p.center")) == 0.5);
}
