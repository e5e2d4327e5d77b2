// The last step of an identification: the IdentificationResult of the final parameters
// (common/formats/README.md), in the order a reader checks a solution: covariance and
// identifiability at the solution, the position accuracy the covariance predicts, one row
// per parameter (a priori, value, one sigma, fixed and why), joint residuals and the
// held-out board pose error, the pose lists.
#pragma once

#include <cstdint>
#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/identification/identification.h"
#include "host/identification/identification_stage.h"

namespace h4::host {

/// The final parameters to summarise and where they come from.
struct SolutionToSummarise {
  const KinematicModel& model;
  const ParameterVector& apriori;        ///< reported beside each value
  const ParameterVector& p;              ///< the final values with their mask
  const std::vector<DatasetRow>& calib;  ///< the poses used (rejected ones removed)
  const std::vector<DatasetRow>& valid;  ///< the held-out poses
  const std::vector<int64_t>& rejected;
  const IdentificationOptions& options;
  /// The estimator's cost at p on exactly `calib`; null: evaluated here.
  const SolutionJacobian* at_solution = nullptr;
};

/// Fills out->result and out->uncertainty.
void SummariseSolution(const SolutionToSummarise& solution, IdentificationOutcome* out);

}  // namespace h4::host
