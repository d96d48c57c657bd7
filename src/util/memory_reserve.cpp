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
