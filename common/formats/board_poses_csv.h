// The offline board poses CSV written by `h4cam measure --out` (common/formats/README.md):
//   image,x,y,z,qw,qx,qy,qz,corners,rms_px,sigma_t,sigma_r
// One row per measurement; an image with no board gives a row with empty pose fields.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/geometry/rigid_transform.h"

namespace h4 {

struct BoardPoseRow {
  std::string image;                   ///< image file (the first of an averaged group)
  std::optional<RigidTransform> X_CT;  ///< board in camera; empty when no board was found
  int corners = 0;                     ///< board corners used by the fit
  std::optional<double> rms_px;        ///< reprojection RMS, px (required with a pose)
  std::optional<double> sigma_t;       ///< one-sigma translation precision, m
  std::optional<double> sigma_r;       ///< one-sigma rotation precision, rad
};

/// Reads the CSV; throws FormatError naming file, line and field on a missing column,
/// an empty image name, a pose with some fields empty and others not, a non-unit
/// quaternion, a negative corner count or RMS, a non-positive sigma, or a pose row
/// without rms_px.
std::vector<BoardPoseRow> ParseBoardPosesCsv(const std::string& text,
                                             const std::string& source_name);
std::vector<BoardPoseRow> ReadBoardPosesCsv(const std::string& path);

/// Header and rows; absent values are written as empty fields.
std::string FormatBoardPosesCsv(const std::vector<BoardPoseRow>& rows);
void WriteBoardPosesCsv(const std::string& path, const std::vector<BoardPoseRow>& rows);

}  // namespace h4
