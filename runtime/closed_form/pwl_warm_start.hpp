// Warm starts of the event path's shooting (pwl_periodic.hpp) between the evaluations of a
// finite-difference Jacobian: the base evaluation records, per harmonic point (u0, omega) and
// piecewise-linear subtree (its ordinal among the point's event-driven subtrees), the start of
// the cycle that closed on itself, i.e. the periodic state and the mode it settles from; each
// column's evaluation (one parameter moved by a relative 1e-6) starts the same point's Newton
// iteration there instead of at the cold start, and needs about two cycles instead of
// four (numerics.md, "Warm starts").
//
// Deterministic across thread counts: every column starts from the same base, whichever thread
// evaluates it, and a warm-started solve is never kept for restoring (a later cold solve of the
// same drive would otherwise get its last bits from whichever thread held it). A column that
// leaves the subtree unchanged starts at the base's own closing cycle and closes at once on the
// same bits the base had (a restore gives the same).
//
// Recording is safe from several threads at once (a grid's points run on every thread); find()
// only after seal(), from any number of threads. Storage is kept across clear(): no allocation
// once the first evaluation has filled it.
#pragma once

#include "runtime/closed_form/pwl_mode.hpp"

#include <cstddef>
#include <mutex>
#include <vector>

namespace rheo::runtime {

// Where a shooting starts: positions and velocities of the branch's nodes at the span's start
// [mm, mm/s], and the mode settled from there (pwl_periodic.cpp); for a periodic state, the
// per-coordinate allowance of the periodic test its closing cycle passed (empty: the plain
// test), which a warm solve from it applies to its first cycle, so that this cycle closes as
// the recorded one did and gives the same bits whichever thread kept which solve.
struct PwlStart {
  PwlVector X0;
  PwlModeCode mode;
  PwlVector allowed;
};

class PwlWarmStarts {
 public:
  void clear();  // forget every record (keeping their storage)
  void record(double u0, double omega, int branch, const PwlStart& start);
  void seal();  // recording is over: ready for find()
  // The start recorded for the point and subtree, or null.
  const PwlStart* find(double u0, double omega, int branch) const;
  std::size_t size() const { return count_; }

 private:
  struct Entry {
    double u0 = 0.0, omega = 0.0;
    int branch = 0;
    PwlStart start;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;  // the first count_ are records; sorted by (u0, omega, branch) when sealed
  std::size_t count_ = 0;
  bool sealed_ = false;
};

}  // namespace rheo::runtime
