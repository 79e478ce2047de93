// Config documents: too large, too deep, not a regular file — refused before they cost time
// or memory, with the source named.
#include <gtest/gtest.h>

#include <string>

#include "core/json_reader.hpp"

namespace armctl {
namespace {

TEST(ConfigDocument, DeepNestingIsRefusedAtOnce) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  try {
    (void)json_reader::parse_document(deep, "deep.json");
    FAIL() << "accepted";
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    EXPECT_NE(std::string(e.what()).find("deep.json: nested deeper than 32 levels"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW((void)json_reader::parse_document("{\"a\": [[[1]]]}", "ok.json"));
}

TEST(ConfigDocument, LargeTextAndNonFilesAreRefused) {
  EXPECT_THROW((void)json_reader::parse_document(std::string(2 << 20, ' '), "big.json"), ArmctlError);
  try {
    (void)json_reader::read_config_file(ARMCTL_SOURCE_DIR, "arm config");
    FAIL() << "a directory was read";
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)json_reader::read_config_file("/nonexistent/x.json", "arm config"), ArmctlError);
}

TEST(ConfigDocument, AKeyHoldingATerminalEscapeIsShownEscaped) {
  // "\u001b" in JSON is a real ESC in the key: the message must not carry it to a terminal.
  const auto doc = json_reader::parse_document("{\"\\u001b]0;owned\\u0007\": 1}", "arm.json");
  try {
    json_reader::ObjectReader reader("arm.json", doc, "");
    reader.finish();
    FAIL() << "unknown key accepted";
  } catch (const ArmctlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("arm.json: \\x1b]0;owned\\x07: unknown key"), std::string::npos) << message;
    EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace armctl
