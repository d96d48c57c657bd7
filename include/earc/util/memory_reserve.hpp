#pragma once

#include <new>
#include <string>

namespace earc {

// Under an address-space limit (`ulimit -v`, or earc-bench's
// --memory-limit-mb) a failed allocation throws std::bad_alloc, and the
// unwinding that follows frees what was built. nlohmann::json's destructor
// allocates while it frees a large document, so a scenario file too large
// for the limit ended in std::terminate (and a core dump) instead of an
// error line. armMemoryReserve() sets memory aside (address space only:
// it is never touched, so it costs no resident memory) and installs a
// new-handler that gives it back at the first failed allocation and then
// throws: the unwinding has room to run, and the program says what
// happened. Call it again after handling a bad_alloc to keep going
// (earc-plan serve). Safe to call from any thread.
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
