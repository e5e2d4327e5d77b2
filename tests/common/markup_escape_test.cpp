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

}  // namespace
}  // namespace h4
