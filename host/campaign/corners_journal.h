// The campaign's board corners (issue 25: corners travel with the pose), appended durably
// beside the dataset: for each recorded pose whose camera sent them (board_corners_t), the
// refined corners as rows of the board-corner CSV (common/formats/README.md#board-corners-csv), all
// rows of a pose in one write(2) and one fsync(2), as the dataset's rows are (dataset_journal.h).
// On open, an existing file is read back (a last line cut by a crash is dropped): the poses it
// holds are not appended again, so a resumed campaign writes each pose's corners once. Locked like
// the dataset while open.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "common/formats/corners_csv.h"
#include "host/campaign/dataset_journal.h"
#include "host/campaign/journal_file.h"

namespace h4::host {

class CornersJournal {
 public:
  /// Opens (creating it with the header when absent or empty) `path`. An existing file must
  /// have the campaign's columns (pose_id,tag_id,corner,u,v,sigma_px) and parse; throws
  /// FormatError or std::runtime_error naming the file otherwise, or when it is locked.
  explicit CornersJournal(std::string path, JournalFileOps ops = {});

  const std::string& path() const { return file_.path(); }
  bool Contains(int64_t pose_id) const { return pose_ids_.count(pose_id) != 0; }
  /// Poses whose corners were in the file when it was opened, plus those appended since.
  size_t pose_count() const { return pose_ids_.size(); }
  const std::set<int64_t>& pose_ids() const { return pose_ids_; }

  /// Appends the corners of one pose (every row's pose_id the same, not yet in the file)
  /// and flushes them to the disk; throws std::invalid_argument for an empty list, mixed or
  /// recorded pose ids, and std::runtime_error (file cut back to its complete poses) when
  /// the disk refuses.
  void Append(const std::vector<CornerObservation>& corners);

 private:
  void Load();

  JournalFile file_;
  std::set<int64_t> pose_ids_;
};

/// Makes a resumed campaign's dataset and corners agree, before the campaign starts (issue 42,
/// defects 6 and 10). A pose's row is written first, then its corners: corners of a pose
/// without a row are another campaign's (an old STEM.corners.csv beside a new dataset kept its
/// pixels for the new poses): refused with std::runtime_error naming the file and the poses,
/// nothing touched. Rows at the end of the dataset without corners, when the camera sends
/// corners (an earlier row has them), are what a crash between a row and its corners left:
/// cut off the dataset with a warning naming them, so the campaign measures them again (the
/// summary said "12 of 12 planned poses, corners of 9 poses"). Other rows without corners
/// (the camera sent none, or they were lost on the bus) are named in a warning. Returns the
/// pose ids cut.
std::vector<int64_t> ReconcileWithDataset(DatasetJournal& dataset, const CornersJournal& corners);

/// The corners file beside `dataset_path`: its stem + ".corners.csv" in the same directory
/// (`runs/day1.csv` -> `runs/day1.corners.csv`), the default of `h4cal collect --corners-out`.
std::string CornersPathBeside(const std::string& dataset_path);

}  // namespace h4::host
