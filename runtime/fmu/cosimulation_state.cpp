// The byte form of an FMU state (fmi2SerializeFMUstate): native doubles and 64-bit counts, in
// this order:
//   "rheoFMS1"  magic and format version (8 bytes)
//   n, name     the model's name (count, bytes)
//   phase       0 instantiated, 1 initialisation, 2 stepping, 3 terminated
//   time [s], input u [mm], input v [mm/s], input_rate du/dt [mm/s], rate_set (1 or 0), state.u [mm],
//   state.force [N]
//   n, values   the model's parameters (internal units)
//   n, values   the network's state (Topology layout: forces N, elongations mm, ...)
// A state is read back only by an instance of the same model on the same platform.
#include "runtime/core/errors.hpp"
#include "runtime/fmu/cosimulation.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>

namespace rheo::runtime::fmu {
namespace {

constexpr char kMagic[9] = "rheoFMS1";

void put(std::string& out, const void* data, std::size_t n) { out.append(static_cast<const char*>(data), n); }
void put_count(std::string& out, std::uint64_t n) { put(out, &n, sizeof n); }
void put_double(std::string& out, double x) { put(out, &x, sizeof x); }
void put_doubles(std::string& out, const std::vector<double>& v) {
  put_count(out, v.size());
  put(out, v.data(), v.size() * sizeof(double));
}

struct Reader {
  std::string_view bytes;
  std::string_view model;
  std::size_t at = 0;

  [[noreturn]] void fail(const std::string& why) const {
    throw DataError(fmt::format("the serialized FMU state ({} bytes) is not one of model '{}': {}", bytes.size(), model, why));
  }
  void take(void* out, std::size_t n) {
    if (n > bytes.size() - at) fail(fmt::format("it ends at byte {}, {} bytes early", bytes.size(), at + n - bytes.size()));
    std::memcpy(out, bytes.data() + at, n);
    at += n;
  }
  std::uint64_t count(std::uint64_t most) {
    std::uint64_t n = 0;
    take(&n, sizeof n);
    if (n > most) fail(fmt::format("a count of {} where at most {} fits", n, most));
    return n;
  }
  double number() {
    double x = 0.0;
    take(&x, sizeof x);
    return x;
  }
  std::vector<double> numbers(std::uint64_t expected) {
    const std::uint64_t n = count(expected);
    if (n != expected) fail(fmt::format("{} values where the model has {}", n, expected));
    std::vector<double> v(n);
    take(v.data(), n * sizeof(double));
    return v;
  }
};

}  // namespace

std::string CoSimulation::serialize(const Snapshot& s) const {
  std::string out(kMagic, 8);
  put_count(out, model_->name.size());
  out += model_->name;
  put_count(out, static_cast<std::uint64_t>(s.phase));
  for (double x : {s.time, s.input, s.input_velocity, s.input_rate, s.rate_set ? 1.0 : 0.0, s.state.u, s.state.force}) put_double(out, x);
  put_doubles(out, s.parameters);
  put_doubles(out, s.state.values);
  return out;
}

Snapshot CoSimulation::deserialize(std::string_view bytes) const {
  Reader in{bytes, model_->name};
  char magic[8];
  in.take(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) in.fail("it does not begin with rheo's mark (rheoFMS1)");
  std::string name(in.count(model_->name.size()), '\0');
  in.take(name.data(), name.size());
  if (name != model_->name) in.fail(fmt::format("it is of model '{}'", name));
  Snapshot s;
  const std::uint64_t phase = in.count(static_cast<std::uint64_t>(Phase::terminated));
  s.phase = static_cast<Phase>(phase);
  s.time = in.number();
  s.input = in.number();
  s.input_velocity = in.number();
  s.input_rate = in.number();
  s.rate_set = in.number() != 0.0;
  s.state.u = in.number();
  s.state.force = in.number();
  s.parameters = in.numbers(model_->parameters.size());
  const bool started = s.phase == Phase::stepping || s.phase == Phase::terminated;
  const auto state_size = static_cast<std::uint64_t>(compiled_->topology().state_size);
  s.state.values = in.numbers(started ? state_size : 0);  // none before initialisation ends
  if (in.at != bytes.size()) in.fail(fmt::format("{} bytes follow its end", bytes.size() - in.at));
  return s;
}

}  // namespace rheo::runtime::fmu
