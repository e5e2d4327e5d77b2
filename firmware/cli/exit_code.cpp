// The exit code of an h4cam run; see exit_code.h.
#include "firmware/cli/exit_code.h"

namespace h4::cam {
namespace {
int g_exit_code = 0;
}  // namespace

int ExitCode() { return g_exit_code; }
void SetExitCode(int code) { g_exit_code = code; }

}  // namespace h4::cam
