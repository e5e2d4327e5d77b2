// The exit code of an h4cam run (README.md#using-h4cal): 0 success, 1 an error (main
// prints it once), 3 the command ran but nothing usable was measured or rendered (the
// command says why), CLI11's usage errors 100 and above. A command that finished without a
// usable result sets 3 here instead of throwing, so that what it wrote stays written.
#pragma once

#include "common/cli/command_line.h"

namespace h4::cam {

/// "Ran, but nothing usable": no image showed the board, the board was not in view.
using cli::kExitNothingUsable;

/// The code main returns when no error was thrown: 0 unless a command set one.
int ExitCode();
void SetExitCode(int code);

}  // namespace h4::cam
