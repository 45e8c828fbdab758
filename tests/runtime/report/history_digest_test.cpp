// A streamed history's digest for a report: whole up to its capacity, evenly strided beyond,
// checked against the samples it must keep, computed from the closed form of its stride.
#include "runtime/report/history_digest.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

namespace history_digest_test {

using rheo::runtime::History;
using rheo::runtime::report::HistoryDigest;

namespace {

// Samples 0..N-1 (displacement k, force -2k: each sample names its index) handed over in
// pieces of varying length, as a stream's blocks and a cut last block are.
void feed(HistoryDigest& digest, std::size_t n) {
  History piece;
  std::size_t k = 0;
  for (std::size_t length = 1; k < n; length = length * 3 % 5000 + 1) {
    piece.time.clear(), piece.displacement.clear(), piece.force.clear();
    for (std::size_t i = 0; i < length && k < n; ++i, ++k) {
      piece.time.push_back(1e-4 * static_cast<double>(k));
      piece.displacement.push_back(static_cast<double>(k));
      piece.force.push_back(-2.0 * static_cast<double>(k));
    }
    digest.write(piece);
  }
}

// The least power of two S with ceil(N / S) <= capacity.
std::uint64_t expected_stride(std::uint64_t n) {
  std::uint64_t s = 1;
  while ((n + s - 1) / s > HistoryDigest::kCapacity) s *= 2;
  return s;
}

}  // namespace

TEST_CASE("a history digest keeps a history of up to its capacity whole, as the held history's report draws it") {
  for (const std::size_t n : {std::size_t{1}, std::size_t{4097}, HistoryDigest::kCapacity}) {
    CAPTURE(n);
    HistoryDigest digest;
    digest.begin({}, {});
    feed(digest, n);
    const auto h = digest.comparison("loop");
    CHECK(h.label == "loop");
    CHECK(digest.stride() == 1);
    CHECK(digest.samples() == n);
    REQUIRE(h.displacement.size() == n);
    REQUIRE(h.model_force.size() == n);
    CHECK(h.displacement.back() == static_cast<double>(n - 1));
    CHECK(h.model_force.back() == -2.0 * static_cast<double>(n - 1));
    CHECK_FALSE(h.measured());
  }
}

TEST_CASE("a history digest of a longer history keeps every stride-th sample, the least power-of-two stride that fits its capacity") {
  for (const std::size_t n : {HistoryDigest::kCapacity + 1, 5 * HistoryDigest::kCapacity + 123, std::size_t{1'000'003}}) {
    CAPTURE(n);
    HistoryDigest digest;
    digest.begin({}, {});
    feed(digest, n);
    const std::uint64_t s = expected_stride(n);
    CHECK(s > 1);
    CHECK(digest.stride() == s);
    const auto h = digest.comparison("loop");
    REQUIRE(h.displacement.size() == (n + s - 1) / s);
    CHECK(h.displacement.size() <= HistoryDigest::kCapacity);
    CHECK(h.displacement.size() > HistoryDigest::kCapacity / 2);
    bool all = true;
    for (std::size_t i = 0; i < h.displacement.size(); ++i)
      all = all && h.displacement[i] == static_cast<double>(i * s) && h.model_force[i] == -2.0 * static_cast<double>(i * s);
    CHECK(all);
  }
}

TEST_CASE("a history digest restarted forgets what it kept, as a stream read whole after a restart needs") {
  HistoryDigest digest;
  digest.begin({}, {});
  feed(digest, 3 * HistoryDigest::kCapacity);
  digest.restart();
  feed(digest, 10);
  CHECK(digest.stride() == 1);
  CHECK(digest.comparison("x").displacement == std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
}

}  // namespace history_digest_test
