#include "runtime/closed_form/phasor.hpp"

#include "runtime/network/leaf_kernels.hpp"

#include <numbers>

namespace rheo::runtime {
namespace {

using Complex = std::complex<double>;

std::optional<Complex> compose(const lang::Element& e, const std::vector<double>& p, double omega) {
  auto at = [&](int slot) { return p[static_cast<std::size_t>(e.parameters[static_cast<std::size_t>(slot)])]; };
  const Complex i{0.0, 1.0};
  switch (e.kind) {
    case lang::ElementKind::spring: return Complex{at(0), 0.0};
    case lang::ElementKind::dashpot: return i * omega * at(0);
    case lang::ElementKind::inerter: return Complex{-at(0) * omega * omega, 0.0};
    case lang::ElementKind::maxwell: {
      const StorageLoss m = maxwell_storage_loss(at(0), omega * (at(1) / at(0)));
      return Complex{m.storage, m.loss};
    }
    case lang::ElementKind::springpot: return at(0) * std::pow(i * omega * at(2), at(1));
    case lang::ElementKind::parallel: {
      Complex sum{0.0, 0.0};
      for (const auto& child : e.children) {
        auto c = compose(child, p, omega);
        if (!c) return std::nullopt;
        sum += *c;
      }
      return sum;
    }
    case lang::ElementKind::series: {
      Complex compliance{0.0, 0.0};
      for (const auto& child : e.children) {
        auto c = compose(child, p, omega);
        if (!c) return std::nullopt;
        if (*c == Complex{0.0, 0.0}) return Complex{0.0, 0.0};
        compliance += 1.0 / *c;
      }
      return 1.0 / compliance;
    }
    default: return std::nullopt;
  }
}

}  // namespace

std::optional<std::complex<double>> complex_stiffness(const lang::CheckedModel& model, const std::vector<double>& parameter_values, double frequency) {
  return compose(model.root, parameter_values, 2.0 * std::numbers::pi * frequency);
}

}  // namespace rheo::runtime
