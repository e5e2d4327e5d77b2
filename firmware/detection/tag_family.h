// AprilTag families by name (board YAML's tagFamily), owned by a smart pointer so the
// detector and the renderer free them with the matching libapriltag destructor.
#pragma once

#include <memory>
#include <string>
#include <vector>

struct apriltag_family;

namespace h4::cam {

using TagFamilyPtr = std::shared_ptr<apriltag_family>;

/// The family called `name` ("tag36h11", "tag25h9", "tag16h5"), or nullptr for a family
/// this program does not support (families with a reversed border are not supported:
/// their tag size is not the outer black border).
TagFamilyPtr CreateTagFamily(const std::string& name);

/// Tag cells of tag `id`: width x width values in row-major order (row = y down),
/// true = white, covering the tag up to the outer edge of its black border. Empty when
/// the id is out of the family's range.
std::vector<bool> TagCells(const apriltag_family& family, int id, int* width);

}  // namespace h4::cam
