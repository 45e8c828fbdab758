// A history written piece by piece (HistoryCsvWriter) is history_csv()'s text byte for byte,
// however it is cut, and each number reads back as the very double written (shortest
// round-trip), checked by an independent reader (strtod).
#include "runtime/io/history_writer.hpp"

#include "portable_random.hpp"
#include "runtime/io/output.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace history_writer_test {

using namespace rheo::runtime;
namespace fs = std::filesystem;

namespace {

// Doubles of every kind: small and large exponents, subnormals, -0, integers, 17-digit values.
// A whole number in [0, N) from RANDOM.
std::size_t below(rheo::test::PortableRandom& random, std::size_t n) { return static_cast<std::size_t>(random.unit() * static_cast<double>(n)); }

History random_history(rheo::test::PortableRandom& random, std::size_t n, bool elements) {
  auto unit = [&] { return random.uniform(-1.0, 1.0); };
  auto any = [&]() {
    switch (below(random, 6)) {
      case 0: return unit() * std::pow(10.0, static_cast<double>(below(random, 621)) - 320.0);
      case 1: return std::floor(unit() * 1e6);
      case 2: return -0.0;
      case 3: return std::numeric_limits<double>::denorm_min() * static_cast<double>(below(random, 1000));
      case 4: return std::nextafter(1.0, 2.0) * unit();
      default: return unit();
    }
  };
  History h;
  for (std::size_t k = 0; k < n; ++k) h.time.push_back(static_cast<double>(k) * 1e-4), h.displacement.push_back(any()), h.force.push_back(any());
  if (elements) {
    h.element_paths = {"a", "b.c"};
    h.element_force.assign(2, {}), h.element_elongation.assign(2, {});
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t k = 0; k < n; ++k) h.element_force[i].push_back(any()), h.element_elongation[i].push_back(any());
  }
  return h;
}

History slice(const History& h, std::size_t from, std::size_t to) {
  auto cut = [&](const std::vector<double>& v) {
    return std::vector<double>(v.begin() + static_cast<long>(from), v.begin() + static_cast<long>(to));
  };
  History p;
  p.element_paths = h.element_paths;
  p.time = cut(h.time), p.displacement = cut(h.displacement), p.force = cut(h.force);
  for (std::size_t i = 0; i < h.element_paths.size(); ++i)
    p.element_force.push_back(cut(h.element_force[i])), p.element_elongation.push_back(cut(h.element_elongation[i]));
  return p;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("a history written in pieces is history_csv's text, and every number reads back as the double written") {
  rheo::test::PortableRandom random(28);
  const fs::path out = fs::temp_directory_path() / fmt::format("rheo-history-writer-{}.csv", ::getpid());
  const ResultHeader header{"m", "m.rheo", "history file=h.csv"};
  for (const bool elements : {false, true}) {
    CAPTURE(elements);
    const History h = random_history(random, 60000, elements);  // more than kFlushBytes of text
    {
      PendingOutput file(out.string());
      HistoryCsvWriter writer(file);
      writer.begin(header, h.element_paths);
      for (std::size_t from = 0; from < h.time.size();) {
        const std::size_t to = std::min(h.time.size(), from + 1 + below(random, 5000));
        writer.write(slice(h, from, to));
        from = to;
      }
      writer.finish();
      file.commit();
    }
    const std::string text = read(out);
    CHECK(text == history_csv(header, h));
    // Read back by strtod, an independent reader: bit for bit.
    std::istringstream lines(text);
    std::string line;
    std::getline(lines, line), std::getline(lines, line);  // the comment and the names
    std::size_t mismatches = 0, k = 0;
    for (; std::getline(lines, line); ++k) {
      std::vector<double> want = {h.time[k], h.displacement[k], h.force[k]};
      for (std::size_t i = 0; i < h.element_paths.size(); ++i) want.push_back(h.element_force[i][k]), want.push_back(h.element_elongation[i][k]);
      const char* p = line.c_str();
      for (double w : want) {
        char* end = nullptr;
        const double got = std::strtod(p, &end);
        mismatches += std::memcmp(&got, &w, sizeof got) != 0;
        p = *end ? end + 1 : end;
      }
    }
    CHECK(k == h.time.size());
    CHECK(mismatches == 0);
  }
  fs::remove(out);
}

}  // namespace history_writer_test
