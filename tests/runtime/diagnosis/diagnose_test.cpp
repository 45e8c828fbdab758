// diagnose()'s own rules (runtime/diagnosis/diagnose.hpp); the whole diagnosis is tested on data
// with a known hidden effect by tests/runtime/diagnosis_*_test.cpp.
#include "runtime/diagnosis/diagnose.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace diagnose_test {

using namespace rheo::runtime;

TEST_CASE("diagnosis_solver: auto takes fixed steps where a time history is fitted, and stands on harmonic tables alone") {
  const FitDataSet table{"grid.csv", 1.0, HarmonicData{}, {}, {}}, history{"rig.csv", 1.0, HistoryData{}, {}, {}};
  CHECK(diagnosis::diagnosis_solver(SolverChoice::automatic, {table}) == SolverChoice::automatic);
  CHECK(diagnosis::diagnosis_solver(SolverChoice::automatic, {table, table}) == SolverChoice::automatic);
  CHECK(diagnosis::diagnosis_solver(SolverChoice::automatic, {history}) == SolverChoice::fixed);
  CHECK(diagnosis::diagnosis_solver(SolverChoice::automatic, {table, history}) == SolverChoice::fixed);
  // A solver the user chose stands, whatever the data.
  for (const SolverChoice chosen : {SolverChoice::fixed, SolverChoice::sundials}) {
    CHECK(diagnosis::diagnosis_solver(chosen, {table}) == chosen);
    CHECK(diagnosis::diagnosis_solver(chosen, {table, history}) == chosen);
  }
}

}  // namespace diagnose_test
