#include "runtime/report/network_diagram.hpp"
#include "report_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

namespace network_diagram_test {

using namespace rheo;
using rheo::test::count;

TEST_CASE("report network diagram: nested series and parallel blocks, one symbol per leaf") {
  const lang::CheckedModel model = test::model_from(R"(
model nested {
  spring   rubber (k = 800 N/mm)
  maxwell  visco (k = 150 N/mm, tau = 3 ms)
  friction f1 (k = 200 N/mm, uy = 0.02 mm)
  series fluid {
    slider  cap (fy = 60 N)
    spring  k1 (k = 600 N/mm)
    parallel y {
      inerter column (b = 40 kg)
      dashpot channel (c = 3.0 N*s/mm)
      spring  bulge (k = 150 N/mm)
    }
  }
}
)",
                                                    "nested");
  const std::string svg = runtime::report::network_diagram_svg(model.root, "Network of nested", true);
  CHECK(test::xml_problem(svg) == "");
  CHECK(count(svg, "class=\"element\"") == 8);
  CHECK(count(svg, "class=\"block\"") == 2);
  CHECK(count(svg, "data-kind=\"series\"") == 1);
  CHECK(count(svg, "data-kind=\"parallel\"") == 1);
  CHECK(count(svg, "data-kind=\"spring\"") == 3);
  for (const char* kind : {"maxwell", "friction", "slider", "inerter", "dashpot"}) CHECK(count(svg, fmt::format("data-kind=\"{}\"", kind)) == 1);
  for (const char* path : {"fluid.y.column", "fluid.cap", "rubber"}) CHECK(count(svg, fmt::format("data-path=\"{}\"", path)) == 1);
  CHECK(svg.find("u(t)") != std::string::npos);
}

TEST_CASE("report network diagram: a long series chain is wider than a parallel block of the same leaves") {
  const lang::CheckedModel chain = test::model_from(
      "model m { series s { spring a (k = 1 N/mm)\n spring b (k = 1 N/mm)\n spring c (k = 1 N/mm) } }", "m");
  const lang::CheckedModel stack = test::model_from("model m { spring a (k = 1 N/mm)\n spring b (k = 1 N/mm)\n spring c (k = 1 N/mm) }", "m");
  const auto width = [](const std::string& svg) {
    const auto at = svg.find("viewBox=\"0 0 ") + 13;
    return std::stod(svg.substr(at, svg.find(' ', at) - at));
  };
  const std::string a = runtime::report::network_diagram_svg(chain.root, "chain", false),
                    b = runtime::report::network_diagram_svg(stack.root, "stack", false);
  CHECK(width(a) > width(b) + 150);  // three leaf widths against one, less the bus bars
  CHECK(count(a, "class=\"element\"") == 3);
  CHECK(count(b, "class=\"element\"") == 3);
}

}  // namespace network_diagram_test
