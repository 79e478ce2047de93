// Where in a text file an error is: the typed detail every file reader attaches (programs,
// points, paths, recordings, action groups), so that apps place an error (the web editor's
// marks, an IDE's file:line:column) without reading its message. In core because readers in
// several layers (motion's file formats, programs) produce it and apps above all of them
// consume it.
#pragma once

#include <any>
#include <cstddef>
#include <string>
#include <utility>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl {

struct SourcePlace {
  std::string file;        // as the reader was given it ("program.rob", "<program>")
  std::size_t line = 0;    // from 1
  std::size_t column = 0;  // from 1; 0: the line as a whole
  std::string reason;      // the message without its "file:line:column: " prefix
  // The detail of the error found at this place, if it had one (a program line whose move
  // would collide: its arm::CollisionDetail), for apps that draw it (detail_or_cause).
  std::any cause{};
};

// The Error "file:line:column: reason" ("file:line: reason" without a column) with the place
// as its detail.
inline Error source_error(ErrorKind kind, SourcePlace place) {
  std::string message = place.column ? fmt::format("{}:{}:{}: {}", place.file, place.line, place.column, place.reason)
                                     : fmt::format("{}:{}: {}", place.file, place.line, place.reason);
  return Error{kind, std::move(message), std::move(place)};
}

// The SourcePlace behind an error, or nullptr.
inline const SourcePlace* source_place(const Error& error) { return error.detail_as<SourcePlace>(); }

// The error's detail D, or that of the error its SourcePlace was made from; nullptr if neither.
template <class D>
const D* detail_or_cause(const Error& error) {
  if (const D* d = error.detail_as<D>()) return d;
  if (const SourcePlace* at = source_place(error)) return std::any_cast<D>(&at->cause);
  return nullptr;
}

}  // namespace armctl
