#include "files/line_reader.hpp"

#include "core/printable.hpp"

namespace armctl::files {

std::vector<TextField> split_fields(std::string_view line) {
  std::vector<TextField> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) fields.push_back({line.substr(start, i - start), start + 1});
  }
  return fields;
}

std::optional<TextLine> LineReader::next() {
  while (!done_) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view code = text_.substr(pos_, end - pos_);
    ++line_;
    if (end == text_.size()) done_ = true;
    pos_ = end + 1;
    if (auto hash = code.find('#'); hash != std::string_view::npos) code = code.substr(0, hash);
    auto fields = split_fields(code);
    if (!fields.empty()) return TextLine{line_, code, std::move(fields)};
  }
  return std::nullopt;
}

std::string shown(std::string_view text, std::size_t longest) {
  std::string out = printable(text.substr(0, longest));
  if (text.size() > longest) out += "...";
  return out;
}

Error file_error(std::string_view source, std::size_t line, std::size_t column, std::string reason) {
  return source_error(ErrorKind::invalid_config, {printable(source), line, column, std::move(reason)});
}

}  // namespace armctl::files
