// Assembling the viewer page: the HTML template from tools/viewer/ with its
// style, scripts and data put in place of the template's placeholders.
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "earc/io/json_io.hpp"
#include "earc/view/viewer.hpp"

namespace earc::view {
namespace {

template <std::size_t N>
constexpr std::string_view literal(const char (&s)[N]) {
  return {s, N - 1};
}

constexpr Asset kAssets[] = {
#include "viewer_assets.inc"
};

std::string_view asset(std::string_view name) {
  for (const Asset& a : kAssets)
    if (name == a.name) return a.text;
  throw std::logic_error("viewer asset missing from the build: " + std::string(name));
}

// JSON that is safe inside <script type="application/json">: "<" only ever
// occurs inside JSON strings, where \u003c means the same, so no "</script>"
// or "<!--" in a robot's name can end the element early.
std::string scriptSafeJson(const nlohmann::json& data) {
  const std::string text = dumpCompact(data);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

}  // namespace

std::span<const Asset> viewerAssets() { return kAssets; }

std::string viewerHtml(const nlohmann::json& data) {
  struct Slot {
    std::string_view placeholder;
    std::string text;
  };
  std::vector<Slot> slots = {{"/*@EARC_CSS@*/", std::string(asset("viewer.css"))},
                             {"/*@EARC_SELFTEST_JS@*/", std::string(asset("selftest.js"))},
                             {"@EARC_DATA@", scriptSafeJson(data)},
                             {"/*@EARC_VIEWER_JS@*/", std::string(asset("viewer.js"))},
                             {"/*@EARC_VIEWER_DRAW_JS@*/", std::string(asset("viewer_draw.js"))},
                             {"/*@EARC_VIEWER_UI_JS@*/", std::string(asset("viewer_ui.js"))}};
  // One pass over the template in order: text put in never gets searched.
  const std::string_view tpl = asset("viewer.html");
  std::string out;
  std::size_t from = 0;
  for (;;) {
    std::size_t best = std::string_view::npos;
    const Slot* slot = nullptr;
    for (const Slot& s : slots) {
      const std::size_t at = tpl.find(s.placeholder, from);
      if (at < best) best = at, slot = &s;
    }
    if (!slot) break;
    out.append(tpl.substr(from, best - from));
    out += slot->text;
    from = best + slot->placeholder.size();
  }
  out.append(tpl.substr(from));
  return out;
}

}  // namespace earc::view
