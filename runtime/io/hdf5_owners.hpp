// RAII owners of HDF5 1.10 C handles (hid_t) and return-code checking, in the manner of
// dae/sundials_owners.hpp.
//
// Every handle is owned by exactly one object and closed by its own close call when the owner
// goes (members are destroyed bottom-up: declare the file first). Every call that returns a
// status or an id goes through check() or an owner's constructor, which turn a failure into a
// DataError naming the file, the call, what it was applied to and HDF5's own description of
// the fault (the innermost message of its error stack). HDF5's printing of its error stack to
// standard error is switched off (library()).
#pragma once

#include "runtime/core/errors.hpp"

#include <hdf5.h>

#include <optional>
#include <string>
#include <utility>

namespace rheo::runtime::hdf5 {

// Switches off HDF5's automatic error printing, once; before any other HDF5 call.
void library();

// "FILE: error: HDF5 CALL failed on WHAT (HDF5's description)", for a status or id < 0.
[[noreturn]] void fail(const std::string& file, const char* call, const std::string& what);

inline herr_t check(herr_t status, const std::string& file, const char* call, const std::string& what) {
  if (status < 0) fail(file, call, what);
  return status;
}

// The innermost description of HDF5's error stack, and the stack cleared; "" when empty.
std::string last_error();

template <herr_t (*Close)(hid_t)>
class Owner {
 public:
  Owner() = default;
  // Takes ID from CALL (applied to WHAT in FILE): DataError when it is negative.
  Owner(hid_t id, const std::string& file, const char* call, const std::string& what) : id_(id) {
    if (id_ < 0) fail(file, call, what);
  }
  ~Owner() { reset(); }
  Owner(Owner&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Owner& operator=(Owner&& other) noexcept {
    if (this != &other) reset(), id_ = std::exchange(other.id_, H5I_INVALID_HID);
    return *this;
  }
  Owner(const Owner&) = delete;
  Owner& operator=(const Owner&) = delete;

  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  // Closes the handle now; the close call's status (>= 0 when nothing was open), for a caller
  // that must know that its data reached the file (File).
  herr_t close() { return id_ >= 0 ? Close(std::exchange(id_, H5I_INVALID_HID)) : 0; }

 private:
  void reset() {
    if (id_ >= 0) Close(std::exchange(id_, H5I_INVALID_HID));
  }
  hid_t id_ = H5I_INVALID_HID;
};

using File = Owner<H5Fclose>;
using Group = Owner<H5Gclose>;
using Dataset = Owner<H5Dclose>;
using Dataspace = Owner<H5Sclose>;
using Datatype = Owner<H5Tclose>;
using Attribute = Owner<H5Aclose>;
using PropertyList = Owner<H5Pclose>;

// The string held by OBJECT's attribute NAME (fixed or variable length; trailing blanks and
// nulls dropped); nullopt when it has none. PATH names OBJECT in messages. An attribute that is
// not one string is a DataError "FILE: error: the 'NAME' attribute of PATH is not a string; ADVICE".
std::optional<std::string> string_attribute(hid_t object, const char* name, const std::string& file, const std::string& path,
                                            const std::string& advice);

}  // namespace rheo::runtime::hdf5
