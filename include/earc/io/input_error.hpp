// Bad input is reported as one line naming the file, the JSON path (or
// field) and the reason: "scenario.json: $.robots[2].start[1]: not a finite
// number". Command-line programs print what() and exit with status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace earc {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string where, std::string reason)
      : std::runtime_error(compose(file, where, reason)),
        file_(std::move(file)), where_(std::move(where)), reason_(std::move(reason)) {}
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string compose(const std::string& f, const std::string& w, const std::string& r) {
    // A command-line option has no file: "--window: must be ...".
    std::string s = f;
    if (!w.empty()) s += (s.empty() ? "" : ": ") + w;
    return s.empty() ? r : s + ": " + r;
  }
  std::string file_, where_, reason_;
};

// Exit status for bad input in every command-line program.
inline constexpr int kExitBadInput = 2;

}  // namespace earc
