// The board detector's second look for the tags of an AprilTag grid that libapriltag's quad
// search missed (fisheye-bent tags, small ones): predicted through the camera model from
// the pose of the found ones, verified by their code, refined as found tags are
// (tag_prediction.h, board_detector.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "firmware/detection/board_detector.h"

namespace h4::cam {

void BoardDetector::RecoverMissedTags(const cv::Mat& image32,
                                      std::vector<std::optional<RefinedTag>>* best,
                                      BoardDetection* detection) const {
  if (!options_.prediction.enabled || !code_reader_ || !code_reader_->ok()) return;
  if (std::all_of(best->begin(), best->end(), [](const auto& tag) { return tag.has_value(); })) {
    return;  // every tag found: nothing to predict (the legacy board's usual case, no cost)
  }
  // A second round from the pose refitted with the recovered tags reaches tags the first,
  // fitted to a corner of the board, placed too loosely.
  std::vector<MissedTag> missed;
  for (int round = 0; round < 2; ++round) {
    RigidTransform X_CT;
    if (!FitPoseToFoundTags(*best, &X_CT)) return;
    missed.clear();
    const int recovered = PredictMissingTags(image32, X_CT, best, &missed);
    detection->tags_predicted += recovered;
    if (recovered == 0) break;
  }
  detection->missed = std::move(missed);
}

bool BoardDetector::FitPoseToFoundTags(const std::vector<std::optional<RefinedTag>>& best,
                                       RigidTransform* X_CT) const {
  std::vector<size_t> used;
  for (size_t index = 0; index < best.size(); ++index) {
    if (best[index]) used.push_back(index);
  }
  const size_t min_tags = static_cast<size_t>(std::max(options_.prediction.min_tags, 1));
  while (used.size() >= min_tags) {
    std::vector<CornerObservation> corners;
    for (size_t index : used) {
      for (size_t k = 0; k < 4; ++k) {
        if (!best[index]->refined[k]) continue;
        CornerObservation corner;
        corner.p_TQ = board_.corners()[index * 4 + k];
        corner.uv = best[index]->corners_px[k];
        corners.push_back(corner);
      }
    }
    double rms_px = 0;
    if (!FitPoseToCorners(corners, camera_, X_CT, &rms_px)) return false;
    // The tag that agrees least with the pose: a misplaced detection drags the fit.
    double worst_rms = 0;
    size_t worst = 0;
    for (size_t u = 0; u < used.size(); ++u) {
      double sum = 0;
      int count = 0;
      for (size_t k = 0; k < 4; ++k) {
        Eigen::Vector2d uv;
        if (!best[used[u]]->refined[k]) continue;
        if (!camera_.ProjectRay(*X_CT * board_.corners()[used[u] * 4 + k], &uv)) continue;
        sum += (uv - best[used[u]]->corners_px[k]).squaredNorm();
        ++count;
      }
      const double rms = count > 0 ? std::sqrt(sum / count) : 0;
      if (rms > worst_rms) worst_rms = rms;
      if (rms >= worst_rms) worst = u;
    }
    if (worst_rms <= options_.prediction.max_tag_rms_px) return true;
    used.erase(used.begin() + static_cast<long>(worst));
  }
  return false;
}

int BoardDetector::PredictMissingTags(const cv::Mat& image32, const RigidTransform& X_CT,
                                      std::vector<std::optional<RefinedTag>>* best,
                                      std::vector<MissedTag>* missed) const {
  const TagPredictionOptions& options = options_.prediction;
  const int first_id = std::get<AprilGridSpec>(board_.spec()).first_id;
  int recovered = 0;
  for (size_t index = 0; index < best->size(); ++index) {
    if ((*best)[index]) continue;
    const int tag_index = static_cast<int>(index);
    MissedTag miss;
    miss.tag_id = first_id + tag_index;
    if (!PredictTagCorners(board_, camera_, X_CT, tag_index, options.image_margin_px,
                           &miss.corners_px)) {
      continue;  // not wholly in the image: not expected
    }
    const TagCodeReading reading = code_reader_->Read(image32, camera_, X_CT, tag_index);
    miss.code_errors = reading.code_errors;
    if (reading.contrast < options.min_contrast) {
      miss.why = TagMiss::kNotFound;
    } else if (reading.code_errors > options.max_code_errors ||
               reading.border_errors > options.max_border_errors) {
      miss.why = TagMiss::kFailedCode;
    } else {
      TagDetection tag;
      tag.id = miss.tag_id;
      tag.corners_px = miss.corners_px;
      (*best)[index] = RefineTag(image32, &tag);
      if ((*best)[index]) {
        ++recovered;
        continue;
      }
      miss.why = TagMiss::kFailedRefinement;
    }
    missed->push_back(miss);
  }
  return recovered;
}

}  // namespace h4::cam
