// Filling the IdentificationResult of an identification (formats.md): parameters with a
// priori values, standard deviations and status, fixed parameters with reasons, joint
// residuals, held-out board pose error, covariance figures and the log.
#pragma once

#include <cstdint>
#include <vector>

#include "host/identification/identification.h"

namespace h4::host {

/// Fills out->result and out->uncertainty for the final parameters `p` (with their mask),
/// `calib` the poses used (rejected ones removed), `valid` the held-out poses.
void FillResult(const KinematicModel& model, const ParameterVector& apriori,
                const ParameterVector& p, const std::vector<DatasetRow>& calib,
                const std::vector<DatasetRow>& valid, const std::vector<int64_t>& rejected,
                const IdentificationOptions& options, IdentificationOutcome* out);

}  // namespace h4::host
