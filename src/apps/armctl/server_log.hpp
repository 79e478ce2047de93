// What a long-running command (serve, sim scara, sim xarm, controller) says while it runs:
// as text for a person, or under --json as one JSON line per event on standard output, so
// that a supervisor script reads where to connect, every log line and the final counts
// without parsing prose (README "Machine-readable output").
//   text:  the device path (if any) alone on stdout, everything else on `text_stream`
//   json:  {"event":"started","source":"sim xarm","device":"/dev/pts/3",...}
//          {"event":"log","source":"sim xarm","message":"..."}
//          {"event":"stopped","source":"sim xarm","frames":12,...}
#pragma once

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace armctl::cli {

class ServerLog {
 public:
  // `source` names the server in every line ("sim xarm", "controller"); `text_stream` is
  // where its text goes (stderr for servers whose stdout carries a device path).
  ServerLog(std::string source, bool json, std::FILE* text_stream = stderr)
      : source_(std::move(source)), json_(json), text_(text_stream) {}

  bool json() const { return json_; }
  const std::string& source() const { return source_; }

  // One line of the server's log (quoted frames and file names are made printable).
  void line(const std::string& message) const;
  // The server is up. `fields` go into the JSON line; `text` is what a person reads. A
  // `device_path` (a pty) is printed alone on stdout in text mode, where scripts read it.
  void started(nlohmann::json fields, const std::string& text, const std::string& device_path = {}) const;
  // The server stopped, with its counts.
  void stopped(nlohmann::json fields, const std::string& text) const;

 private:
  void event(const char* name, nlohmann::json fields) const;
  std::string source_;
  bool json_;
  std::FILE* text_;
};

}  // namespace armctl::cli
