#include "runtime/solver_choice.hpp"

namespace rheo::runtime {

bool uses_sundials(const Network& network, SolverChoice choice) {
  if (choice != SolverChoice::automatic) return choice == SolverChoice::sundials;
  for (const auto& node : network.topology().nodes)
    if (node.kind == NodeKind::inerter) return true;
  return false;
}

std::optional<SolverChoice> parse_solver_choice(std::string_view word) {
  if (word == "auto") return SolverChoice::automatic;
  if (word == "fixed") return SolverChoice::fixed;
  if (word == "sundials") return SolverChoice::sundials;
  return std::nullopt;
}

const char* solver_word(SolverChoice choice) {
  switch (choice) {
    case SolverChoice::automatic: return "auto";
    case SolverChoice::fixed: return "fixed";
    case SolverChoice::sundials: return "sundials";
  }
  return "auto";
}

}  // namespace rheo::runtime
