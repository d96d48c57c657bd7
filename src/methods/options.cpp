#include "earc/methods/options.hpp"

#include <stdexcept>
#include <utility>

#include "earc/io/input_error.hpp"

namespace earc {

std::string optionName(const char* key, OptionStyle style) {
  std::string name = key;
  if (style == OptionStyle::Python) return name;
  if (style == OptionStyle::Request) return "$." + name;
  for (char& c : name)
    if (c == '_') c = '-';
  return "--" + name;
}

PlannerSettings plannerSettingsFor(const MethodOptions& o, OptionStyle style) {
  const auto name = [style](const char* key) { return optionName(key, style); };
  const std::string source = style == OptionStyle::Request ? "request" : "";
  PlannerSettings s;
  try {
    s.method = methodFromName(o.method);
  } catch (const std::invalid_argument& e) {
    throw InputError(source, name("method"), e.what());
  }
  s.time_limit_s = o.time_limit;
  s.seed = o.seed;
  s.trace = o.trace;
  if (o.window) s.arc.initial_window = *o.window;
  s.db.learn = o.learn;
  if (o.deterministic && s.method == Method::Lightning)
    throw InputError(source, name("deterministic"), kWorkBudgetsNotForLightning);
  s.work_budgets = o.deterministic;
  s.post.compact = o.compact;
  s.arc.crowd_fallback = o.crowd;
  s.arc.retime_windows = o.retime_windows;
  s.arc.restamp_coupled = o.restamp_coupled;
  s.post.refine_s = o.refine;
  for (const auto& [given, option] :
       {std::pair{o.shadow_decoupled, "shadow_decoupled"}, std::pair{o.db_k.has_value(), "db_k"},
        std::pair{o.db_repair_max.has_value(), "db_repair_max"},
        std::pair{o.db_max_stretch.has_value(), "db_max_stretch"}})
    if (given && s.method != Method::Earc) throw InputError(source, name(option), "is for method earc");
  s.db.shadow_decoupled = o.shadow_decoupled;
  if (o.db_k) s.db.k = *o.db_k;
  if (o.db_max_stretch) s.db.max_stretch = *o.db_max_stretch;
  if (o.db_repair_max) s.db.max_invalid_segments = *o.db_repair_max;
  // Only ARC and E-ARC find conflicts and make subproblems to trace.
  if (o.trace && s.method != Method::Arc && s.method != Method::Earc)
    throw InputError(source, name("trace"), "is for methods arc and earc (the others make no subproblems to trace)");
  // A database the method would not read is a mistake, not a no-op.
  if (!o.db.empty() && s.method != Method::Earc && s.method != Method::Lightning)
    throw InputError(source, name("db"), "is for methods earc and lightning");
  if (s.method == Method::Lightning) s.db.lightning_file = o.db;
  return s;
}

}  // namespace earc
