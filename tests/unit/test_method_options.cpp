// plannerSettingsFor: the checks every front end shares, named in each style.
#include <doctest/doctest.h>

#include "earc/io/input_error.hpp"
#include "earc/methods/options.hpp"

using namespace earc;

TEST_CASE("method options name a refused option as the front end spells it") {
  MethodOptions o;
  o.method = "arc";
  o.db_k = 3;
  CHECK_THROWS_WITH_AS(plannerSettingsFor(o, OptionStyle::Cli), "--db-k: is for method earc", InputError);
  CHECK_THROWS_WITH_AS(plannerSettingsFor(o, OptionStyle::Python), "db_k: is for method earc", InputError);
  try {
    plannerSettingsFor(o, OptionStyle::Request);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.file() == "request");
    CHECK(e.where() == "$.db_k");
  }
  o.method = "earc";
  const PlannerSettings s = plannerSettingsFor(o, OptionStyle::Request);
  CHECK(s.method == Method::Earc);
  CHECK(s.db.k == 3);
  o.method = "lightning";
  o.db_k.reset();
  o.deterministic = true;
  CHECK_THROWS_AS(plannerSettingsFor(o, OptionStyle::Request), InputError);
  o.method = "fast";
  CHECK_THROWS_AS(plannerSettingsFor(o, OptionStyle::Cli), InputError);
}
