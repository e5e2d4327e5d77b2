// The poses CSV (common/formats/README.md): `pose_id,X,Y,Z,theta`, end-effector poses X_BE in the
// base frame (m, rad), input of `h4cal ik`; and the fk output
// `pose_id,X,Y,Z,theta,x,y,z,qw,qx,qy,qz`: the end-effector pose and the board pose
// X_CT = inv(X_BC) * X_BE * inv(X_TE) it implies.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry/rigid_transform.h"

namespace h4 {

struct EndEffectorPoseRow {
  int64_t pose_id = 0;
  double X = 0.0, Y = 0.0, Z = 0.0;  ///< translation of X_BE, m
  double theta = 0.0;                ///< rotation of X_BE about z_B, rad
};

struct FkRow {
  EndEffectorPoseRow pose;  ///< X_BE from forward kinematics
  RigidTransform X_CT;      ///< board pose in the camera frame it implies
};

/// No end-effector position read from a file is farther than this from the base (m).
inline constexpr double kMaxEndEffectorPosition_m = 10.0;

/// Poses CSV; throws FormatError naming file, line and field on a missing column or
/// field, a non-number, a duplicate pose_id, |X|, |Y| or |Z| above
/// kMaxEndEffectorPosition_m, or |theta| above pi (degrees given by mistake).
std::vector<EndEffectorPoseRow> ParsePosesCsv(const std::string& text,
                                              const std::string& source_name);
std::vector<EndEffectorPoseRow> ReadPosesCsv(const std::string& path);
std::string FormatPosesCsv(const std::vector<EndEffectorPoseRow>& rows);
void WritePosesCsv(const std::string& path, const std::vector<EndEffectorPoseRow>& rows);

/// fk output; the reader also checks the quaternion (norm 1 within 1e-3).
std::vector<FkRow> ParseFkCsv(const std::string& text, const std::string& source_name);
std::vector<FkRow> ReadFkCsv(const std::string& path);
std::string FormatFkCsv(const std::vector<FkRow>& rows);
void WriteFkCsv(const std::string& path, const std::vector<FkRow>& rows);

}  // namespace h4
