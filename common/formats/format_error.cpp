// FormatError; see format_error.h.
#include "common/formats/format_error.h"

#include <fmt/core.h>

namespace h4 {
namespace {
std::string Compose(const std::string& file, int line, const std::string& field,
                    const std::string& what) {
  std::string message = file;
  if (line > 0) message += fmt::format(":{}", line);
  message += ": ";
  if (!field.empty()) message += "field '" + field + "': ";
  return message + what;
}
}  // namespace

FormatError::FormatError(std::string file, int line, std::string field, const std::string& what)
    : std::runtime_error(Compose(file, line, field, what)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)) {}

}  // namespace h4
