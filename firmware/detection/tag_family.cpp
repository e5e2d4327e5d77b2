// AprilTag family lookup and tag bit patterns; see tag_family.h.
#include "firmware/detection/tag_family.h"

#include <cstdlib>
#include <vector>

#include <apriltag/apriltag.h>
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h11.h>

namespace h4::cam {

TagFamilyPtr CreateTagFamily(const std::string& name) {
  if (name == "tag36h11") return TagFamilyPtr(tag36h11_create(), tag36h11_destroy);
  if (name == "tag25h9") return TagFamilyPtr(tag25h9_create(), tag25h9_destroy);
  if (name == "tag16h5") return TagFamilyPtr(tag16h5_create(), tag16h5_destroy);
  return nullptr;
}

std::vector<bool> TagCells(const apriltag_family& family, int id, int* width) {
  *width = family.width_at_border;
  if (id < 0 || static_cast<uint32_t>(id) >= family.ncodes) return {};
  // libapriltag's own rendering (white quiet zone of one cell around the black border),
  // so the bit layout is exactly the one its decoder expects.
  image_u8_t* im = apriltag_to_image(const_cast<apriltag_family*>(&family), id);
  const int start = (family.total_width - family.width_at_border) / 2;
  std::vector<bool> cells(static_cast<size_t>(*width * *width));
  for (int y = 0; y < *width; ++y) {
    for (int x = 0; x < *width; ++x) {
      cells[static_cast<size_t>(y * *width + x)] =
          im->buf[(y + start) * im->stride + x + start] > 127;
    }
  }
  // image_u8_destroy is not exported by Debian's libapriltag; it frees exactly these.
  std::free(im->buf);
  std::free(im);
  return cells;
}

}  // namespace h4::cam
