// The log's line style: warnings and errors as "h4cal: warning: <what>" and "h4cal: error:
// <what>", the same form main prints a command's error in (common/cli/command_line.h,
// README.md#using-h4cal); information lines as they are, without a prefix.
#pragma once

#include <string>

namespace h4::host::cli {

/// Installs that style on the default spdlog logger, which writes to stderr.
void UseProgramLogStyle(const std::string& program);

}  // namespace h4::host::cli
