#include "plan_store.hpp"

#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"

namespace earc {

std::shared_ptr<exp::ExperienceStore> openStoreForPlanning(Method method, const std::string& db, bool learn) {
  if (method != Method::Earc) return nullptr;
  if (db.empty()) throw InputError("", "--db", "method earc needs an experience database file (earc-db build makes one; a new file name starts empty)");
  exp::StoreOptions options;
  options.check_in_background = true;
  if (!learn) {
    options.read_only = true;
    options.new_session = false;
  }
  try {
    return std::make_shared<exp::ExperienceStore>(db, options);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // Foreign, newer or damaged files: one line naming the file, nothing written.
    throw InputError(db, "database", exp::withoutFile(e.what(), db));
  }
}

}  // namespace earc
