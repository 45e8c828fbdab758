// Columns found by role: usual names in any case, names a data line gives, units that suit the
// role, material data turned into the component's terms by the specimen's geometry.
#include "runtime/io/column_roles.hpp"

#include "lang/fit_schema.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/io/fit_data.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace column_roles_test {

using namespace rheo::runtime;

namespace {
const std::string trios = std::string(RHEO_DATA_DIR) + "/real/trios_multi_technique.txt";

std::string harmonic_error(const std::string& text, const DataReading& reading = {}) {
  try {
    harmonic_data_from_table(parse_table("h.csv", text), reading);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("every role the language accepts in `columns` is one the readers know, and back") {
  for (const auto& name : rheo::lang::data_column_roles()) CHECK(role_named(name).has_value());
  for (Role r : {Role::time, Role::displacement, Role::force, Role::amplitude, Role::frequency, Role::stiffness, Role::phase, Role::storage,
                 Role::loss, Role::weight})
    CHECK(std::find(rheo::lang::data_column_roles().begin(), rheo::lang::data_column_roles().end(), std::string(role_name(r))) !=
          rheo::lang::data_column_roles().end());
}

TEST_CASE("a role's usual names listed for messages, in order of preference") {
  CHECK(role_usual_names(Role::time) == "time, t, test time, elapsed time");
  CHECK(role_usual_names(Role::displacement) == "displacement, position, stroke, travel, deflection, disp, x, u");
  CHECK(role_usual_names(Role::force) == "force, load, standard force, reaction force, f");
}

TEST_CASE("short names as MATLAB variables and scripts have them: x and u are a displacement, F a force, the long names first") {
  const Table t = parse_table("s.csv", "t [s],x [mm],F [N]\n0,0,1\n1,0.5,2\n");
  CHECK(find_role(t, Role::time, {}) == 0);
  CHECK(find_role(t, Role::displacement, {}) == 1);
  CHECK(find_role(t, Role::force, {}) == 2);
  const Table u = parse_table("u.csv", "time [s],u [um],f [kN]\n0,0,1\n1,5,2\n");
  CHECK(role_values(u, find_role(u, Role::displacement, {}), Role::displacement, {})[1] == doctest::Approx(0.005).scale(0.0));
  CHECK(role_values(u, find_role(u, Role::force, {}), Role::force, {})[1] == 2000.0);
  const Table both = parse_table("b.csv", "x [mm],displacement [mm],F [N],force [N]\n0,0,1,1\n");
  CHECK(find_role(both, Role::displacement, {}) == 1);
  CHECK(find_role(both, Role::force, {}) == 3);
  // A frequency written f beside a force: the force column, named as preferred and of a force unit.
  const Table sweep = parse_table("f.csv", "f [Hz],force [N]\n1,2\n");
  CHECK(find_role(sweep, Role::force, {}) == 1);
}

TEST_CASE("usual names in any case and spacing, unused columns may hold anything") {
  const Table t = parse_table("h.csv",
                              "Temperature [degC],Amplitude [mm],FREQUENCY [Hz],Dynamic  Stiffness [N/mm],Phase Angle [\xC2\xB0],Comment\n"
                              "23,0.5,10,1200,8,first\n23,1,10,1100,9,\n");
  const HarmonicData d = harmonic_data_from_table(t, {});
  REQUIRE(d.size() == 2);
  CHECK(d.amplitude[1] == 1.0);
  CHECK(d.stiffness[0] == 1200.0);
  CHECK(d.phase[1] == doctest::Approx(9.0 * std::numbers::pi / 180.0).scale(0.0));
  // Storage and loss under their modulus names, in stiffness units.
  const HarmonicData e = harmonic_data_from_table(parse_table("e.csv", "amplitude [mm],frequency [Hz],K' [N/mm],K'' [N/mm]\n1,1,300,400\n"), {});
  CHECK(e.stiffness[0] == doctest::Approx(500.0));
  CHECK(e.phase[0] == doctest::Approx(std::atan2(400.0, 300.0)).scale(0.0));
}

TEST_CASE("a data line names unusual columns, a name the header lacks is an error listing the header") {
  DataReading reading;
  reading.columns.columns = {{Role::frequency, "f"}, {Role::storage, "Es"}, {Role::loss, "El"}, {Role::amplitude, "u0"}};
  const HarmonicData d = harmonic_data_from_table(parse_table("m.csv", "u0 [mm],f [Hz],Es [N/mm],El [N/mm]\n0.1,2,30,40\n"), reading);
  CHECK(d.frequency[0] == 2.0);
  CHECK(d.stiffness[0] == doctest::Approx(50.0));
  reading.columns.columns = {{Role::frequency, "freq_hz"}};
  CHECK(harmonic_error("amplitude [mm],f [Hz],stiffness [N/mm],phase [deg]\n1,1,1,1\n", reading)
            .find("h.csv:1:1: error: the data line reads 'frequency' from a column 'freq_hz', which this table does not have; name one of its "
                  "columns (the header has: amplitude, f, stiffness, phase)") == 0);
}

TEST_CASE("of two candidates the one whose unit suits the role is read") {
  // TRIOS writes a torsional 'Stiffness [N.m/rad]' next to 'Complex modulus [MPa]'.
  DataReading reading;
  reading.columns.area = 100.0;
  reading.columns.height = 2.0;
  const HarmonicData d = harmonic_data_from_table(
      parse_table("t.txt",
                  "Oscillation strain\tFrequency\tStiffness\tComplex modulus\tPhase angle\n%\tHz\tN.m/rad\tMPa\t\xC2\xB0\n10\t1\t5\t0.5\t30\n"),
      reading);
  CHECK(d.stiffness[0] == doctest::Approx(0.5 * 100.0 / 2.0));     // K = E A / h
  CHECK(d.amplitude[0] == doctest::Approx(0.1 * 2.0).scale(0.0));  // u = strain h
  CHECK(d.material);
}

TEST_CASE("material data without geometry, and an amplitude twice, are errors that say what to add") {
  CHECK(harmonic_error("strain [%],frequency [Hz],stiffness [N/mm],phase [deg]\n1,1,1,1\n")
            .find("h.csv:1:9: error: column 'strain' is a strain (%); give the specimen's geometry on the data line (height = 10 mm)") == 0);
  CHECK(harmonic_error("amplitude [mm],frequency [Hz],storage [MPa],loss [MPa]\n1,1,1,1\n")
            .find("column 'storage' is a modulus (MPa); give the specimen's geometry on the data line (area = 314 mm^2, height = 10 mm)") !=
        std::string::npos);
  DataReading reading;
  reading.amplitude = 0.2;
  CHECK(harmonic_error("amplitude [mm],frequency [Hz],stiffness [N/mm],phase [deg]\n1,1,1,1\n", reading)
            .find("the data line gives an amplitude, and the table has an amplitude column 'amplitude'; remove one of them") != std::string::npos);
  // An angle is not a strain: 'Oscillation displacement [rad]' is no amplitude.
  CHECK(harmonic_error("amplitude [rad],frequency [Hz],stiffness [N/mm],phase [deg]\n1,1,1,1\n")
            .find("column 'amplitude' has unit 'rad', a plain number") != std::string::npos);
}

TEST_CASE("a master curve without an amplitude column takes the data line's amplitude, as a length or a strain") {
  const std::string curve = "frequency [Hz],storage [MPa],loss [MPa]\n1,2,0.5\n10,3,1\n";
  DataReading reading;
  reading.columns.area = 50.0;
  reading.columns.height = 5.0;
  reading.strain_amplitude = 0.001;
  const HarmonicData strained = harmonic_data_from_table(parse_table("m.csv", curve), reading);
  CHECK(strained.amplitude == std::vector<double>{0.005, 0.005});
  CHECK(strained.stiffness[1] == doctest::Approx(std::hypot(3.0, 1.0) * 10.0));
  reading.strain_amplitude.reset();
  reading.amplitude = 0.01;
  CHECK(harmonic_data_from_table(parse_table("m.csv", curve), reading).amplitude[0] == 0.01);
}

TEST_CASE("the shared TRIOS export reads as harmonic data from a data line alone") {
  DataReading reading;
  reading.step = "Amplitude sweep";
  reading.columns.area = 490.87;
  reading.columns.height = 1.0;
  const FitDataSet set = read_fit_data(trios, 1.0, nullptr, reading);
  REQUIRE(set.is_harmonic());
  const HarmonicData& d = set.harmonic();
  CHECK(d.size() == 29);
  // First row: strain 0.00989877906867619 %, 1 Hz (6.28318548202515 rad/s), |G*| 0.01838055859375 MPa
  // ('Complex modulus', read before storage and loss), within 1e-4 of |G' + i G''|.
  CHECK(d.amplitude[0] == doctest::Approx(0.00989877906867619e-2 * 1.0).epsilon(1e-12).scale(0.0));
  CHECK(d.frequency[0] == doctest::Approx(1.0).epsilon(1e-7));
  CHECK(d.stiffness[0] == doctest::Approx(0.01838055859375 * 490.87).epsilon(1e-12));
  CHECK(d.stiffness[0] == doctest::Approx(std::hypot(0.01836746484375, 0.000693655334472656) * 490.87).epsilon(1e-4));
  CHECK(set.source.step == "Amplitude sweep - 1");
  CHECK(set.source.material);
  reading.step = "Flow ramp";
  // The flow ramp has a time column but no force: a history that cannot be read, located at its names row.
  CHECK_THROWS_WITH_AS(read_fit_data(trios, 1.0, nullptr, reading),
                       doctest::Contains("trios_multi_technique.txt:236:1: error: a measured history needs a column 'force [N]'"), DataError);
}

}  // namespace column_roles_test
