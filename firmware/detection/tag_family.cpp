// AprilTag family lookup, wide-border variants and tag bit patterns; see tag_family.h.
#include "firmware/detection/tag_family.h"

#include <cstdlib>
#include <vector>

#include <apriltag/apriltag.h>
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h11.h>

namespace h4::cam {
namespace {

TagFamilyPtr CreatePlainFamily(const std::string& name) {
  if (name == "tag36h11") return TagFamilyPtr(tag36h11_create(), tag36h11_destroy);
  if (name == "tag25h9") return TagFamilyPtr(tag25h9_create(), tag25h9_destroy);
  if (name == "tag16h5") return TagFamilyPtr(tag16h5_create(), tag16h5_destroy);
  return nullptr;
}

// A shallow copy of `plain` that shares its codes and name (kept alive by the deleter) and
// owns bit positions shifted inwards by `extra` cells.
TagFamilyPtr WidenBorder(const TagFamilyPtr& plain, int extra) {
  auto* wide = static_cast<apriltag_family*>(std::calloc(1, sizeof(apriltag_family)));
  *wide = *plain;
  wide->impl = nullptr;  // the detector fills its own decode table
  wide->width_at_border = plain->width_at_border + 2 * extra;
  wide->total_width = plain->total_width + 2 * extra;
  wide->bit_x = static_cast<uint32_t*>(std::calloc(plain->nbits, sizeof(uint32_t)));
  wide->bit_y = static_cast<uint32_t*>(std::calloc(plain->nbits, sizeof(uint32_t)));
  for (uint32_t i = 0; i < plain->nbits; ++i) {
    wide->bit_x[i] = plain->bit_x[i] + static_cast<uint32_t>(extra);
    wide->bit_y[i] = plain->bit_y[i] + static_cast<uint32_t>(extra);
  }
  return TagFamilyPtr(wide, [plain](apriltag_family* family) {
    std::free(family->bit_x);
    std::free(family->bit_y);
    std::free(family);
  });
}

}  // namespace

TagFamilyPtr CreateTagFamily(const std::string& name, int border_cells) {
  if (border_cells < 1 || border_cells > kMaxBorderCells) return nullptr;
  TagFamilyPtr plain = CreatePlainFamily(name);
  if (!plain || border_cells == 1) return plain;
  return WidenBorder(plain, border_cells - 1);
}

std::vector<bool> TagCells(const apriltag_family& family, int id, int border_cells, int* width) {
  const int extra = border_cells - 1;
  *width = family.width_at_border + 2 * extra;
  if (id < 0 || static_cast<uint32_t>(id) >= family.ncodes || extra < 0) return {};
  // libapriltag's own rendering (white quiet zone of one cell around the black border),
  // so the bit layout is exactly the one its decoder expects; a wider border adds black
  // cells outside it.
  image_u8_t* im = apriltag_to_image(const_cast<apriltag_family*>(&family), id);
  const int start = (family.total_width - family.width_at_border) / 2;
  std::vector<bool> cells(static_cast<size_t>(*width * *width), false);
  for (int y = 0; y < family.width_at_border; ++y) {
    for (int x = 0; x < family.width_at_border; ++x) {
      cells[static_cast<size_t>((y + extra) * *width + x + extra)] =
          im->buf[(y + start) * im->stride + x + start] > 127;
    }
  }
  // image_u8_destroy is not exported by Debian's libapriltag; it frees exactly these.
  std::free(im->buf);
  std::free(im);
  return cells;
}

}  // namespace h4::cam
