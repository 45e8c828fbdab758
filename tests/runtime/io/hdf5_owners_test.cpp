// The HDF5 owners: a failed call is a DataError naming the file, the call, what it was applied to
// and HDF5's own description, with HDF5's error stack cleared and not printed; an owner closes
// its handle once, when it goes or is moved over.
#include "runtime/io/hdf5_owners.hpp"

#include <doctest/doctest.h>

#include <string>
#include <utility>

namespace hdf5_owners_test {

using namespace rheo::runtime;

TEST_CASE("a failed HDF5 call is a DataError naming the file, the call, its object and HDF5's description") {
  hdf5::library();
  const hid_t absent = H5Fopen("/nonexistent-rheo/run.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(absent < 0);
  try {
    hdf5::fail("run.h5", "H5Fopen", "the file");
    FAIL("no exception");
  } catch (const DataError& e) {
    const std::string message = e.what();
    CHECK(message.starts_with("run.h5: error: HDF5 H5Fopen failed on the file ("));
    CHECK(message.ends_with(")"));
  }
  CHECK(hdf5::last_error().empty());  // the stack was cleared
  CHECK(hdf5::check(0, "run.h5", "H5Dread", "/t") == 0);
  CHECK_THROWS_WITH_AS(hdf5::check(-1, "run.h5", "H5Dread", "/t"), "run.h5: error: HDF5 H5Dread failed on /t", DataError);
  CHECK_THROWS_AS(hdf5::Dataspace(H5I_INVALID_HID, "run.h5", "H5Screate", "a space"), DataError);
}

TEST_CASE("an HDF5 owner closes its handle once: when it goes, when moved over, or by close()") {
  const hsize_t n = 4;
  hid_t id = H5I_INVALID_HID;
  {
    hdf5::Dataspace space(H5Screate_simple(1, &n, nullptr), "f", "H5Screate_simple", "s");
    id = space.get();
    CHECK(H5Iis_valid(id) > 0);
    hdf5::Dataspace moved(std::move(space));
    CHECK(moved.get() == id);
    CHECK_FALSE(space);
    CHECK(H5Iis_valid(id) > 0);
  }
  CHECK(H5Iis_valid(id) <= 0);
  hdf5::Dataspace a(H5Screate_simple(1, &n, nullptr), "f", "H5Screate_simple", "a");
  const hid_t first = a.get();
  a = hdf5::Dataspace(H5Screate_simple(1, &n, nullptr), "f", "H5Screate_simple", "b");
  CHECK(H5Iis_valid(first) <= 0);
  CHECK(a.close() >= 0);
  CHECK_FALSE(a);
  CHECK(a.close() == 0);  // nothing open: nothing to close
}

}  // namespace hdf5_owners_test
