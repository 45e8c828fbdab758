// Depth-first traversal of a dependency graph (parameters that reference parameters, models that
// instantiate models) on an explicit stack, so that no chain in the input, however long, can
// exhaust the call stack.
#pragma once

#include <cstddef>
#include <vector>

namespace rheo::lang {

// Visits nodes 0..count-1 and everything they depend on, each node once, in the order a
// recursive depth-first search would: edges(i) returns i's dependencies in order as a vector of
// Edge, each with a member `int to`; finish(i) runs after finish has run for each dependency of
// i. A dependency still being visited closes a cycle: cycle(path, edge) receives the nodes being
// visited from edge.to to the current node, and the traversal goes on as if the edge were
// absent (finish still runs for every node on the cycle).
template <class Edges, class Finish, class Cycle>
void visit_in_dependency_order(std::size_t count, Edges&& edges, Finish&& finish, Cycle&& cycle) {
  enum class Mark { unvisited, visiting, finished };
  std::vector<Mark> marks(count, Mark::unvisited);
  using Edge = typename decltype(edges(0))::value_type;
  struct Frame {
    int node;
    std::vector<Edge> edges;
    std::size_t next = 0;
  };
  std::vector<Frame> stack;
  std::vector<int> path;  // the nodes of `stack`, for cycle reports
  for (std::size_t root = 0; root < count; ++root) {
    if (marks[root] != Mark::unvisited) continue;
    auto enter = [&](int node) {
      marks[static_cast<std::size_t>(node)] = Mark::visiting;
      stack.push_back({node, edges(node)});
      path.push_back(node);
    };
    enter(static_cast<int>(root));
    while (!stack.empty()) {
      Frame& top = stack.back();
      if (top.next == top.edges.size()) {
        const int node = top.node;
        stack.pop_back();
        path.pop_back();
        marks[static_cast<std::size_t>(node)] = Mark::finished;
        finish(node);
        continue;
      }
      const Edge edge = top.edges[top.next++];
      const Mark mark = marks[static_cast<std::size_t>(edge.to)];
      if (mark == Mark::unvisited) {
        enter(edge.to);
      } else if (mark == Mark::visiting) {
        std::size_t start = path.size();
        while (path[--start] != edge.to) {}
        cycle(std::vector<int>(path.begin() + static_cast<std::ptrdiff_t>(start), path.end()), edge);
      }
    }
  }
}

}  // namespace rheo::lang
