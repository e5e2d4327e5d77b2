// Markup escaping: every special character becomes its entity, the rest is kept.
#include "common/text/markup_escape.h"

#include <gtest/gtest.h>

namespace h4 {
namespace {

TEST(MarkupEscape, EscapesTheFourSpecialCharacters) {
  EXPECT_EQ(MarkupEscape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
  EXPECT_EQ(MarkupEscape("tag 30.0 mm, 6x6"), "tag 30.0 mm, 6x6");
  EXPECT_EQ(MarkupEscape(""), "");
}

// Issue 42 point 18: a file name that is a scheme ("javascript:...") must not become one.
TEST(RelativeFileUrl, StartsWithDotSlashAndPercentEncodesAllButUnreservedCharacters) {
  EXPECT_EQ(RelativeFileUrl("camera-coverage.svg"), "./camera-coverage.svg");
  EXPECT_EQ(RelativeFileUrl("javascript:alert(document.domain);x.yaml"),
            "./javascript%3Aalert%28document.domain%29%3Bx.yaml");
  EXPECT_EQ(RelativeFileUrl("a b\"<>&#?%.svg"), "./a%20b%22%3C%3E%26%23%3F%25.svg");
  EXPECT_EQ(RelativeFileUrl("dir/f~_-.txt"), "./dir/f~_-.txt");
  EXPECT_EQ(RelativeFileUrl("\xC3\xA9.yaml"), "./%C3%A9.yaml");
}

}  // namespace
}  // namespace h4
