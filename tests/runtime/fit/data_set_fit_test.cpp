// data_set_fit (runtime/fit/data_set_fit.hpp): a history's err and worst residual computed by
// hand with its declared or fitted force offset.
#include "runtime/fit/data_set_fit.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace data_set_fit_test {

using namespace rheo;

TEST_CASE("data_set_fit: a history's err and worst residual include its declared or fitted offset") {
  const runtime::Network spring = test::network_from("model s { spring e (k = 10 N/mm) }", "s");
  runtime::HistoryData h;
  h.drive.time = {0.0, 1.0, 2.0};
  h.drive.displacement = {0.0, 1.0, 2.0};  // network force 0, 10, 20 N
  h.force = {5.0, 14.0, 27.0};
  h.force_scale = 27.0;
  h.rows = {2, 3, 4};
  runtime::FitDataSet set{"h.csv", 1.0, h};
  set.force_offset = {.given = true, .free = false, .value = 5.0};
  const runtime::DataSetFit declared = runtime::data_set_fit(spring, set, {});
  CHECK(declared.force_offset.value == 5.0);
  CHECK_FALSE(declared.force_offset.free);
  // residuals 0, 1, -2 N
  CHECK(declared.err == doctest::Approx(std::sqrt((0.0 + 1.0 + 4.0) / 3.0) / 27.0).epsilon(1e-14).scale(0.0));
  CHECK(declared.worst == doctest::Approx(2.0 / 27.0).epsilon(1e-14).scale(0.0));

  set.force_offset.free = true;
  const runtime::DataSetFit fitted = runtime::data_set_fit(spring, set, {});
  CHECK(fitted.force_offset.value == doctest::Approx((5.0 + 4.0 + 7.0) / 3.0).epsilon(1e-14));
  const double c = fitted.force_offset.value;
  const double sum = (c - 5.0) * (c - 5.0) + (10.0 + c - 14.0) * (10.0 + c - 14.0) + (20.0 + c - 27.0) * (20.0 + c - 27.0);
  CHECK(fitted.err == doctest::Approx(std::sqrt(sum / 3.0) / 27.0).epsilon(1e-14).scale(0.0));
  CHECK(std::isnan(fitted.force_offset.standard_error));  // statistics come from the fit
}

}  // namespace data_set_fit_test
