// Bad input is reported as one line naming the file, the JSON path (or
// field) and the reason: "scenario.json: $.robots[2].start[1]: not a finite
// number". Command-line programs print what() and exit with status 2.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace earc {

// "FILE: WHERE: REASON", leaving out what is empty (a command-line option
// has no file: "--window: must be ...").
inline std::string inputMessage(const std::string& file, const std::string& where, const std::string& reason) {
  std::string s = file;
  if (!where.empty()) s += (s.empty() ? "" : ": ") + where;
  return s.empty() ? reason : s + ": " + reason;
}

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string where, std::string reason)
      : std::runtime_error(inputMessage(file, where, reason)),
        file_(std::move(file)), where_(std::move(where)), reason_(std::move(reason)) {}
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, where_, reason_;
};

// Something in an input that is read all the same but is likely a
// mistake (an unknown key, an angle that looks like degrees). Commands
// print each as one line on stderr, "PROGRAM: warning: " and text().
struct InputWarning {
  std::string file, where, reason;
  std::string text() const { return inputMessage(file, where, reason); }
};

// Exit status for bad input in every command-line program.
inline constexpr int kExitBadInput = 2;

}  // namespace earc
