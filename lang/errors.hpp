// The errors a user can cause, one class per kind of mistake, each with its documented exit
// code (docs/errors.md). A user error is thrown where the mistake is found; its message says
// where (file:line:col, element path, option) and what to do. Every other exception is a bug:
// broken preconditions and invariants throw std::logic_error, and the CLI reports any exception
// that is not a UserError as an internal error (exit 1). Nothing converts one kind into another
// by its message.
#pragma once

#include <exception>
#include <stdexcept>
#include <string>

namespace rheo {

namespace exit_code {
inline constexpr int ok = 0;
inline constexpr int internal = 1;
inline constexpr int usage = 2;
inline constexpr int model = 3;
inline constexpr int data = 4;
inline constexpr int numerical = 5;
}  // namespace exit_code

class UserError : public std::runtime_error {
 public:
  int exit_code() const noexcept { return code_; }

 protected:
  UserError(const std::string& message, int code) : std::runtime_error(message), code_(code) {}

 private:
  int code_;
};

// Exit 2: the command line, or a choice it makes, is wrong (an option, a method the model
// cannot take).
struct UsageError : UserError {
  explicit UsageError(const std::string& message) : UserError(message, ::rheo::exit_code::usage) {}
};
// Exit 3: the model file: invalid language (lang::CompileError), or valid language that cannot
// be simulated (e.g. an inerter no compliant member holds).
struct ModelError : UserError {
  explicit ModelError(const std::string& message) : UserError(message, ::rheo::exit_code::model) {}
};
// Exit 4: a data file, source file or output path is unusable.
struct DataError : UserError {
  explicit DataError(const std::string& message) : UserError(message, ::rheo::exit_code::data) {}
};
// Exit 5: the numerics could not deliver.
struct NumericalError : UserError {
  explicit NumericalError(const std::string& message) : UserError(message, ::rheo::exit_code::numerical) {}
};

// A UserError's exit code; exit_code::internal for every other exception.
inline int exit_code_of(const std::exception& e) noexcept {
  const auto* user = dynamic_cast<const UserError*>(&e);
  return user ? user->exit_code() : exit_code::internal;
}

}  // namespace rheo
