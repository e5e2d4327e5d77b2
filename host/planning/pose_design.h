// D-optimal choice of calibration poses: N poses out of a candidate set that maximise
// log det of the information matrix of the measurement-space identification
// (information_model.h), by a DETMAX-style exchange (Mitchell 1974; Fedorov's exchange
// restricted to add-one / drop-one steps): from a seeded random start, add the candidate
// that raises log det most, drop the design pose whose loss is least, and stop when the
// pose dropped is the one just added.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/planning/information_model.h"

namespace h4::host {

struct DesignOptions {
  int pose_count = 25;  ///< N, the poses to choose
  uint64_t seed = 1;    ///< the random start; the same seed gives the same design
  /// Exchanges before giving up on convergence (each is one add and one drop).
  int max_exchanges = 2000;
  /// Added to M's diagonal, relative to the mean diagonal of all the candidates'
  /// information, so that a start with fewer rows than parameters has a determinant; the
  /// final log det is reported without it.
  double ridge = 1e-9;
  /// Exchanges run from this many seeded random starts (seed, seed + 1, ...); the planner
  /// keeps the best design by its criterion (pose_planner.h). The exchange stops at a local
  /// optimum, which depends on the start.
  int restarts = 1;
  /// Poses measured already (indices into the information model, none a candidate): their
  /// information is in every matrix of the exchange, and the pose_count new poses complete
  /// them (the sequential campaign: plan the rest once the first batch is identified).
  std::vector<int> existing;

  bool IsValid(std::string* why) const;
};

struct Design {
  std::vector<int> chosen;  ///< indices into the candidates, ascending
  double log_det = 0.0;     ///< log det of M (scaled units); -inf when singular
  int exchanges = 0;
  bool converged = false;  ///< stopped because no exchange improved log det
};

/// Chooses options.pose_count of the poses [0, candidate_count) of `info`. Throws
/// std::invalid_argument when the options are invalid or ask for more poses than candidates.
Design PlanDOptimal(const InformationModel& info, int candidate_count,
                    const DesignOptions& options);

/// The same exchange for the predicted accuracy instead (I-optimality): from the D-optimal
/// design, minimise trace(A M^-1) with A the sum of T_j^T T_j over the translation rows of
/// the poses `evaluated`, i.e. the mean predicted board position variance over them
/// (information_model.h, PredictedPositionRms).
Design PlanForAccuracy(const InformationModel& info, int candidate_count,
                       const std::vector<int>& evaluated, const DesignOptions& options);

/// Bayesian I-optimality: the same exchange for the mean of trace(A_k M_k^-1) over `models`,
/// one per robot drawn from the a priori uncertainty (the same poses, each at its own
/// robot's Jacobian), from the D-optimal design of the first. A design good for the a priori
/// alone may lean on directions another robot of the prior does not give (Chaloner and
/// Verdinelli 1995, Bayesian experimental design, section 2.3: the expected utility over the
/// prior). One model: PlanForAccuracy.
Design PlanForMeanAccuracy(const std::vector<const InformationModel*>& models, int candidate_count,
                           const std::vector<int>& evaluated, const DesignOptions& options);

/// n distinct indices of [0, count) drawn with the seed, in draw order (n <= count).
std::vector<int> SeededSubset(int count, int n, uint64_t seed);

/// log det of a symmetric positive (semi)definite matrix; -inf when it is not positive.
double LogDet(const Eigen::MatrixXd& M);

}  // namespace h4::host
