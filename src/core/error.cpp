#include "core/error.hpp"

namespace rupture {

namespace {
std::string compose(const std::string& where, const std::string& problem, const std::string& fix) {
  std::string message = where.empty() ? problem : where + ": " + problem;
  if (!fix.empty()) message += "; " + fix;
  return message;
}
}  // namespace

InputError::InputError(const std::string& where, const std::string& problem, const std::string& fix)
    : std::runtime_error(compose(where, problem, fix)) {}

}  // namespace rupture
