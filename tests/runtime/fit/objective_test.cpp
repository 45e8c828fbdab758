// phi (5.1, 5.38) and err (6.1) on specimen D: the Appendix D model against its noise-free
// data is exact to the data's precision; against the noisy data err is the noise level.
#include "runtime/fit/objective.hpp"

#include "lang/frontend.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace rheo;

namespace {
runtime::Network specimen_d() {
  const auto program = lang::load_program(std::string(RHEO_EXAMPLES_DIR) + "/specimen_d.rheo");
  return runtime::Network::compile(*program.find_model("specimen_d"));
}
}  // namespace

TEST_CASE("err (6.1) of the Appendix D model of specimen D") {
  const auto net = specimen_d();
  const auto clean = runtime::read_harmonic_data(std::string(RHEO_DATA_DIR) + "/specimen_D_reference.csv");
  const auto noisy = runtime::read_harmonic_data(std::string(RHEO_DATA_DIR) + "/specimen_D_harmonic.csv");
  const auto model = runtime::simulate_at(net, clean, {});
  const auto exact = runtime::relative_residuals(clean, model);
  CHECK(runtime::thesis_err(exact) < 1e-6);
  // Noise of 1 % in stiffness and 0.15 deg in phase (about 1 % in d at ~15 deg): phi ~ 2e-4 n,
  // err ~ sqrt(2e-4 / n) ~ 1e-3 for n = 182.
  const auto r = runtime::relative_residuals(noisy, runtime::simulate_at(net, noisy, {}));
  const double err = runtime::thesis_err(r);
  MESSAGE("err(6.1) of Appendix D on specimen_D_harmonic.csv: " << err);
  CHECK(err > 5e-4);
  CHECK(err < 2e-3);
  CHECK(runtime::phi(r, 0.5, 0.5) == doctest::Approx(0.5 * runtime::phi(r, 1.0, 1.0)));
}
