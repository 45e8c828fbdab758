// The model-order study of thesis Fig. 6.2 (`rheo fit FILE --orders maxwell=1..4,friction=1..6`).
//
// The model must hold only leaves in its root parallel block. For every combination of counts,
// its Maxwell and friction elements are replaced by that many copies of the first one (same
// bounds and units), with start values spread log-evenly over the data: relaxation times over
// 1/(2 pi f) for the measured frequencies, slip displacements over the measured amplitudes. The
// other elements keep their values and bounds. Each structure is written as .rheo source,
// compiled and fitted like the original; the table gives err (6.1) against the element counts.
// A structure with one element more than one already fitted starts from that fit (warm_start),
// so err falls as elements are added.
#pragma once

#include "lang/model.hpp"
#include "runtime/io/fit_data.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

struct CountRange {
  int first = 0, last = 0;
};

// Element counts to study; an absent family keeps the model's elements as they are.
struct OrderSpec {
  std::optional<CountRange> maxwell, friction;
};

// Where the copies' start values are spread, log-evenly: relaxation times and slip displacements.
struct StartSpreads {
  std::vector<double> tau, uy;  // s, mm: the first and last start value of each family
};

class OrderStudy {
 public:
  // UsageError when MODEL has a block in its root, or no element of a family SPEC varies.
  OrderStudy(const lang::CheckedModel& model, const OrderSpec& spec, const std::vector<FitDataSet>& data);

  struct Variant {
    int maxwell = -1, friction = -1;  // counts; -1: the model's own elements of that family
    std::string source;               // the structure as .rheo source, a model of the same name
  };
  // Every combination of counts, Maxwell counts outer.
  std::vector<Variant> variants() const;

  // Start values (internal units, one per parameter of VARIANT) from the fit of PREVIOUS, a
  // structure of this study with one copy fewer (FITTED: its fitted parameters). Parameters both
  // have take the fitted value (clamped into VARIANT's bounds). The added copy and PREVIOUS's
  // stiffest copy of the same family share that copy's fit: each half its k (and c or fy), both
  // its tau or uy, so VARIANT starts with PREVIOUS's response exactly (where the bounds allow)
  // and its fit can only lower err. With no copy to split, the new one starts at its lower k,
  // its tau or uy in the widest gap (in log) of the data's spread.
  std::vector<double> warm_start(const lang::CheckedModel& variant, const lang::CheckedModel& previous, const std::vector<double>& fitted) const;

 private:
  const lang::CheckedModel& model_;
  OrderSpec spec_;
  StartSpreads spreads_;
  const lang::Element* maxwell_template_ = nullptr;
  const lang::Element* friction_template_ = nullptr;
  std::string kept_;  // the other elements, as source lines
};

}  // namespace rheo::runtime
