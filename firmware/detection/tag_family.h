// AprilTag families by name (board YAML's tagFamily), owned by a smart pointer so the
// detector and the renderer free them with the matching libapriltag destructor; and the
// same families for tags printed with a wider black border (Kalibr's aprilgrid: 2 cells),
// which libapriltag's decoder reads once its bit positions are measured from that border.
#pragma once

#include <memory>
#include <string>
#include <vector>

struct apriltag_family;

namespace h4::cam {

using TagFamilyPtr = std::shared_ptr<apriltag_family>;

/// Widest black border supported, in cells.
inline constexpr int kMaxBorderCells = 3;

/// The family called `name` ("tag36h11", "tag25h9", "tag16h5") for tags whose black border
/// is `border_cells` wide (1: libapriltag's own tags; 2: Kalibr's), or nullptr for a family
/// this program does not support (families with a reversed border are not supported:
/// their tag size is not the outer black border) or a border outside 1..kMaxBorderCells.
/// With a wider border, width_at_border and total_width grow by 2 (border_cells - 1) and
/// every data bit moves inwards by border_cells - 1: the decoder (libapriltag's
/// quad_decode) samples bit (bit_x + 0.5) / width_at_border across the quad.
TagFamilyPtr CreateTagFamily(const std::string& name, int border_cells = 1);

/// Tag cells of tag `id` printed with a black border `border_cells` wide: width x width
/// values in row-major order (row = y down), true = white, covering the tag up to the outer
/// edge of its black border. Empty when the id is out of the family's range. `family` is
/// the plain family (CreateTagFamily(name), border 1).
std::vector<bool> TagCells(const apriltag_family& family, int id, int border_cells, int* width);

}  // namespace h4::cam
