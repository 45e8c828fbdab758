// fmt's compiled part (fmt 9.1, Debian's libfmt-dev: format-inl.h), for the FMU binary alone, which
// links no libfmt.so: the functions format-inl.h defines, and the instances of the templates that
// fmt/format.h declares `extern template` for char (the binary formats no wide text).
#include <fmt/format-inl.h>

namespace fmt::detail {

template FMT_API auto thousands_sep_impl<char>(locale_ref) -> thousands_sep_result<char>;
template FMT_API auto decimal_point_impl(locale_ref) -> char;

}  // namespace fmt::detail
