// What `identify` prints of an identification, shared by every command that identifies
// (`identify`, `collect --report-dir`): the verdict first (what the technician acts on),
// then the figures that decided it.
#pragma once

#include "host/identification/identification.h"
#include "host/validation/validation.h"

namespace h4::host::cli {

/// The verdict, the convergence, the poses (and the rejected ones with their reasons), the
/// fixed parameters, the residuals, the held-out figures and the predictions, to stdout.
void PrintHeadline(const IdentificationOutcome& outcome);

/// The accuracy map written with a report, in one line (README.md#using-h4cal).
void PrintAccuracyMapLine(const ModelValidation& identified);

}  // namespace h4::host::cli
