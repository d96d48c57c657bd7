#include "earc/util/memory_reserve.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace earc {

namespace {
// Enough for nlohmann to free an array of about two million values.
constexpr std::size_t kReserveBytes = std::size_t{32} << 20;
constexpr std::size_t kLeastReserveBytes = std::size_t{1} << 20;
std::atomic<void*> g_reserve{nullptr};

void onOutOfMemory() {
  std::free(g_reserve.exchange(nullptr));
  throw std::bad_alloc();
}
}  // namespace

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
void armMemoryReserve() {
  if (g_reserve.load() == nullptr) {
    // Under a tight limit, as much as there is room for.
    void* block = nullptr;
    for (std::size_t bytes = kReserveBytes; !block && bytes >= kLeastReserveBytes; bytes /= 2)
      block = std::malloc(bytes);
    void* none = nullptr;
    if (block && !g_reserve.compare_exchange_strong(none, block)) std::free(block);
  }
  std::set_new_handler(onOutOfMemory);
}

std::string outOfMemoryMessage(const std::bad_alloc& e, const std::string& doing) {
  if (dynamic_cast<const OutOfMemory*>(&e)) return e.what();
  return outOfMemoryText(doing);
}

std::string outOfMemoryText(const std::string& doing) {
  return "out of memory" + (doing.empty() ? "" : " " + doing) + " (is the memory limit, ulimit -v, too low?)";
}

}  // namespace earc
