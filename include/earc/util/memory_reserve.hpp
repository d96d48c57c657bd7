#pragma once

#include <new>
#include <string>

namespace earc {

// Sets address space aside and installs a new-handler that gives it back at
// the first failed allocation, then throws std::bad_alloc, so that unwinding
// has room to run. Call again after handling a bad_alloc. Thread-safe.
void armMemoryReserve();

// A bad_alloc that says what ran out of memory ("FILE: out of memory while
// reading its 12.4 MB of JSON"), caught wherever a bad_alloc is.
class OutOfMemory : public std::bad_alloc {
 public:
  explicit OutOfMemory(std::string message) : message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

// The line to print for a caught bad_alloc: an OutOfMemory's own, else
// "out of memory" and `doing` ("while handling the request"), where
// std::bad_alloc's what() says only "std::bad_alloc".
std::string outOfMemoryMessage(const std::bad_alloc& e, const std::string& doing = "");
// "out of memory while reading it (is the memory limit, ulimit -v, too low?)".
std::string outOfMemoryText(const std::string& doing);

}  // namespace earc
