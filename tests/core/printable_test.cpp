// printable(): control characters and invalid UTF-8 in outside text are shown as escapes,
// printable text (UTF-8 included) is kept, and a second pass changes nothing.
#include <gtest/gtest.h>

#include <string>

#include "core/printable.hpp"

namespace armctl {
namespace {

TEST(Printable, TerminalEscapeSequencesAreShownNotSent) {
  EXPECT_EQ(printable("\x1b]0;owned\x07"), "\\x1b]0;owned\\x07");
  EXPECT_EQ(printable("\x1b[2J"), "\\x1b[2J");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("\x7f"), "\\x7f");
  EXPECT_EQ(printable("line\nnext\r\ttab"), "line\\nnext\\r\\ttab");
}

TEST(Printable, C1ControlsAndInvalidUtf8AreEscaped) {
  EXPECT_EQ(printable("\xc2\x9b" "2J"), "\\xc2\\x9b2J");   // U+009B, CSI for some terminals
  EXPECT_EQ(printable("\xff\xfe"), "\\xff\\xfe");          // never valid in UTF-8
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");          // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xe2\x82"), "\\xe2\\x82");          // cut short
  EXPECT_EQ(printable("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
}

TEST(Printable, PrintableTextIsKept) {
  const std::string text = "servo 3: 30\xc2\xb0 caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\xa4\x96 C:\\path 'x'";
  EXPECT_EQ(printable(text), text);
  EXPECT_EQ(printable(""), "");
}

TEST(Printable, IsIdempotent) {
  for (const std::string text : {"\x1b]0;x\x07", "\xff\n", "a\\x1b", "\xc2\x85 ok"}) {
    EXPECT_EQ(printable(printable(text)), printable(text)) << text;
  }
}

}  // namespace
}  // namespace armctl
