#include "io/error.h"

namespace softmol::io {

std::string SourceLocation::ToString() const {
  std::string s = file;
  if (line > 0) {
    s += ':' + std::to_string(line);
    if (column > 0) s += ':' + std::to_string(column);
  }
  if (!detail.empty()) {
    if (!s.empty()) s += ": ";
    s += detail;
  }
  return s;
}

static std::string Compose(const SourceLocation& where, std::string_view message) {
  std::string w = where.ToString();
  return w.empty() ? std::string(message) : w + ": " + std::string(message);
}

InputError::InputError(SourceLocation where, std::string_view message)
    : std::runtime_error(Compose(where, message)), where_(std::move(where)), message_(message) {}

}  // namespace softmol::io
