#include "lang/dependency_order.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace dependency_order_test {

using namespace rheo::lang;

namespace {
struct Edge {
  int to;
};
using Graph = std::vector<std::vector<Edge>>;

struct Run {
  std::vector<int> finished;
  std::vector<std::vector<int>> cycles;
};

Run visit(const Graph& g) {
  Run r;
  visit_in_dependency_order(
      g.size(), [&](int i) { return g[static_cast<std::size_t>(i)]; }, [&](int i) { r.finished.push_back(i); },
      [&](const std::vector<int>& path, const Edge&) { r.cycles.push_back(path); });
  return r;
}
}  // namespace

TEST_CASE("visit_in_dependency_order: dependencies first, in the order of a recursive search") {
  const Run r = visit({{{2}, {1}}, {}, {{1}}, {{0}}});
  CHECK(r.finished == std::vector<int>{1, 2, 0, 3});
  CHECK(r.cycles.empty());
}

TEST_CASE("visit_in_dependency_order: a cycle is reported with its path and every node still finishes") {
  const Run r = visit({{{1}}, {{2}}, {{0}, {3}}, {}});
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0] == std::vector<int>{0, 1, 2});
  CHECK(r.finished == std::vector<int>{3, 2, 1, 0});
  CHECK(visit({{{0}}}).cycles == std::vector<std::vector<int>>{{0}});
}

TEST_CASE("visit_in_dependency_order: a chain a million long needs no call stack") {
  const int n = 1000000;
  Graph chain(static_cast<std::size_t>(n));
  for (int i = 0; i + 1 < n; ++i) chain[static_cast<std::size_t>(i)].push_back({i + 1});
  chain.back().push_back({0});  // and closes a cycle through all of it
  const Run r = visit(chain);
  CHECK(r.finished.front() == n - 1);
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0].size() == static_cast<std::size_t>(n));
}

}  // namespace dependency_order_test
