// The error classes (lang/errors.hpp): each user error has its documented exit code and is no
// std::logic_error; a broken precondition is a std::logic_error, which the CLI reports as an
// internal error (exit 1), never as a usage error.
#include "runtime/core/errors.hpp"

#include "lang/diagnostics.hpp"
#include "lang/frontend.hpp"
#include "runtime/fit/fit.hpp"
#include "runtime/fit/objective.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>
#include <type_traits>

namespace errors_test {

using namespace rheo;

namespace {

// The exit code main() returns for whatever BODY throws (0 when it throws nothing).
template <class Body>
int exit_code_for(Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    return exit_code_of(e);
  }
  return exit_code::ok;
}

template <class Error>
void check_user_error(const Error& e, int code) {
  CAPTURE(e.what());
  CHECK(exit_code_of(e) == code);
  CHECK(e.exit_code() == code);
  CHECK(dynamic_cast<const std::logic_error*>(&e) == nullptr);  // so never std::invalid_argument either
}

}  // namespace

TEST_CASE("each user error has its documented exit code and is not a std::logic_error") {
  static_assert(std::is_same_v<runtime::UsageError, UsageError> && std::is_same_v<runtime::ModelError, ModelError> &&
                std::is_same_v<runtime::DataError, DataError> && std::is_same_v<runtime::NumericalError, NumericalError>);
  check_user_error(UsageError("u"), 2);
  check_user_error(ModelError("m"), 3);
  check_user_error(DataError("d"), 4);
  check_user_error(NumericalError("n"), 5);
  lang::SourceSet sources;
  sources.add("a.rheo", "model a {}\n");
  check_user_error(lang::CompileError({{{"a.rheo", 1, 1}, "bad"}}, sources), 3);
  check_user_error(lang::UnreadableSource("a.rheo: error: cannot read it"), 4);
  CHECK(exit_code_for([] { (void)lang::load_program("/nonexistent/file.rheo"); }) == exit_code::data);
  CHECK(exit_code_for([] { (void)lang::compile_source("a.rheo", "model a { spring s (k = 5 mm) }"); }) == exit_code::model);
}

TEST_CASE("standard exceptions are internal errors (exit 1), not usage errors") {
  CHECK(exit_code_of(std::logic_error("x")) == exit_code::internal);
  CHECK(exit_code_of(std::invalid_argument("x")) == exit_code::internal);
  CHECK(exit_code_of(std::runtime_error("x")) == exit_code::internal);
  CHECK(exit_code_of(std::out_of_range("x")) == exit_code::internal);
}

TEST_CASE("a broken precondition (mismatched sizes) is a std::logic_error and exits 1, not a usage error") {
  const auto net = test::network_from("model z { spring e (k = 100 in [1, 1000]) }", "z");
  CHECK_THROWS_AS(net.with_parameters({1.0, 2.0}), std::logic_error);
  CHECK(exit_code_for([&] { (void)net.with_parameters({}); }) == exit_code::internal);
  runtime::HarmonicData data;
  data.amplitude = {1.0}, data.frequency = {1.0}, data.stiffness = {100.0}, data.phase = {0.1}, data.rows = {2};
  CHECK_THROWS_AS(runtime::relative_residuals(data, {}), std::logic_error);
  CHECK(exit_code_for([&] { (void)runtime::relative_residuals(data, {}); }) == exit_code::internal);
  // fit() with nothing to fit: the front end reports that to the user (fit_schema, `rheo fit`);
  // reaching fit() with it is a bug of the caller.
  CHECK(exit_code_for([&] { (void)runtime::fit(net, {}, {}, {}); }) == exit_code::internal);
}

TEST_CASE("the approximate method on a nested model is a usage error raised by fit(), naming the element") {
  const auto net = test::network_from(
      "model n {\n  spring e (k = 100 in [1, 1000])\n  series arm {\n    spring s (k = 50 in [1, 1000])\n"
      "    dashpot d (c = 0.5)\n    slider cap (fy = 10)\n  }\n}\n",
      "n");
  runtime::HarmonicData data;
  data.path = "sweep.csv";
  data.amplitude = {1.0}, data.frequency = {1.0}, data.stiffness = {100.0}, data.phase = {0.1}, data.rows = {2};
  runtime::FitSettings settings;
  settings.score.method = runtime::FitMethod::approximate;
  const std::vector<runtime::FitDataSet> sets{{"sweep.csv", 1.0, data}};
  CHECK_THROWS_WITH_AS(runtime::fit(net, runtime::bounded_parameters(net), sets, settings),
                       doctest::Contains("cannot fit model 'n': spring 'arm.s' sits inside a nested series/parallel block"), UsageError);
  CHECK(exit_code_for([&] { (void)runtime::fit(net, runtime::bounded_parameters(net), sets, settings); }) == exit_code::usage);
}

TEST_CASE("fitted values that put a springpot's f_low above its f_high are a model error at the parameter") {
  const auto net = test::network_from(
      "model b {\n  springpot sp (k = 10, alpha = 0.5, tau = 0.01 s, f_low = 1 Hz in [0.1, 100], f_high = 10 Hz)\n}\n", "b");
  std::vector<double> values = net.parameters();
  values[static_cast<std::size_t>(test::parameter_index(net, "sp.f_low"))] = 20.0;
  CHECK_THROWS_WITH_AS(net.with_parameters(values), doctest::Contains("give f_low and f_high bounds that do not overlap"), ModelError);
  CHECK_THROWS_WITH_AS(net.with_parameters(values), doctest::Contains("test.rheo:2:"), ModelError);
}

}  // namespace errors_test
