// The error contract's rule, enforced (docs/architecture.md "Errors"): no code outside
// src/core decides anything from an error's message text. Meaning travels in the ErrorKind
// and the typed detail; a message is for people. This scans src/ (C++ and Python) for code
// that inspects a message: find/rfind/starts_with/ends_with/contains/compare on it, a
// comparison with == or !=, a regex over it, or the same on a variable that holds it.
// Building a message (prefixing, formatting, substr of one's own text) is not flagged.
//
// ARMCTL_ERROR_TEXT_ROOT scans another tree instead of this one's src/ (to show that the
// rule catches the code it replaced: point it at an older checkout's src/).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

enum class Language { cpp, python };

// The text with comments and the contents of string and character literals blanked (kept as
// spaces, newlines kept), so that a message's words or a comment about the rule never match.
std::string code_only(const std::string& text, Language language) {
  std::string out = text;
  std::size_t i = 0;
  auto blank = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to && k < out.size(); ++k)
      if (out[k] != '\n') out[k] = ' ';
  };
  while (i < text.size()) {
    const char c = text[i];
    if (language == Language::cpp && c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      const std::size_t end = text.find('\n', i);
      blank(i, end == std::string::npos ? text.size() : end);
      i = end == std::string::npos ? text.size() : end;
    } else if (language == Language::cpp && c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const std::size_t end = text.find("*/", i + 2);
      const std::size_t stop = end == std::string::npos ? text.size() : end + 2;
      blank(i, stop);
      i = stop;
    } else if (language == Language::python && c == '#') {
      const std::size_t end = text.find('\n', i);
      blank(i, end == std::string::npos ? text.size() : end);
      i = end == std::string::npos ? text.size() : end;
    } else if (language == Language::cpp && c == 'R' && i + 1 < text.size() && text[i + 1] == '"' &&
               (i == 0 || !(std::isalnum(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '_'))) {
      const std::size_t open = text.find('(', i + 2);
      if (open == std::string::npos) break;
      const std::string close = ")" + text.substr(i + 2, open - i - 2) + "\"";
      const std::size_t end = text.find(close, open);
      const std::size_t stop = end == std::string::npos ? text.size() : end + close.size();
      blank(i + 2, stop - 1);
      i = stop;
    } else if (c == '"' || c == '\'') {
      std::size_t k = i + 1;
      while (k < text.size() && text[k] != c && text[k] != '\n') k += text[k] == '\\' ? 2 : 1;
      blank(i + 1, k);
      i = k + 1;
    } else {
      ++i;
    }
  }
  return out;
}

struct Finding {
  std::string file;
  std::size_t line;
  std::string code;
};

std::size_t line_of(const std::string& text, std::size_t at) {
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

std::string line_text(const std::string& text, std::size_t at) {
  const std::size_t from = text.rfind('\n', at) == std::string::npos ? 0 : text.rfind('\n', at) + 1;
  const std::size_t to = text.find('\n', at);
  return text.substr(from, (to == std::string::npos ? text.size() : to) - from);
}

// Where `source` (one file's text) decides from an error's message.
std::vector<std::size_t> inspections(const std::string& source, Language language) {
  const std::string code = code_only(source, language);
  std::vector<std::size_t> at;
  auto add_all = [&](const std::regex& re) {
    for (auto it = std::sregex_iterator(code.begin(), code.end(), re); it != std::sregex_iterator(); ++it)
      at.push_back(static_cast<std::size_t>(it->position(0)));
  };
  if (language == Language::cpp) {
    // The text of an error: `.message`, a variable or parameter named `message`, `what()`.
    const std::string text = R"((?:\bmessage\b|\bwhat\s*\(\s*\)))";
    const std::string inspect =
        R"(\s*\.\s*(?:find|rfind|starts_with|ends_with|contains|compare|find_first_of|find_last_of|find_first_not_of)\s*\()";
    add_all(std::regex(text + R"(\s*\)?)" + inspect));  // also std::string(e.what()).find(
    add_all(std::regex(text + R"(\s*\)?\s*[!=]=)"));
    add_all(std::regex(R"([!=]=\s*[\w.\->()\[\]]*)" + text));
    add_all(std::regex(R"(regex_(?:search|match)\s*\([^;]*)" + text));
    // A variable holding a message (`std::string m = e.message;`), then inspected.
    const std::regex alias(R"((?:std::string(?:_view)?|auto)\s*(?:const\s*)?&?\s*(\w+)\s*(?:=|\{|\()\s*[\w.\->()\[\]]*?)" +
                           text + R"(\s*[;})])");
    std::set<std::string> names;
    for (auto it = std::sregex_iterator(code.begin(), code.end(), alias); it != std::sregex_iterator(); ++it)
      names.insert((*it)[1].str());
    for (const std::string& name : names) {
      if (name == "message") continue;  // already covered
      add_all(std::regex(R"(\b)" + name + inspect));
      add_all(std::regex(R"(\b)" + name + R"(\s*[!=]=)"));
      add_all(std::regex(R"(regex_(?:search|match)\s*\(\s*)" + name + R"(\b)"));
    }
  } else {
    // Python: str(e) / e.message / e.args[0] searched, compared or matched.
    const std::string text = R"((?:\bstr\s*\(\s*\w+\s*\)|\.message\b|\.args\s*\[\s*0\s*\]))";
    add_all(std::regex(text + R"(\s*\.\s*(?:find|rfind|index|startswith|endswith|count)\s*\()"));
    add_all(std::regex(text + R"(\s*[!=]=)"));
    add_all(std::regex(R"(\bin\s+)" + text));
    add_all(std::regex(R"(\bre\s*\.\s*(?:search|match|fullmatch|findall)\s*\([^)]*)" + text));
  }
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  return at;
}

std::vector<Finding> scan(const fs::path& root) {
  std::vector<Finding> out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), root);
    if (rel.begin() != rel.end() && *rel.begin() == "core") continue;  // the error model itself
    const std::string ext = entry.path().extension().string();
    Language language;
    if (ext == ".cpp" || ext == ".hpp" || ext == ".h" || ext == ".cc") language = Language::cpp;
    else if (ext == ".py") language = Language::python;
    else continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    for (std::size_t at : inspections(text, language))
      out.push_back({rel.string(), line_of(text, at), line_text(text, at)});
  }
  return out;
}

std::size_t count_cpp(const std::string& code) { return inspections(code, Language::cpp).size(); }
std::size_t count_py(const std::string& code) { return inspections(code, Language::python).size(); }

// The scanner finds what it is meant to (each line below decided from text in the old code).
TEST(ErrorText, ScannerFlagsDecisionsFromMessageText) {
  EXPECT_EQ(count_cpp(R"(return e.message.rfind("busy", 0) == 0;)"), 1u);
  EXPECT_EQ(count_cpp(R"(bool f = report.error().message.find("following error") != std::string::npos;)"), 1u);
  EXPECT_EQ(count_cpp(R"(if (message.rfind(prefix, 0) != 0) continue;)"), 1u);
  EXPECT_EQ(count_cpp("std::string m = e.message;\nif (m.rfind(prefix, 0) == 0) {}"), 1u);
  EXPECT_EQ(count_cpp("const std::string& text = s.error().message;\nreturn text.starts_with(\"x\");"), 1u);
  EXPECT_EQ(count_cpp(R"(if (std::string(e.what()).find("lost") != std::string::npos) {})"), 1u);
  EXPECT_EQ(count_cpp(R"(if (e.what() == std::string("closed")) {})"), 1u);
  EXPECT_EQ(count_cpp(R"(if (error.message == "busy") {})"), 1u);
  EXPECT_EQ(count_cpp(R"(if ("busy" == error.message) {})"), 1u);
  EXPECT_EQ(count_cpp(R"(if (std::regex_search(e.message, re)) {})"), 1u);
  EXPECT_EQ(count_py(R"(if "busy" in str(e): pass)"), 1u);
  EXPECT_EQ(count_py(R"(if e.message.startswith("busy"): pass)"), 1u);
  EXPECT_EQ(count_py(R"(if re.search("busy", e.args[0]): pass)"), 1u);
}

// ... and leaves building messages alone.
TEST(ErrorText, ScannerLeavesMessageBuildingAlone) {
  EXPECT_EQ(count_cpp(R"(return Error{e.kind, fmt::format("{}: {}", what, e.message)};)"), 0u);
  EXPECT_EQ(count_cpp(R"(return e.prefixed("joint 3: ");)"), 0u);
  EXPECT_EQ(count_cpp(R"(r.fail(path, q.error().message.substr(path.size() + 2));)"), 0u);
  EXPECT_EQ(count_cpp(R"(publish_error(e.what());)"), 0u);
  EXPECT_EQ(count_cpp("// e.message.find(\"busy\") was how it was done\nint x = 0;"), 0u);
  EXPECT_EQ(count_cpp(R"(log("use e.message.find(x) never");)"), 0u);
  EXPECT_EQ(count_cpp(R"(auto at = text.find('\n', pos);)"), 0u);
  EXPECT_EQ(count_py(R"x(raise Error(str(e) + " (while closing)"))x"), 0u);
  EXPECT_EQ(count_py(R"(if e.kind != "timeout": raise)"), 0u);
}

TEST(ErrorText, NoCodeOutsideCoreDecidesFromAnErrorsMessage) {
  const char* other = std::getenv("ARMCTL_ERROR_TEXT_ROOT");
  const fs::path root = other && *other ? fs::path(other) : fs::path(ARMCTL_SOURCE_DIR) / "src";
  ASSERT_TRUE(fs::is_directory(root)) << root;
  const auto findings = scan(root);
  std::string report;
  for (const auto& f : findings) report += "\n  src/" + f.file + ":" + std::to_string(f.line) + ": " + f.code;
  EXPECT_TRUE(findings.empty())
      << findings.size() << " place(s) decide from an error's message text; attach a typed detail at the "
      << "producer and branch on it (docs/architecture.md \"Errors\"):" << report;
}

}  // namespace
