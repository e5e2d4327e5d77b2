// The campaign's dataset file, appended durably (issue "Live system", item 3): each row is
// written with one write(2) and fsync(2)ed before the campaign moves on, so a crash or a
// kill loses at most the pose in flight and never leaves a half row behind that a restart
// would misread; a write or fsync that fails (a full disk) cuts the file back to its last
// complete row and stops the campaign with the reason. On open, an existing file is read
// back: its pose ids are the poses the restarted campaign skips, so every pose ends up in
// the file exactly once. The file is locked (flock, exclusive) while the journal is open:
// a second campaign on the same file is refused instead of interleaving its rows.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "host/campaign/journal_file.h"
#include "host/formats/dataset_csv.h"

namespace h4::host {

class DatasetJournal {
 public:
  /// Opens (creating it with the header when absent or empty) `path`. An existing file must
  /// have the campaign's columns (common/formats/README.md's dataset with sigma_t, sigma_r) and
  /// parse; a last line cut by a crash (no newline) is removed with a warning. Throws FormatError
  /// or std::runtime_error naming the file on anything else, including when another
  /// process holds the file (its pid named when /proc/locks tells it).
  /// `ops`: the write and fsync calls (the system's unless a test injects faults).
  explicit DatasetJournal(std::string path, JournalFileOps ops = {});

  const std::string& path() const { return file_.path(); }
  /// Rows already in the file when it was opened, plus those appended since.
  const std::vector<DatasetRow>& rows() const { return rows_; }
  bool Contains(int64_t pose_id) const { return pose_ids_.count(pose_id) != 0; }
  /// Rows found in the file when it was opened (a resumed campaign).
  size_t resumed_count() const { return resumed_count_; }

  /// Appends one row and flushes it to the disk; throws std::runtime_error (naming the file
  /// and the system error) when it cannot, leaving the file with its complete rows only,
  /// and std::invalid_argument for a pose id already in the file or a row the dataset
  /// reader would refuse (nothing is written then).
  void Append(const DatasetRow& row);

  /// Cuts the last `count` rows off the file (durably) and forgets them, so that a resumed
  /// campaign measures those poses again: the rows whose corners an interrupted run lost
  /// (corners_journal.h ReconcileWithDataset). Throws std::runtime_error naming the file
  /// when it cannot; std::invalid_argument for more rows than the file holds.
  void DropLastRows(size_t count);

 private:
  /// Reads the file back (dropping a cut last line), or writes the header of a new one.
  void Load();

  JournalFile file_;
  std::vector<DatasetRow> rows_;
  std::set<int64_t> pose_ids_;
  size_t resumed_count_ = 0;
};

}  // namespace h4::host
