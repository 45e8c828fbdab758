// The friction damper rig file (examples/data/friction_damper_rig.csv) is what its generator
// (rig_file_support.hpp) writes: every number within the last digit written (the simulation's
// rounding may differ between compilers in the last bit, which can move a rounded digit by one).
// RHEO_WRITE_RIG_FILE=PATH writes the generator's file to PATH (how the file was made).
#include "rig_file_support.hpp"

#include "runtime/io/history_csv.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>

namespace rig_file_test {

using namespace rheo;

TEST_CASE("examples/data/friction_damper_rig.csv is what its generator writes, within the last digit") {
  const std::string text = test::rig_file::csv();
  if (const char* path = std::getenv("RHEO_WRITE_RIG_FILE")) std::ofstream(path, std::ios::binary) << text;
  const runtime::Table made = runtime::parse_table("generated.csv", text);
  const runtime::Table stored = runtime::read_table(std::string(RHEO_DATA_DIR) + "/friction_damper_rig.csv");
  REQUIRE(stored.names == made.names);
  REQUIRE(stored.units == made.units);
  REQUIRE(stored.rows.size() == made.rows.size());
  // Internal units: s, mm, N; the file writes 0.01 s, 0.001 mm and 1 N.
  const double digit[3] = {0.01, 0.001, 1.0};
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t r = 0; r < made.rows.size(); ++r)
      if (std::abs(stored.columns[c][r] - made.columns[c][r]) > 1.001 * digit[c]) {
        FAIL_CHECK("row " << stored.rows[r] << ", column " << stored.names[c] << ": stored " << stored.columns[c][r] << ", generated "
                          << made.columns[c][r]);
        break;
      }
}

}  // namespace rig_file_test
