// k-fold cross-validation of an identification: the poses in the fit are dealt into k
// folds; each fold is predicted by the model fitted without it (the estimator's cost,
// Levenberg-Marquardt warm-started from the fit on every pose, the same parameters fixed),
// so every pose gets a held-out prediction while the final fit keeps every pose. Each
// held-out pose is scored by its board pose error and by its measurement residual
// normalised by the pose's covariance (its chi-square, 6 degrees of freedom when the
// sigmas are right).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/identification/identification_cost.h"
#include "host/identification/least_squares.h"
#include "host/identification/parameter_vector.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct CrossValidationOptions {
  /// Folds (2 or more; `h4cal identify --folds K`); 0 turns cross-validation off. With
  /// fewer poses than folds every pose is its own fold (leave-one-out).
  int folds = 10;
  /// Seed of the deal of poses into folds.
  uint64_t seed = 1;

  bool IsValid(std::string* why) const;
};

/// One pose predicted by the model fitted without its fold.
struct HeldOutPrediction {
  int64_t pose_id = 0;
  bool ok = false;                ///< false: the fold's model cannot predict it (FK fails)
  double position_error_m = 0.0;  ///< board position, predicted vs measured
  double rotation_error_rad = 0.0;
  double chi2 = 0.0;  ///< of its normalised residual against I + J C_fold J^T (6 dof)
};

struct CrossValidation {
  int folds = 0;                         ///< 0: not run
  std::vector<HeldOutPrediction> poses;  ///< in the order of the rows given
  double position_rms_m = 0.0;           ///< over the poses predicted
  double rotation_rms_rad = 0.0;
  double reduced_chi2 = 0.0;  ///< sum of chi2 / (6 * poses predicted)
  int failed_folds = 0;       ///< folds whose fit did not converge (their poses still scored)
  double seconds = 0.0;
};

/// What a cross-validation needs from the identification.
struct CrossValidationInputs {
  const KinematicModel& model;
  const ParameterVector& fit;  ///< the fit on every row, with its mask
  const std::vector<DatasetRow>& rows;
  CostKind estimator = CostKind::kMeasurement;
  const CostOptions& cost;
  const LmOptions& lm;
};

CrossValidation CrossValidate(const CrossValidationInputs& inputs,
                              const CrossValidationOptions& options);

}  // namespace h4::host
